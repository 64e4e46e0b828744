// extern "C" layer of pw85_overlap, pw85_contact and the batch calls over
// per-pair arrays and scenes: argument checks, the call into the core, the
// copy of the results into the C structures. The batch loops (threads,
// prefetch, lanes, the periodic box) are in src/core/batch/; each pair is
// computed by the one-pair function, or in a vector lane that gives its
// result bit for bit (docs/batch.md), so results do not depend on the number
// of threads, the position or the neighbours.
#include <cmath>
#include <cstring>

#include "pw85.h"
#include "batch/box.hpp"
#include "batch/lanes.hpp"
#include "batch/pairs.hpp"
#include "batch/schedule.hpp"
#include "contact/contact.hpp"
#include "derivatives/derivatives.hpp"
#include "geometry/contact_geometry.hpp"
#include "overlap/overlap.hpp"
#include "common/sym3.hpp"
#include "validate.hpp"

using pw85::capi::fill_nan;

namespace {

void fill_nan_contact(pw85_contact_t *c) noexcept {
  fill_nan(&c->mu2, 1);
  fill_nan(&c->lambda, 1);
  fill_nan(c->x0, 3);
  fill_nan(c->n, 3);
  fill_nan(&c->dca, 1);
  fill_nan(&c->depth, 1);
  fill_nan(&c->depth_n, 1);
}

// pw85_overlap off its hot path: full argument check (L D L^T pivots instead
// of a Cholesky factorisation, docs/overlap.md (O9)), then scaling if needed.
// Kept out of line so that the screening pass compiles without spills.
__attribute__((noinline)) int overlap_general(double const *r12, double const *q1,
                                              double const *q2) noexcept {
  int const status = pw85::capi::validate_pair(r12, q1, q2);
  if (status != PW85_OK) return status;
  int verdict = -1;
  int const s = pw85::overlap(pw85::load_vec3(r12), pw85::load_sym3(q1),
                              pw85::load_sym3(q2), verdict);
  return s == PW85_OK ? verdict : s;
}

}  // namespace

extern "C" {

int pw85_overlap(double const r12[PW85_DIM], double const q1[PW85_SYM],
                 double const q2[PW85_SYM]) {
  if (r12 == nullptr || q1 == nullptr || q2 == nullptr) return PW85_ERR_INVALID_ARGUMENT;
  // Hot path: one screening pass (finite, L D L^T pivots, safe range), then
  // the filters with no scaling. Anything else takes the general path.
  int verdict = -1;
  pw85::Status s = pw85::kOk;
  if (pw85::overlap_screened(r12, q1, q2, verdict, s)) return s == pw85::kOk ? verdict : s;
  return overlap_general(r12, q1, q2);
}

int pw85_contact(double const r12[PW85_DIM], double const q1[PW85_SYM],
                 double const q2[PW85_SYM], pw85_contact_t *c) {
  if (c == nullptr) return PW85_ERR_INVALID_ARGUMENT;
  int const status = pw85::capi::validate_pair(r12, q1, q2);
  if (status != PW85_OK) {
    fill_nan_contact(c);
    return status;
  }
  if (r12[0] == 0.0 && r12[1] == 0.0 && r12[2] == 0.0) {
    fill_nan_contact(c);
    return PW85_ERR_INVALID_ARGUMENT;
  }
  pw85::ContactGeometry g;
  int const s = pw85::contact_geometry(pw85::load_vec3(r12), pw85::load_sym3(q1),
                                       pw85::load_sym3(q2), g);
  if (s != PW85_OK && s != PW85_ERR_NO_CONVERGENCE && s != PW85_ERR_INACCURATE &&
      s != PW85_ERR_RANGE) {
    fill_nan_contact(c);
    return s;
  }
  c->mu2 = g.mu2;
  c->lambda = g.lambda;
  for (int d = 0; d < 3; ++d) {
    c->x0[d] = g.x0[d];
    c->n[d] = g.n[d];
  }
  c->dca = g.dca;
  c->depth = g.depth;
  c->depth_n = g.depth_n;
  return s;
}

}  // extern "C"

namespace {

void fill_nan_result(pw85_result *res, int method) noexcept {
  fill_nan(&res->mu2, 1);
  fill_nan(&res->lambda, 1);
  fill_nan(&res->mu2_error, 1);
  res->iterations = 0;
  res->method = method;
}

// The copy of DEFAULT's lanes for pairs k0 ... k0 + kDefaultLanes - 1
// (batch::default_lanes_of) into res, the undecided lanes by the one-pair
// call; st[l]: the status of pair k0 + l.
template <class Pair>
void default_block(long long k0, Pair const &pair, pw85_result *res, int st[]) noexcept {
  pw85::batch::DefaultLanes dl;
  pw85::batch::default_lanes_of(k0, pair, dl);
  for (int l = 0; l < pw85::batch::DefaultLanes::w; ++l) {
    pw85_result &o = res[k0 + l];
    if (!dl.ok[l]) {
      fill_nan_result(&o, PW85_METHOD_DEFAULT);
      st[l] = PW85_ERR_INVALID_ARGUMENT;
    } else if (dl.status[l] != pw85::kLaneUndecided) {
      o.mu2 = dl.res[l].mu2;
      o.lambda = dl.res[l].lambda;
      o.mu2_error = dl.res[l].mu2_error;
      o.iterations = dl.res[l].iterations;
      o.method = dl.res[l].method;
      st[l] = dl.status[l];
    } else {
      st[l] = pw85_contact_function_method(dl.r[l], dl.q1[l], dl.q2[l], PW85_METHOD_DEFAULT, &o);
    }
  }
}

// The same for pw85_contact_derivatives_ex (batch::lane_derivatives, else
// the one-pair call).
template <class Pair>
void derivatives_block(long long k0, Pair const &pair, unsigned flags, pw85_derivatives_t *d,
                       int st[]) noexcept {
  pw85::DerivativeFields fields = pw85::DerivativeFields::kAll;
  pw85::capi::derivative_fields(flags, fields);  // checked by the caller
  pw85::batch::DefaultLanes dl;
  pw85::batch::default_lanes_of(k0, pair, dl);
  for (int l = 0; l < pw85::batch::DefaultLanes::w; ++l) {
    pw85_derivatives_t &o = d[k0 + l];
    pw85::Derivatives out;
    if (!dl.ok[l]) {
      fill_nan(&o.mu2, 29);
      st[l] = PW85_ERR_INVALID_ARGUMENT;
    } else if (pw85::batch::lane_derivatives(dl, l, fields, out, st[l])) {
      std::memcpy(&o, &out, sizeof out);
    } else {
      st[l] = pw85_contact_derivatives_ex(dl.r[l], dl.q1[l], dl.q2[l], flags, &o);
    }
  }
}

// The checks shared by the calls of m > 0 pairs (pointers checked by the
// caller).
inline bool valid_count(long long m, int nthreads) noexcept { return m > 0 && nthreads >= 0; }

inline bool scene_args(long long n, double const *centres, double const *q, double const *box,
                       long long m, long long const *pairs, void const *out, int nthreads,
                       pw85::batch::Box &b) noexcept {
  return n >= 0 && valid_count(m, nthreads) && centres != nullptr && q != nullptr &&
         pairs != nullptr && out != nullptr && pw85::batch::make_box(box, b);
}

// pw85_overlap as the lanes' one-pair call.
struct OverlapOnePair {
  int operator()(double const *r, double const *a, double const *b) const noexcept {
    return pw85_overlap(r, a, b);
  }
};

}  // namespace

extern "C" {

int pw85_overlap_pairs(long long m, double const *r12, double const *q1, double const *q2,
                       int *overlap, int *status, int nthreads) {
  if (m == 0) return PW85_OK;
  if (!valid_count(m, nthreads) || r12 == nullptr || q1 == nullptr || q2 == nullptr ||
      overlap == nullptr)
    return PW85_ERR_INVALID_ARGUMENT;
  auto one = [&](long long k) noexcept {
    int const res = pw85_overlap(r12 + 3 * k, q1 + 6 * k, q2 + 6 * k);
    overlap[k] = res;
    return res < 0 ? res : PW85_OK;
  };
  return pw85::batch::run_overlap(m, status, nthreads,
                                  pw85::batch::PrefetchedArrayPair{m, r12, q1, q2},
                                  OverlapOnePair{}, overlap, one);
}

int pw85_contact_function_pairs(long long m, double const *r12, double const *q1,
                                double const *q2, int method, pw85_result *res, int *status,
                                int nthreads) {
  if (m == 0) return PW85_OK;
  if (!valid_count(m, nthreads) || r12 == nullptr || q1 == nullptr || q2 == nullptr ||
      res == nullptr)
    return PW85_ERR_INVALID_ARGUMENT;
  if (!pw85::is_method(method)) return PW85_ERR_UNKNOWN_METHOD;
  auto one = [&](long long k) noexcept {
    return pw85_contact_function_method(r12 + 3 * k, q1 + 6 * k, q2 + 6 * k, method, res + k);
  };
  if (method != PW85_METHOD_DEFAULT)
    return pw85::batch::run_pairs(m, status, nthreads, pw85::batch::kPairChunk, one);
  auto block = [&](long long k0, int st[]) noexcept {
    default_block(k0, pw85::batch::ArrayPair{r12, q1, q2}, res, st);
  };
  return pw85::batch::run_default(m, status, nthreads, block, one);
}

int pw85_contact_pairs(long long m, double const *r12, double const *q1, double const *q2,
                       pw85_contact_t *c, int *status, int nthreads) {
  if (m == 0) return PW85_OK;
  if (!valid_count(m, nthreads) || r12 == nullptr || q1 == nullptr || q2 == nullptr ||
      c == nullptr)
    return PW85_ERR_INVALID_ARGUMENT;
  return pw85::batch::run_pairs(m, status, nthreads, pw85::batch::kPairChunk,
                                [&](long long k) noexcept {
                                  return pw85_contact(r12 + 3 * k, q1 + 6 * k, q2 + 6 * k, c + k);
                                });
}

int pw85_contact_derivatives_pairs_ex(long long m, double const *r12, double const *q1,
                                      double const *q2, unsigned flags, pw85_derivatives_t *d,
                                      int *status, int nthreads) {
  if (m == 0) return PW85_OK;
  pw85::DerivativeFields fields = pw85::DerivativeFields::kAll;
  if (!valid_count(m, nthreads) || r12 == nullptr || q1 == nullptr || q2 == nullptr ||
      d == nullptr || !pw85::capi::derivative_fields(flags, fields))
    return PW85_ERR_INVALID_ARGUMENT;
  auto one = [&](long long k) noexcept {
    return pw85_contact_derivatives_ex(r12 + 3 * k, q1 + 6 * k, q2 + 6 * k, flags, d + k);
  };
  auto block = [&](long long k0, int st[]) noexcept {
    derivatives_block(k0, pw85::batch::ArrayPair{r12, q1, q2}, flags, d, st);
  };
  return pw85::batch::run_default(m, status, nthreads, block, one);
}

int pw85_contact_derivatives_pairs(long long m, double const *r12, double const *q1,
                                   double const *q2, pw85_derivatives_t *d, int *status,
                                   int nthreads) {
  return pw85_contact_derivatives_pairs_ex(m, r12, q1, q2, PW85_DERIVATIVES_ALL, d, status,
                                           nthreads);
}

int pw85_contact_time_pairs(long long m, double const *r12, double const *v12, double const *q1,
                            double const *w1, double const *q2, double const *w2, double t_max,
                            double *t, int *status, int nthreads) {
  if (m == 0) return PW85_OK;
  if (!valid_count(m, nthreads) || r12 == nullptr || v12 == nullptr || q1 == nullptr ||
      w1 == nullptr || q2 == nullptr || w2 == nullptr || t == nullptr ||
      !std::isfinite(t_max) || !(t_max > 0.0))
    return PW85_ERR_INVALID_ARGUMENT;
  return pw85::batch::run_pairs(m, status, nthreads, pw85::batch::kContactTimeChunk,
                                [&](long long k) noexcept {
                                  return pw85_contact_time(r12 + 3 * k, v12 + 3 * k, q1 + 6 * k,
                                                           w1 + 3 * k, q2 + 6 * k, w2 + 3 * k,
                                                           t_max, t + k);
                                });
}

int pw85_scene_overlap(long long n, double const *centres, double const *q,
                       double const box[6], long long m, long long const *pairs, int *overlap,
                       int *status, int nthreads) {
  if (m == 0) return PW85_OK;
  pw85::batch::Box b;
  if (!scene_args(n, centres, q, box, m, pairs, overlap, nthreads, b))
    return PW85_ERR_INVALID_ARGUMENT;
  pw85::batch::Scene const s{n, centres, q, b, pairs, m};
  auto one = [&](long long k) noexcept {
    double r12[3];
    long long i, j;
    int const st = pw85::batch::scene_r12(s, k, r12, i, j);
    int const res = st == PW85_OK ? pw85_overlap(r12, q + 6 * i, q + 6 * j) : st;
    overlap[k] = res;
    return res < 0 ? res : PW85_OK;
  };
  return pw85::batch::run_overlap(m, status, nthreads, pw85::batch::ScenePair{s},
                                  OverlapOnePair{}, overlap, one);
}

int pw85_scene_contact_function(long long n, double const *centres, double const *q,
                                double const box[6], long long m, long long const *pairs,
                                int method, pw85_result *res, int *status, int nthreads) {
  if (m == 0) return PW85_OK;
  pw85::batch::Box b;
  if (!scene_args(n, centres, q, box, m, pairs, res, nthreads, b))
    return PW85_ERR_INVALID_ARGUMENT;
  if (!pw85::is_method(method)) return PW85_ERR_UNKNOWN_METHOD;
  pw85::batch::Scene const s{n, centres, q, b, pairs, m};
  auto one_r12 = [&](long long k, double const *r12, long long i, long long j) noexcept {
    if (r12) return pw85_contact_function_method(r12, q + 6 * i, q + 6 * j, method, res + k);
    fill_nan_result(res + k, method);
    return int{PW85_ERR_INVALID_ARGUMENT};
  };
  if (method != PW85_METHOD_DEFAULT)
    return pw85::batch::run_scene(s, status, nthreads, pw85::batch::kPairChunk, one_r12);
  auto one = [&](long long k) noexcept { return pw85::batch::scene_one(s, k, one_r12); };
  auto block = [&](long long k0, int st[]) noexcept {
    default_block(k0, pw85::batch::ScenePair{s}, res, st);
  };
  return pw85::batch::run_default(m, status, nthreads, block, one);
}

int pw85_scene_contact(long long n, double const *centres, double const *q, double const box[6],
                       long long m, long long const *pairs, pw85_contact_t *c, int *status,
                       int nthreads) {
  if (m == 0) return PW85_OK;
  pw85::batch::Box b;
  if (!scene_args(n, centres, q, box, m, pairs, c, nthreads, b))
    return PW85_ERR_INVALID_ARGUMENT;
  pw85::batch::Scene const s{n, centres, q, b, pairs, m};
  return pw85::batch::run_scene(
      s, status, nthreads, pw85::batch::kPairChunk,
      [&](long long k, double const *r12, long long i, long long j) noexcept {
        if (r12) return pw85_contact(r12, q + 6 * i, q + 6 * j, c + k);
        fill_nan_contact(c + k);
        return int{PW85_ERR_INVALID_ARGUMENT};
      });
}

int pw85_scene_contact_derivatives_ex(long long n, double const *centres, double const *q,
                                      double const box[6], long long m, long long const *pairs,
                                      unsigned flags, pw85_derivatives_t *d, int *status,
                                      int nthreads) {
  if (m == 0) return PW85_OK;
  pw85::batch::Box b;
  pw85::DerivativeFields fields = pw85::DerivativeFields::kAll;
  if (!scene_args(n, centres, q, box, m, pairs, d, nthreads, b) ||
      !pw85::capi::derivative_fields(flags, fields))
    return PW85_ERR_INVALID_ARGUMENT;
  pw85::batch::Scene const s{n, centres, q, b, pairs, m};
  auto one_r12 = [&](long long k, double const *r12, long long i, long long j) noexcept {
    if (r12) return pw85_contact_derivatives_ex(r12, q + 6 * i, q + 6 * j, flags, d + k);
    fill_nan(&d[k].mu2, 29);
    return int{PW85_ERR_INVALID_ARGUMENT};
  };
  auto one = [&](long long k) noexcept { return pw85::batch::scene_one(s, k, one_r12); };
  auto block = [&](long long k0, int st[]) noexcept {
    derivatives_block(k0, pw85::batch::ScenePair{s}, flags, d, st);
  };
  return pw85::batch::run_default(m, status, nthreads, block, one);
}

int pw85_scene_contact_derivatives(long long n, double const *centres, double const *q,
                                   double const box[6], long long m, long long const *pairs,
                                   pw85_derivatives_t *d, int *status, int nthreads) {
  return pw85_scene_contact_derivatives_ex(n, centres, q, box, m, pairs, PW85_DERIVATIVES_ALL, d,
                                           status, nthreads);
}

// The older index-pair calls: the scene calls without a box (one line each),
// and pw85_contact_function's Brent iteration over the pairs of a scene.

int pw85_overlap_batch(long long n, double const *centres, double const *q, long long m,
                       long long const *pairs, int *overlap, int *status, int nthreads) {
  return pw85_scene_overlap(n, centres, q, nullptr, m, pairs, overlap, status, nthreads);
}

int pw85_contact_batch(long long n, double const *centres, double const *q, long long m,
                       long long const *pairs, pw85_contact_t *c, int *status, int nthreads) {
  return pw85_scene_contact(n, centres, q, nullptr, m, pairs, c, status, nthreads);
}

int pw85_contact_function_batch(long long n, double const *centres, double const *q,
                                long long m, long long const *pairs, double *out, int *status,
                                int nthreads) {
  if (m == 0) return PW85_OK;
  pw85::batch::Box b;
  if (!scene_args(n, centres, q, nullptr, m, pairs, out, nthreads, b))
    return PW85_ERR_INVALID_ARGUMENT;
  pw85::batch::Scene const s{n, centres, q, b, pairs, m};
  return pw85::batch::run_scene(
      s, status, nthreads, pw85::batch::kPairChunk,
      [&](long long k, double const *r12, long long i, long long j) noexcept {
        if (r12) return pw85_contact_function(r12, q + 6 * i, q + 6 * j, out + 2 * k);
        fill_nan(out + 2 * k, 2);
        return int{PW85_ERR_INVALID_ARGUMENT};
      });
}

}  // extern "C"
