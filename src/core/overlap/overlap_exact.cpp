// Exact stage of the overlap predicate (docs/overlap.md, "Exact stage").
//
// With Q(lambda) = (1 - lambda) Q1 + lambda Q2, b(lambda) = det Q(lambda) and
// a(lambda) = r^T adj Q(lambda) r (pw85 documentation, chapter 4,
// eqs. (10)-(11)), f = lambda (1 - lambda) a / b, and b > 0 on [0, 1]. Hence
//     mu^2 >= 1  <=>  f(lambda) >= 1 for some lambda in [0, 1]
//               <=>  p(lambda) = b(lambda) - lambda (1 - lambda) a(lambda) <= 0
//                    for some lambda in [0, 1]
//               <=>  p has a root in (0, 1)   (p(0) = det Q1 > 0, p(1) = det Q2 > 0).
// Every double is an integer times a power of two, so after multiplying by a
// positive power of two p has integer coefficients, computed exactly here; the
// number of distinct roots of p in (0, 1) is the difference of the sign
// variations at 0 and 1 of its Sturm sequence (Sturm's theorem), built with
// sign-corrected pseudo-remainders so that every member is a positive
// multiple of the classical one.
#include <cmath>
#include <cstdint>

#include "arith/bigint.hpp"
#include "arith/exact_double.hpp"
#include "overlap/overlap.hpp"

namespace pw85 {

using exact::BigInt;
using exact::Ctx;
using exact::to_integers;

namespace {

constexpr int kMaxDeg = 4;

struct Poly {
  int deg;  // -1 for the zero polynomial
  BigInt c[kMaxDeg + 1];
};

void trim(Poly &p) noexcept {
  while (p.deg >= 0 && p.c[p.deg].s == 0) --p.deg;
}

// Linear polynomial u + v lambda and products of two of them.
struct Lin {
  BigInt u, v;
};

void zero_poly(Poly &p, int deg) noexcept {
  p.deg = deg;
  for (int i = 0; i <= kMaxDeg; ++i) exact::set_zero(p.c[i]);
}

// Sign of p at 0 and at 1.
int sign_at_0(Poly const &p) noexcept { return p.deg < 0 ? 0 : p.c[0].s; }

int sign_at_1(Ctx &ctx, Poly const &p, BigInt &t) noexcept {
  exact::set_zero(t);
  for (int i = 0; i <= p.deg; ++i) exact::add(ctx, t, t, p.c[i]);
  return t.s;
}

// r = -(positive multiple of rem(a, b)), b != 0. r must not alias a or b.
void neg_prem(Ctx &ctx, Poly &r, Poly const &a, Poly const &b, BigInt &t1,
              BigInt &t2) noexcept {
  r.deg = a.deg;
  for (int i = 0; i <= kMaxDeg; ++i) {
    if (i <= a.deg)
      exact::copy(r.c[i], a.c[i]);
    else
      exact::set_zero(r.c[i]);
  }
  trim(r);
  BigInt const &lb = b.c[b.deg];
  int steps = 0;
  while (r.deg >= b.deg && r.deg >= 0) {
    int const shift = r.deg - b.deg;
    exact::copy(t2, r.c[r.deg]);  // leading coefficient of r
    for (int i = 0; i <= r.deg; ++i) {
      exact::mul(ctx, t1, lb, r.c[i]);
      exact::copy(r.c[i], t1);
      if (i >= shift) {
        exact::mul(ctx, t1, t2, b.c[i - shift]);
        exact::sub(ctx, r.c[i], r.c[i], t1);
      }
    }
    ++steps;
    trim(r);
    if (ctx.overflow) return;
  }
  // r = lb^steps rem(a, b); make the factor positive, then negate.
  int flip = -1;
  if (lb.s < 0 && (steps % 2) == 1) flip = 1;
  for (int i = 0; i <= r.deg; ++i) r.c[i].s *= flip;
}


// Integer coefficients of p (times a positive power of two). Returns kOk,
// kNotSpd or kInaccurate (capacity exceeded). Kept out of line so that its
// stack frame and the Sturm stage's do not coexist.
__attribute__((noinline)) Status quartic_p(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                                           Poly &p) noexcept {
  Ctx ctx;
  // Exact integers: Q_k = 2^eq Qk_int, r = 2^er r_int. q[i].u <- Q1, q[i].v <- Q2.
  Lin q[kSym];
  BigInt ri[3];
  double qq[12];
  BigInt *outq[12];
  BigInt *outr[3] = {&ri[0], &ri[1], &ri[2]};
  for (int i = 0; i < kSym; ++i) {
    qq[i] = q1[i];
    qq[kSym + i] = q2[i];
    outq[i] = &q[i].u;
    outq[kSym + i] = &q[i].v;
  }
  int const eq = to_integers(ctx, qq, 12, outq);
  int const er = to_integers(ctx, r.x, 3, outr);
  if (ctx.overflow) return kInaccurate;
  BigInt t1, t2, t3;

  // Exact positive definiteness (Sylvester's criterion), first two minors.
  for (int k = 0; k < 2; ++k) {
    BigInt const &q0 = k == 0 ? q[0].u : q[0].v;
    BigInt const &q1k = k == 0 ? q[1].u : q[1].v;
    BigInt const &q3 = k == 0 ? q[3].u : q[3].v;
    if (q0.s <= 0) return kNotSpd;
    exact::mul(ctx, t1, q0, q3);
    exact::mul(ctx, t2, q1k, q1k);
    exact::sub(ctx, t1, t1, t2);
    if (t1.s <= 0) return kNotSpd;
  }
  // Q(lambda) = A + lambda D, A = Q1, D = Q2 - Q1.
  for (int i = 0; i < kSym; ++i) exact::sub(ctx, q[i].v, q[i].v, q[i].u);

  // Adjugate entries (quadratics): adj00 = q3 q5 - q4^2, adj01 = q2 q4 - q1 q5,
  // adj02 = q1 q4 - q2 q3, adj11 = q0 q5 - q2^2, adj12 = q1 q2 - q0 q4,
  // adj22 = q0 q3 - q1^2.
  static constexpr int kAdj[6][4] = {{3, 5, 4, 4}, {2, 4, 1, 5}, {1, 4, 2, 3},
                                     {0, 5, 2, 2}, {1, 2, 0, 4}, {0, 3, 1, 1}};
  // r_i r_j (times 2 off the diagonal), in the order of kAdj.
  static constexpr int kRij[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
  Poly &det = p;  // det Q(lambda) is accumulated in p directly (degree 3)
  zero_poly(det, 4);
  BigInt a[3], adj[3];
  for (int i = 0; i < 3; ++i) exact::set_zero(a[i]);
  for (int k = 0; k < kSym; ++k) {
    for (int i = 0; i < 3; ++i) exact::set_zero(adj[i]);
    for (int sgn = 1, h = 0; h < 2; ++h, sgn = -1) {
      Lin const &x = q[kAdj[k][2 * h]];
      Lin const &y = q[kAdj[k][2 * h + 1]];
      exact::mul(ctx, t1, x.u, y.u);
      exact::add_signed(ctx, adj[0], adj[0], t1, sgn);
      exact::mul(ctx, t1, x.u, y.v);
      exact::mul(ctx, t2, x.v, y.u);
      exact::add(ctx, t1, t1, t2);
      exact::add_signed(ctx, adj[1], adj[1], t1, sgn);
      exact::mul(ctx, t1, x.v, y.v);
      exact::add_signed(ctx, adj[2], adj[2], t1, sgn);
    }
    // det = q0 adj00 + q1 adj01 + q2 adj02 (first-row cofactor expansion).
    if (k < 3) {
      for (int i = 0; i <= 2; ++i) {
        exact::mul(ctx, t1, q[k].u, adj[i]);
        exact::add(ctx, det.c[i], det.c[i], t1);
        exact::mul(ctx, t1, q[k].v, adj[i]);
        exact::add(ctx, det.c[i + 1], det.c[i + 1], t1);
      }
    }
    // a = sum_ij r_i r_j adj_ij.
    exact::mul(ctx, t3, ri[kRij[k][0]], ri[kRij[k][1]]);
    if (kRij[k][0] != kRij[k][1]) exact::shl(ctx, t3, 1);
    for (int i = 0; i <= 2; ++i) {
      exact::mul(ctx, t1, t3, adj[i]);
      exact::add(ctx, a[i], a[i], t1);
    }
  }
  if (ctx.overflow) return kInaccurate;
  // Last minors: det Q1 = det(0) > 0, det Q2 = det(1) > 0.
  if (det.c[0].s <= 0) return kNotSpd;
  exact::set_zero(t1);
  for (int i = 0; i <= 3; ++i) exact::add(ctx, t1, t1, det.c[i]);
  if (t1.s <= 0) return kNotSpd;

  // det Q = 2^(3 eq) det_int and r^T adj Q r = 2^(2 er + 2 eq) a_int, so
  // p = 2^(3 eq - sb) (2^sb det_int - (lambda - lambda^2) 2^sa a_int)
  // with s = 2 er - eq, sa = max(s, 0), sb = max(-s, 0).
  long const s = 2L * er - eq;
  if (s > 64L * exact::kLimbs || -s > 64L * exact::kLimbs) return kInaccurate;
  int const sa = s > 0 ? static_cast<int>(s) : 0;
  int const sb = s < 0 ? static_cast<int>(-s) : 0;
  for (int i = 0; i <= 3; ++i) exact::shl(ctx, det.c[i], sb);
  for (int i = 0; i <= 2; ++i) exact::shl(ctx, a[i], sa);
  // (lambda - lambda^2)(a0 + a1 l + a2 l^2) = a0 l + (a1 - a0) l^2 + (a2 - a1) l^3 - a2 l^4.
  exact::sub(ctx, p.c[1], p.c[1], a[0]);
  exact::sub(ctx, t1, a[1], a[0]);
  exact::sub(ctx, p.c[2], p.c[2], t1);
  exact::sub(ctx, t1, a[2], a[1]);
  exact::sub(ctx, p.c[3], p.c[3], t1);
  exact::copy(p.c[4], a[2]);
  trim(p);
  if (ctx.overflow) return kInaccurate;
  return kOk;
}

}  // namespace

Status overlap_exact(Vec3 const &r, Sym3 const &q1, Sym3 const &q2, int &verdict) noexcept {
  if (r[0] == 0.0 && r[1] == 0.0 && r[2] == 0.0) {
    verdict = 1;
    return kOk;
  }
  Poly seq[3];  // rolling window of the Sturm sequence
  Status const st = quartic_p(r, q1, q2, seq[0]);
  if (st != kOk) return st;
  Ctx ctx;
  BigInt t1, t2, t3;
  Poly &p = seq[0];

  // p' (integer coefficients k c_k).
  Poly &dp = seq[1];
  zero_poly(dp, p.deg - 1);
  for (int i = 1; i <= p.deg; ++i) {
    BigInt &c = dp.c[i - 1];
    exact::set_zero(c);
    for (int k = 0; k < i; ++k) exact::add(ctx, c, c, p.c[i]);
  }
  trim(dp);

  // Sign variations at 0 and 1 along the Sturm sequence.
  int v0 = 0, v1 = 0, last0 = 0, last1 = 0;
  auto count = [&](Poly const &x) {
    int const a0 = sign_at_0(x);
    int const a1 = sign_at_1(ctx, x, t3);
    if (a0 != 0) {
      if (last0 != 0 && a0 != last0) ++v0;
      last0 = a0;
    }
    if (a1 != 0) {
      if (last1 != 0 && a1 != last1) ++v1;
      last1 = a1;
    }
  };
  count(seq[0]);
  int prev = 0, cur = 1;
  while (seq[cur].deg >= 0) {
    count(seq[cur]);
    if (seq[cur].deg == 0) break;
    int const next = 3 - prev - cur;
    neg_prem(ctx, seq[next], seq[prev], seq[cur], t1, t2);
    if (ctx.overflow) return kInaccurate;
    prev = cur;
    cur = next;
  }
  if (ctx.overflow) return kInaccurate;
  int const roots = v0 - v1;  // distinct roots of p in (0, 1]
  verdict = roots > 0 ? 0 : 1;
  return kOk;
}

}  // namespace pw85
