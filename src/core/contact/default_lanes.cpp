// PW85_METHOD_DEFAULT across pairs (docs/batch.md, "Throughput"): the
// common path of default_body (default.cpp) for kLanes pairs at once (a
// block of kDefaultLanes pairs in kDefaultLanes / kLanes vectors), pair l in
// lane l of each vector: the screen of the entry (screen.hpp,
// screen_contact_pair), the start (M22) (start.hpp: start_quartics;
// start.hpp: log_newton_iterate, newton_start), then the Halley
// iteration (M8) with adjugate evaluations (f_adj.hpp, eq. (M16)) until the
// quartic model (M18) is accepted with the first-order error of step 1
// (eqs. (M10), (M17)) or of the stationary form (M11) below kFastRel mu2.
// Every lane performs the scalar
// operations of that code in the same order on its own pair (this file is
// compiled without contraction, src/meson.build, so each lane's IEEE
// operations are those of the one-pair call), so an accepted lane carries
// the bits of pw85_contact_function_method; the others (screen failed, a
// failed evaluation, step 2 needed, more than kLaneMaxIter steps) are
// returned undecided for the caller's one-pair call. On x86-64-v4, where the
// one-pair DEFAULT runs the rational step first, default_lanes runs the
// lanes of rational_lanes.cpp instead.
#include <cmath>

#include "common/fp.hpp"
#include "common/isa.hpp"
#include "common/lanes.hpp"
#include "common/screen.hpp"
#include "contact/contact.hpp"
#include "contact/default_params.hpp"
#include "contact/rational_step.hpp"
#include "contact/start.hpp"
#include "contact/start_lanes.hpp"
#include "eval/f_adj.hpp"
#include "eval/f_dd.hpp"

namespace pw85 {

namespace {

using namespace lanes;
constexpr int W = kLanes;
static_assert(kDefaultLanes % W == 0, "kDefaultLanes / W vectors per block");

using namespace default_params;
constexpr double kClamp = kLogNewtonClamp;
// Halley steps tried in the lanes; the pairs that need more are left to the
// one-pair call (which repeats them: same bits).
constexpr int kLaneMaxIter = 8;

typedef SymL<W> S;
typedef Vec3L<W> T;

// DEFAULT's start (M22) (start.hpp).
PW85_ALWAYS_INLINE V default_start(T const &r, S const &q1, S const &q2) noexcept {
  return log_newton_start<kStartMin, kStartMax>(r, q1, q2, kStartTol);
}

// f_adj.hpp: f_eval_adj and adj_error for these lanes.
typedef AdjEvalOf<V, S, T> E;

// The body, compiled once per instruction-set level below.
PW85_ALWAYS_INLINE void lanes_body(double const *const rp[W], double const *const q1p[W],
                                   double const *const q2p[W], MethodResult res[W],
                                   bool accepted[W]) noexcept {
  T r;
  S q1, q2;
  M active{};
  for (int l = 0; l < W; ++l) {
    for (int i = 0; i < kDim; ++i) r[i][l] = rp[l][i];
    for (int i = 0; i < kSym; ++i) {
      q1[i][l] = q1p[l][i];
      q2[i][l] = q2p[l][i];
    }
    active[l] = screen_contact_pair(rp[l], q1p[l], q2p[l], kSafeLo, kSafeHi) ? -1 : 0;
  }
  M ok{};  // lanes accepted
  V mu2{}, lam{}, err{};
  M iters{};
  if (any(active)) {
    S d;
    for (int i = 0; i < kSym; ++i) d[i] = q2[i] - q1[i];
    V lambda = default_start(r, q1, q2);
    V lo{}, hi = V{} + 1.0;
    E e;
    for (int it = 0; it < kLaneMaxIter && any(active); ++it) {
      iters -= active;  // + 1 in the active lanes
      active &= f_eval_adj(lambda, r, q1, q2, d, e);
      HalleyDecision<V> const hd = halley_decide(lambda, e, lo, hi);
      V const a = hd.a, step = hd.step, next = hd.next;
      M const inside = hd.inside, tiny = hd.tiny;
      M const near = active & hd.near;
      if (any(near)) {
        M fast_or_stat;
        // Step 1 of default_body at a lambda near enough for the model.
        T const Er = adj_error(e, r, q1, q2);
        V const p = lambda * (1.0 - lambda), p1 = vabs(1.0 - 2.0 * lambda);
        T const as{{vabs(e.s[0]), vabs(e.s[1]), vabs(e.s[2])}};
        S da;
        for (int i = 0; i < kSym; ++i) da[i] = vabs(d[i]);
        T const ar{{vabs(r[0]), vabs(r[1]), vabs(r[2])}};
        V const edf = p1 * dot(ar, Er) + 2.0 * p * dot(as, multiply(da, Er)) +
                      4.0 * kU * (p1 * e.phi + p * vabs(e.dphi));
        V const h = select(tiny, V{}, step);
        V const err_l = model_error(edf, h, a, e.d4f);
        M const done =
            near & ((err_l <= kExtrapBudget * e.f) | (vabs(e.df) <= 2.0 * edf) | tiny);
        V const corr = model_increment(h, e);
        V const err1 = p * (dot(ar, Er) + 3.0 * kU * dot(ar, as)) + 4.0 * kU * e.f + err_l;
        M const fast = done & (err1 <= kFastRel * e.f);
        V m = e.f + corr, em = err1;
        // The stationary form (M11) where the first-order error is too large:
        // second-order error p E^T |Q| E tested first; f_stationary itself
        // is the one-pair call's (its instruction-set variants included),
        // called lane by lane.
        M const slow = done & ~fast;
        if (any(slow)) {
          S qa;
          for (int i = 0; i < kSym; ++i) qa[i] = vabs(e.q[i]);
          V const err2 = p * dot(Er, multiply(qa, Er)) + err_l;
          M const try_stat = slow & ~(err2 + e.f * kStatRel > 0.999 * kFastRel * e.f);
          V fs{};
          for (int l = 0; l < W; ++l) {
            if (try_stat[l] == 0) continue;
            fs[l] = f_stationary(lambda[l], Vec3{{r[0][l], r[1][l], r[2][l]}},
                                 Sym3{{q1[0][l], q1[1][l], q1[2][l], q1[3][l], q1[4][l], q1[5][l]}},
                                 Sym3{{q2[0][l], q2[1][l], q2[2][l], q2[3][l], q2[4][l], q2[5][l]}},
                                 Vec3{{e.s[0][l], e.s[1][l], e.s[2][l]}});
          }
          V const ms = fs + corr;
          V const es = ms * kStatRel + err2;
          M const stat_ok = try_stat & (es <= kFastRel * ms);
          m = select(stat_ok, ms, m);
          em = select(stat_ok, es, em);
          fast_or_stat = fast | stat_ok;
        } else {
          fast_or_stat = fast;
        }
        V const lh = lambda + h;
        // The promise checked after every method (methods.cpp, checked).
        M const take = fast_or_stat & (m >= 0.0) & (lh >= 0.0) & (lh <= 1.0) & (em == em);
        mu2 = select(take, m, mu2);
        lam = select(take, lh, lam);
        err = select(take, em, err);
        ok |= take;
        active &= ~done;  // accepted, or step 2 needed
      }
      active &= ~tiny;  // step 2 needed
      lambda = select(inside, next, 0.5 * (lo + hi));
    }
  }
  for (int l = 0; l < W; ++l) {
    accepted[l] = ok[l] != 0;
    res[l].mu2 = mu2[l];
    res[l].lambda = lam[l];
    res[l].mu2_error = err[l];
    res[l].iterations = static_cast<int>(iters[l]);
    res[l].method = kMethodDefault;
  }
}

#if PW85_ISA_LEVELS
PW85_TARGET_V3 void lanes_v3(double const *const rp[W], double const *const q1p[W],
                             double const *const q2p[W], MethodResult res[W],
                             bool accepted[W]) noexcept {
  lanes_body(rp, q1p, q2p, res, accepted);
}
#endif

}  // namespace

void default_lanes(double const *const r[kDefaultLanes], double const *const q1[kDefaultLanes],
                   double const *const q2[kDefaultLanes], MethodResult res[kDefaultLanes],
                   int status[kDefaultLanes]) noexcept {
#if PW85_ISA_LEVELS
  // On x86-64-v4 the one-pair DEFAULT runs the rational step first
  // (default.cpp): its lanes are those of rational_lanes.cpp.
  if (isa::has_v4()) return rational_lanes_v4(r, q1, q2, res, status);
#endif
  bool accepted[kDefaultLanes];
  for (int b = 0; b < kDefaultLanes; b += W) {
#if PW85_ISA_LEVELS
    if (isa::has_v3()) {
      lanes_v3(r + b, q1 + b, q2 + b, res + b, accepted + b);
      continue;
    }
#endif
    lanes_body(r + b, q1 + b, q2 + b, res + b, accepted + b);
  }
  for (int l = 0; l < kDefaultLanes; ++l) status[l] = accepted[l] ? kOk : kLaneUndecided;
}

}  // namespace pw85
