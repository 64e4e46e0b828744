// The fuzz target's checks of the calls over many pairs and over time
// (fuzz_pw85.cpp decodes the input and runs the one-pair checks): the pairs
// calls (pw85_*_pairs), the scene calls (pw85_scene_*, with and without a
// periodic box), the configuration object (pw85_configuration_*), the
// derivatives (one pair, pairs, scene) and the contact time. Each pair of a
// batch must give the bits and status of its one-pair call, the call
// errors must leave every output as it was, and the periodic image must be
// the one of pw85.h's wrap.
#include <cmath>
#include <cstring>

#include "fuzz_checks.hpp"
#include "pw85.h"

namespace fuzz {
namespace {

// A value no call writes: the outputs of a call error must keep it.
constexpr unsigned char kFill = 0xA5;
template <class T>
void fill(T *p, std::size_t n) {
  std::memset(static_cast<void *>(p), kFill, n * sizeof(T));
}
template <class T>
bool untouched(T const *p, std::size_t n) {
  unsigned char const *c = reinterpret_cast<unsigned char const *>(p);
  for (std::size_t i = 0; i < n * sizeof(T); ++i)
    if (c[i] != kFill) return false;
  return true;
}

// The return value of a pairs or scene call: PW85_OK, or the status of the
// lowest failing pair.
int first_failure(int const *status, int m) {
  for (int k = 0; k < m; ++k)
    if (status[k] != PW85_OK) return status[k];
  return PW85_OK;
}

constexpr int kDerivativeFields = sizeof(pw85_derivatives_t) / sizeof(double);
constexpr int kContactFields = sizeof(pw85_contact_t) / sizeof(double);

bool is_zero(double const *r) { return r[0] == 0.0 && r[1] == 0.0 && r[2] == 0.0; }

// The two pairs of the per-pair arrays: (r, q1, q2) and its swap (-r, q2, q1).
struct TwoPairs {
  double r12[6], q1[12], q2[12];
  explicit TwoPairs(Input const &in) {
    for (int i = 0; i < 3; ++i) {
      r12[i] = in.r[i];
      r12[3 + i] = 0.0 - in.r[i];
    }
    std::memcpy(q1, in.q1, 48);
    std::memcpy(q1 + 6, in.q2, 48);
    std::memcpy(q2, in.q2, 48);
    std::memcpy(q2 + 6, in.q1, 48);
  }
};

// A box the scene calls accept (pw85.h): lengths finite and > 0, tilts
// finite, each tilt times its length finite.
bool box_valid(double const *b) {
  for (int i = 0; i < 3; ++i)
    if (!(b[i] > 0.0) || !std::isfinite(b[i])) return false;
  for (int i = 3; i < 6; ++i)
    if (!std::isfinite(b[i])) return false;
  return std::isfinite(b[3] * b[1]) && std::isfinite(b[4] * b[2]) && std::isfinite(b[5] * b[2]);
}

// Radius of the bounding sphere of pw85.h's scene calls: the square root of
// the smaller of the trace and the largest Gershgorin row sum of |Q|.
double bounding_radius(double const *q) {
  double const a = std::fabs(q[0]), b = std::fabs(q[1]), c = std::fabs(q[2]),
               d = std::fabs(q[3]), e = std::fabs(q[4]), f = std::fabs(q[5]);
  double const rows = std::fmax(a + b + c, std::fmax(b + d + e, c + e + f));
  return std::sqrt(std::fmin(q[0] + q[3] + q[5], rows));
}

}  // namespace

void check_pairs(Input const &in) {
  TwoPairs const p(in);
  int const m = 2;
  {
    char const *fn = "pw85_overlap_pairs";
    int ov[2], st[2];
    int const s = pw85_overlap_pairs(m, p.r12, p.q1, p.q2, ov, st, 2);
    for (int k = 0; k < m; ++k) {
      int const one = pw85_overlap(p.r12 + 3 * k, p.q1 + 6 * k, p.q2 + 6 * k);
      CHECK(kBatch, ov[k] == one && st[k] == (one < 0 ? one : PW85_OK), fn, one);
    }
    CHECK(kStatus, s == first_failure(st, m), fn, s);
    fill(ov, 2);
    fill(st, 2);
    CHECK(kUntouched, pw85_overlap_pairs(-1, p.r12, p.q1, p.q2, ov, st, 1) ==
                          PW85_ERR_INVALID_ARGUMENT && untouched(ov, 2) && untouched(st, 2),
          fn, 0);
    CHECK(kUntouched, pw85_overlap_pairs(m, p.r12, p.q1, p.q2, ov, st, -1) ==
                          PW85_ERR_INVALID_ARGUMENT && untouched(ov, 2) && untouched(st, 2),
          fn, 0);
  }
  {
    char const *fn = "pw85_contact_function_pairs";
    current_method = in.method;
    pw85_result res[2], one;
    int st[2];
    fill(res, 2);
    fill(st, 2);
    int const s = pw85_contact_function_pairs(m, p.r12, p.q1, p.q2, in.method, res, st, 1);
    if (in.method < PW85_METHOD_DEFAULT || in.method > PW85_METHOD_ZHENG) {
      CHECK(kUntouched, s == PW85_ERR_UNKNOWN_METHOD && untouched(res, 2) && untouched(st, 2),
            fn, s);
    } else {
      for (int k = 0; k < m; ++k) {
        int const so = pw85_contact_function_method(p.r12 + 3 * k, p.q1 + 6 * k, p.q2 + 6 * k,
                                                    in.method, &one);
        CHECK(kBatch, st[k] == so && same_bits(&res[k], &one, sizeof one), fn, so);
      }
      CHECK(kStatus, s == first_failure(st, m), fn, s);
    }
    current_method = -1;
  }
  {
    char const *fn = "pw85_contact_pairs";
    pw85_contact_t c[2], one;
    int st[2];
    int const s = pw85_contact_pairs(m, p.r12, p.q1, p.q2, c, st, 1);
    for (int k = 0; k < m; ++k) {
      int const so = pw85_contact(p.r12 + 3 * k, p.q1 + 6 * k, p.q2 + 6 * k, &one);
      CHECK(kBatch, st[k] == so && same_bits(&c[k], &one, sizeof one), fn, so);
    }
    CHECK(kStatus, s == first_failure(st, m), fn, s);
    fill(c, 2);
    CHECK(kUntouched, pw85_contact_pairs(m, p.r12, p.q1, nullptr, c, nullptr, 1) ==
                          PW85_ERR_INVALID_ARGUMENT && untouched(c, 2),
          fn, 0);
  }
  {
    char const *fn = "pw85_contact_derivatives_pairs";
    pw85_derivatives_t d[2], one;
    int st[2];
    int const s = pw85_contact_derivatives_pairs(m, p.r12, p.q1, p.q2, d, st, 1);
    for (int k = 0; k < m; ++k) {
      int const so = pw85_contact_derivatives(p.r12 + 3 * k, p.q1 + 6 * k, p.q2 + 6 * k, &one);
      CHECK(kBatch, st[k] == so && same_bits(&d[k], &one, sizeof one), fn, so);
    }
    CHECK(kStatus, s == first_failure(st, m), fn, s);
    fill(d, 2);
    fill(st, 2);
    CHECK(kUntouched, pw85_contact_derivatives_pairs(-1, p.r12, p.q1, p.q2, d, st, 1) ==
                          PW85_ERR_INVALID_ARGUMENT && untouched(d, 2) && untouched(st, 2),
          fn, 0);
  }
}

// The scene {0, r} (q1, q2) with pairs (0, 1), (1, 0) and (0, 2), the last
// with an index out of range; with or without the input's box.
void check_scene(Input const &in) {
  double const centres[6] = {0.0, 0.0, 0.0, in.r[0], in.r[1], in.r[2]};
  double q[12];
  std::memcpy(q, in.q1, 48);
  std::memcpy(q + 6, in.q2, 48);
  long long const pairs[6] = {0, 1, 1, 0, 0, 2};
  int const m = 3;
  double const *box = in.has_box ? in.box : nullptr;
  bool const valid = box == nullptr || box_valid(box);

  // The image r12 of pairs 0 and 1 that pw85.h's wrap gives, where this
  // check knows it exactly: without a box, r and -r; with one, when the
  // wrap moves along a1 only (no tilt, or r = (x, 0, 0)), the IEEE
  // remainder of each component (exact; nearest count, the header's ties
  // away from zero are not IEEE's ties to even: a relative 2^-46 about a
  // tie is left out, where the header allows either count).
  double image[2][3];
  bool known = valid;
  for (int i = 0; i < 3; ++i) {
    image[0][i] = in.r[i];
    image[1][i] = 0.0 - in.r[i];
  }
  if (box && valid) {
    bool const untilted = box[3] == 0.0 && box[4] == 0.0 && box[5] == 0.0;
    known = known && (untilted || (in.r[1] == 0.0 && in.r[2] == 0.0)) && all_finite(in.r, 3);
    for (int i = 0; i < 3 && known; ++i) {
      for (int k = 0; k < 2; ++k) {
        double const x = std::remainder(image[k][i], box[i]);
        if (std::fabs(std::fabs(x) - 0.5 * box[i]) <= 0x1p-46 * box[i]) known = false;
        // the exact zero keeps the sign of c_j - c_i's component
        image[k][i] = x == 0.0 ? 0.0 * image[k][i] : x;
      }
    }
  }
  // Whether the pairs of the scene fall under the bounding-sphere bound.
  // Not refused is required only without tilt: a tilted box also refuses
  // a pair whose wrap needs more than 2^50 lattice vectors along a2 or a3
  // (pw85.h), which the tilts can make of any centre difference.
  int bound = -1;  // 1: must be refused, 0: must not be refused, -1: either
  if (box && valid && all_finite(in.q1, 6) && all_finite(in.q2, 6) && all_finite(in.r, 3) &&
      spd_expected == 0) {
    double const sum = bounding_radius(in.q1) + bounding_radius(in.q2);
    double const half = 0.5 * std::fmin(box[0], std::fmin(box[1], box[2]));
    bool const untilted = box[3] == 0.0 && box[4] == 0.0 && box[5] == 0.0;
    if (sum < 0.99 * half && untilted) bound = 0;
    if (sum > 1.01 * half) bound = 1;
  }

  {
    char const *fn = "pw85_scene_overlap";
    int ov[3], st[3];
    fill(ov, 3);
    fill(st, 3);
    int const s = pw85_scene_overlap(2, centres, q, box, m, pairs, ov, st, 1);
    record(fn, s);
    if (!valid) {
      CHECK(kUntouched, s == PW85_ERR_INVALID_ARGUMENT && untouched(ov, 3) && untouched(st, 3),
            fn, s);
      return;
    }
    CHECK(kStatus, s == first_failure(st, m) && st[2] == PW85_ERR_INVALID_ARGUMENT &&
                       ov[2] == PW85_ERR_INVALID_ARGUMENT, fn, s);
    for (int k = 0; k < 2; ++k) {
      record(fn, ov[k]);
      CHECK(kStatus, st[k] == (ov[k] < 0 ? ov[k] : PW85_OK), fn, ov[k]);
      if (bound == 1) CHECK(kImage, ov[k] == PW85_ERR_INVALID_ARGUMENT, fn, ov[k]);
      if (bound == 0) CHECK(kImage, ov[k] != PW85_ERR_INVALID_ARGUMENT, fn, ov[k]);
      if (known && ov[k] != PW85_ERR_INVALID_ARGUMENT) {
        int const one = k ? pw85_overlap(image[1], in.q2, in.q1)
                          : pw85_overlap(image[0], in.q1, in.q2);
        CHECK(box ? kImage : kBatch, ov[k] == one, fn, ov[k]);
      }
    }
    // Both orders of the pair, decided: the same verdict (for a periodic
    // pair that overlaps in some image both give the nearest image).
    if (ov[0] >= 0 && ov[1] >= 0) CHECK(kSwap, ov[0] == ov[1], fn, ov[0]);
  }
  {
    char const *fn = "pw85_scene_contact_function";
    current_method = in.method;
    pw85_result res[3], one;
    int st[3];
    fill(res, 3);
    fill(st, 3);
    int const s = pw85_scene_contact_function(2, centres, q, box, m, pairs, in.method, res, st, 1);
    record(fn, s);
    if (in.method < PW85_METHOD_DEFAULT || in.method > PW85_METHOD_ZHENG) {
      CHECK(kUntouched, s == PW85_ERR_UNKNOWN_METHOD && untouched(res, 3) && untouched(st, 3),
            fn, s);
    } else {
      CHECK(kStatus, s == first_failure(st, m) && st[2] == PW85_ERR_INVALID_ARGUMENT &&
                         std::isnan(res[2].mu2), fn, s);
      for (int k = 0; k < 2; ++k) {
        record(fn, st[k]);
        if (!known || st[k] == PW85_ERR_INVALID_ARGUMENT) continue;
        int const so = k ? pw85_contact_function_method(image[1], in.q2, in.q1, in.method, &one)
                         : pw85_contact_function_method(image[0], in.q1, in.q2, in.method, &one);
        CHECK(box ? kImage : kBatch, st[k] == so && same_bits(&res[k], &one, sizeof one), fn, so);
      }
    }
    current_method = -1;
  }
  {
    char const *fn = "pw85_scene_contact";
    pw85_contact_t c[3], one;
    int st[3];
    int const s = pw85_scene_contact(2, centres, q, box, m, pairs, c, st, 1);
    record(fn, s);
    CHECK(kStatus, s == first_failure(st, m) && st[2] == PW85_ERR_INVALID_ARGUMENT &&
                       all_nan(&c[2].mu2, kContactFields), fn, s);
    for (int k = 0; k < 2; ++k) {
      record(fn, st[k]);
      if (st[k] == PW85_ERR_INVALID_ARGUMENT && box)
        CHECK(kNan, all_nan(&c[k].mu2, kContactFields), fn, st[k]);
      if (!known || st[k] == PW85_ERR_INVALID_ARGUMENT) continue;
      int const so = k ? pw85_contact(image[1], in.q2, in.q1, &one)
                       : pw85_contact(image[0], in.q1, in.q2, &one);
      CHECK(box ? kImage : kBatch, st[k] == so && same_bits(&c[k], &one, sizeof one), fn, so);
    }
    fill(c, 3);
    CHECK(kUntouched, pw85_scene_contact(-1, centres, q, box, m, pairs, c, nullptr, 1) ==
                          PW85_ERR_INVALID_ARGUMENT && untouched(c, 3),
          fn, 0);
  }
  {
    char const *fn = "pw85_scene_contact_derivatives";
    pw85_derivatives_t d[3], one;
    int st[3];
    int const s = pw85_scene_contact_derivatives(2, centres, q, box, m, pairs, d, st, 1);
    record(fn, s);
    CHECK(kStatus, s == first_failure(st, m) && st[2] == PW85_ERR_INVALID_ARGUMENT &&
                       all_nan(&d[2].mu2, kDerivativeFields), fn, s);
    for (int k = 0; k < 2; ++k) {
      record(fn, st[k]);
      if (!known || st[k] == PW85_ERR_INVALID_ARGUMENT) continue;
      int const so = k ? pw85_contact_derivatives(image[1], in.q2, in.q1, &one)
                       : pw85_contact_derivatives(image[0], in.q1, in.q2, &one);
      CHECK(box ? kImage : kBatch, st[k] == so && same_bits(&d[k], &one, sizeof one), fn, so);
    }
  }
}

void check_configuration(Input const &in) {
  char const *fn = "pw85_configuration_create";
  double const centres[6] = {0.0, 0.0, 0.0, in.r[0], in.r[1], in.r[2]};
  double q[12];
  std::memcpy(q, in.q1, 48);
  std::memcpy(q + 6, in.q2, 48);
  double const *box = in.has_box ? in.box : nullptr;
  static int sentinel_object;
  pw85_configuration *const sentinel = reinterpret_cast<pw85_configuration *>(&sentinel_object);
  pw85_configuration *cfg = sentinel;
  long long bad = -7;
  int const s = pw85_configuration_create(2, centres, q, box, &cfg, &bad);
  record(fn, s);
  CHECK(kStatus, in_list(s, {PW85_OK, PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD,
                             PW85_ERR_RANGE, PW85_ERR_NO_MEMORY}), fn, s);
  CHECK(kStatus, bad >= -1 && bad <= 1, fn, s);
  if (s == PW85_OK) CHECK(kSpd, spd_expected != 1, fn, s);
  if (s == PW85_ERR_NOT_SPD) CHECK(kSpd, spd_expected != 0 && bad >= 0, fn, s);
  if (s != PW85_OK) {
    CHECK(kUntouched, cfg == sentinel, fn, s);
    return;
  }
  CHECK(kStatus, cfg != sentinel && cfg != nullptr && pw85_configuration_size(cfg) == 2, fn, s);

  // The verdict of the pair (0, 1) by the scene call, which the
  // configuration must reproduce (pw85.h).
  long long const pair[2] = {0, 1};
  int verdict, st;
  pw85_scene_overlap(2, centres, q, box, 1, pair, &verdict, &st, 1);
  pw85_result res;
  int const mu2_status = pw85_scene_contact_function(2, centres, q, box, 1, pair,
                                                     PW85_METHOD_DEFAULT, &res, &st, 1);

  fn = "pw85_configuration_pairs";
  long long count = -7, ex[2];
  int sp = pw85_configuration_pairs(cfg, 1.0, 1, 0, nullptr, nullptr, nullptr, &count, ex);
  record(fn, sp);
  CHECK(kStatus, in_list(sp, {PW85_OK, PW85_ERR_CAPACITY, PW85_ERR_NOT_SPD, PW85_ERR_INACCURATE,
                              PW85_ERR_NO_MEMORY}), fn, sp);
  long long i[2], j[2];
  double mu2[2];
  fill(i, 2);
  long long count1 = -7;
  sp = pw85_configuration_pairs(cfg, 1.0, 1, 2, i, j, mu2, &count1, ex);
  record(fn, sp);
  if (sp == PW85_OK) {
    record(fn, count1);
    CHECK(kStatus, count1 == 0 || count1 == 1, fn, sp);
    if (verdict >= 0) CHECK(kBatch, count1 == verdict, fn, verdict);
    if (count1 == 1) {
      CHECK(kStatus, i[0] == 0 && j[0] == 1, fn, sp);
      if (mu2_status == PW85_OK) CHECK(kBatch, same_bits(&mu2[0], &res.mu2, 8), fn, sp);
    }
  } else {
    CHECK(kUntouched, count1 == -7 && untouched(i, 2), fn, sp);
    if (verdict < 0 && verdict != PW85_ERR_INVALID_ARGUMENT) CHECK(kBatch, sp == verdict, fn, sp);
  }
  // Scaled pairs: s < 1 or not finite is a call error, nothing written;
  // the pairs within s >= 1 include the overlapping ones.
  long long count_s = -7;
  int const ss = pw85_configuration_pairs(cfg, in.scale, 1, 2, i, j, nullptr, &count_s, nullptr);
  record(fn, ss);
  if (!(in.scale >= 1.0) || !std::isfinite(in.scale))
    CHECK(kUntouched, ss == PW85_ERR_INVALID_ARGUMENT && count_s == -7, fn, ss);
  if (ss == PW85_OK && sp == PW85_OK) CHECK(kBatch, count_s >= count1, fn, ss);

  fn = "pw85_configuration_test_move";
  long long jm = -7;
  int const sm = pw85_configuration_test_move(cfg, 1, in.r, in.q2, &jm);
  record(fn, sm);
  if (sm == PW85_OK) {
    CHECK(kStatus, jm == -1 || jm == 0, fn, sm);
    if (sp == PW85_OK) CHECK(kBatch, (jm == 0) == (count1 == 1), fn, sm);
  } else {
    CHECK(kUntouched, jm == -7, fn, sm);
  }
  jm = -7;
  CHECK(kUntouched, pw85_configuration_test_move(cfg, 2, in.r, in.q2, &jm) ==
                        PW85_ERR_INVALID_ARGUMENT && jm == -7, fn, 0);

  // Failed changes leave the configuration as it was.
  fn = "pw85_configuration_move";
  double const nan_centre[3] = {NAN, 0.0, 0.0};
  CHECK(kUntouched, pw85_configuration_move(cfg, 0, nan_centre, in.q1) ==
                        PW85_ERR_INVALID_ARGUMENT, fn, 0);
  CHECK(kUntouched, pw85_configuration_move(cfg, -1, centres, in.q1) ==
                        PW85_ERR_INVALID_ARGUMENT, fn, 0);
  fn = "pw85_configuration_update";
  CHECK(kUntouched, pw85_configuration_update(cfg, -1, centres, q, box, &bad) ==
                        PW85_ERR_INVALID_ARGUMENT, fn, 0);
  CHECK(kUntouched, pw85_configuration_size(cfg) == 2, fn, 0);
  long long count2 = -7;
  int const sp2 = pw85_configuration_pairs(cfg, 1.0, 1, 2, i, j, mu2, &count2, nullptr);
  CHECK(kUntouched, sp2 == sp && (sp != PW85_OK || count2 == count1), fn, sp2);
  // Moving particle 0 where it is and updating with the same particles
  // change nothing either.
  fn = "pw85_configuration_move";
  CHECK(kStatus, pw85_configuration_move(cfg, 0, centres, in.q1) == PW85_OK, fn, 0);
  fn = "pw85_configuration_update";
  CHECK(kStatus, pw85_configuration_update(cfg, 2, centres, q, box, &bad) == PW85_OK, fn, 0);
  count2 = -7;
  CHECK(kBatch, pw85_configuration_pairs(cfg, 1.0, 1, 2, i, j, mu2, &count2, nullptr) == sp &&
                    (sp != PW85_OK || count2 == count1), fn, sp);
  pw85_configuration_destroy(cfg);
  pw85_configuration_destroy(nullptr);
  CHECK(kStatus, pw85_configuration_size(nullptr) == -1, "pw85_configuration_size", 0);
}

// f nearly flat at its maximum (pw85.h, pw85_contact_derivatives): f at
// lambda -+ min(lambda, 1 - lambda) / 4 within 1e-6 mu2 of mu2 (pw85_f_neg,
// whose rounding error is far below that).
bool nearly_flat(Input const &in, double lambda, double mu2) {
  double params[15];
  std::memcpy(params, in.r, sizeof in.r);
  std::memcpy(params + 3, in.q1, sizeof in.q1);
  std::memcpy(params + 9, in.q2, sizeof in.q2);
  double const h = std::fmin(lambda, 1.0 - lambda) / 4;
  for (double l : {lambda - h, lambda + h})
    if (!(std::fabs(-pw85_f_neg(l, params) - mu2) <= 1e-6 * mu2)) return false;
  return true;
}

// q numerically singular in double (pw85.h, pw85_contact_derivatives):
// det q below 2^-50 times the product of its diagonal entries, computed in
// long double (64-bit significand: error far below 2^-50 of that product,
// which bounds each term of det q for a positive definite q).
bool numerically_singular(double const *q) {
  long double const a = q[0], b = q[1], c = q[2], d = q[3], e = q[4], f = q[5];
  long double const det = a * (d * f - e * e) - b * (b * f - e * c) + c * (b * e - d * c);
  return det < 0x1p-50L * (a * d * f);
}

void check_derivatives(Input const &in) {
  char const *fn = "pw85_contact_derivatives";
  pw85_derivatives_t d, d2;
  int const s = pw85_contact_derivatives(in.r, in.q1, in.q2, &d);
  int const s2 = pw85_contact_derivatives(in.r, in.q1, in.q2, &d2);
  record(fn, s);
  spd_decision(fn, s);
  CHECK(kDeterminism, s == s2 && same_bits(&d, &d2, sizeof d), fn, s);
  CHECK(kStatus, in_list(s, {PW85_OK, PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD,
                             PW85_ERR_NO_CONVERGENCE, PW85_ERR_INACCURATE}), fn, s);
  if (s == PW85_ERR_INVALID_ARGUMENT || s == PW85_ERR_NOT_SPD)
    CHECK(kNan, all_nan(&d.mu2, kDerivativeFields), fn, s);
  if (s == PW85_OK) {
    CHECK(kFinite, all_finite(&d.mu2, kDerivativeFields), fn, s);
    CHECK(kLambda, lambda_ok(d.lambda), fn, s);
  }
  // The derivatives answer where DEFAULT does, unless a field leaves the
  // range of double, min(lambda, 1 - lambda) is below about 1e-15, f is
  // nearly flat at its maximum, or q1 or q2 is numerically singular (pw85.h). The fields scale as mu2 times
  // 1/|r12| (d_r12), 1/|r12|^2 (hess_r12) and 1/q (d_q1, d_q2): far inside
  // the range when those all are.
  pw85_result res;
  int const sd = pw85_contact_function_method(in.r, in.q1, in.q2, PW85_METHOD_DEFAULT, &res);
  if (sd == PW85_OK && !is_zero(in.r) && s == PW85_ERR_NO_CONVERGENCE) {
    double qmax = 0.0, qmin = HUGE_VAL;
    for (double const *qq : {in.q1, in.q2})
      for (int k : {0, 3, 5}) {
        qmax = std::fmax(qmax, std::fabs(qq[k]));
        qmin = std::fmin(qmin, std::fabs(qq[k]));
      }
    double const r = std::sqrt(in.r[0] * in.r[0] + in.r[1] * in.r[1] + in.r[2] * in.r[2]);
    double const lo = 0x1p-600, hi = 0x1p600;
    bool const moderate = res.mu2 > lo && res.mu2 < hi && r > lo && r < hi && qmin > lo &&
                          qmax < hi && res.mu2 / (r * r) < hi && res.mu2 / qmin < hi &&
                          std::fmin(res.lambda, 1.0 - res.lambda) > 1e-12;
    CHECK(kAnswers,
          !moderate || nearly_flat(in, res.lambda, res.mu2) || numerically_singular(in.q1) ||
              numerically_singular(in.q2),
          fn, s);
  }
}

void check_contact_time(Input const &in) {
  char const *fn = "pw85_contact_time";
  double t = -7.0, t2 = -7.0;
  int evaluations = -7;
  int const s = pw85_contact_time(in.r, in.v12, in.q1, in.w1, in.q2, in.w2, in.t_max, &t);
  int const s2 = pw85_contact_time_ex(in.r, in.v12, in.q1, in.w1, in.q2, in.w2, in.t_max, &t2,
                                      &evaluations);
  record(fn, s);
  CHECK(kDeterminism, s == s2 && same_bits(&t, &t2, 8), fn, s);
  CHECK(kStatus, in_list(s, {PW85_OK, PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD,
                             PW85_ERR_NO_CONVERGENCE, PW85_ERR_INACCURATE}), fn, s);
  // PW85_ERR_INACCURATE is decided from the inputs before any evaluation.
  CHECK(kStatus, s != PW85_ERR_INACCURATE || (t == 0.0 && evaluations == 0), fn, s);
  CHECK(kStatus, evaluations >= 0 && evaluations <= PW85_CONTACT_TIME_MAX_EVAL + 64, fn, s);
  // One decision, where no other argument is at fault first.
  bool const moderate_motion = all_finite(in.v12, 3) && all_finite(in.w1, 3) &&
                               all_finite(in.w2, 3) && in.t_max > 0.0 && in.t_max < 1e100 &&
                               std::fabs(in.v12[0]) + std::fabs(in.v12[1]) +
                                       std::fabs(in.v12[2]) < 1e100 &&
                               std::fabs(in.w1[0]) + std::fabs(in.w1[1]) + std::fabs(in.w1[2]) +
                                       std::fabs(in.w2[0]) + std::fabs(in.w2[1]) +
                                       std::fabs(in.w2[2]) < 1e100;
  if (moderate_motion) spd_decision(fn, s);
  if (s == PW85_ERR_INVALID_ARGUMENT || s == PW85_ERR_NOT_SPD) CHECK(kNan, std::isnan(t), fn, s);
  if (s == PW85_OK)
    CHECK(kTime, (t >= 0.0 && t <= in.t_max) || t == HUGE_VAL, fn, s);
  if (s == PW85_ERR_NO_CONVERGENCE) CHECK(kTime, t >= 0.0 && t <= in.t_max, fn, s);
  if (s == PW85_OK) {
    // 0 when the pair overlaps at t = 0; a contact at 0 only where mu^2(0)
    // <= 1 within the certificate (1e-14 computed, DEFAULT's 1e-14).
    int const v = pw85_overlap(in.r, in.q1, in.q2);
    if (v == 1) CHECK(kTime, t == 0.0, fn, s);
    pw85_result res;
    if (t == 0.0 && v == 0 &&
        pw85_contact_function_method(in.r, in.q1, in.q2, PW85_METHOD_DEFAULT, &res) == PW85_OK)
      CHECK(kTime, res.mu2 <= 1.0 + 1e-13, fn, s);
  }

  fn = "pw85_contact_time_pairs";
  double tp = -7.0;
  int sp = -7;
  int const spr = pw85_contact_time_pairs(1, in.r, in.v12, in.q1, in.w1, in.q2, in.w2, in.t_max,
                                          &tp, &sp, 1);
  if (!(in.t_max > 0.0) || !std::isfinite(in.t_max))
    CHECK(kUntouched, spr == PW85_ERR_INVALID_ARGUMENT && tp == -7.0 && sp == -7, fn, spr);
  else
    CHECK(kBatch, spr == s && sp == s && same_bits(&tp, &t, 8), fn, spr);
}

}  // namespace fuzz
