// f(lambda) and f'(lambda) in double-double arithmetic (src/core/dd.hpp),
// for the final steps of PW85_METHOD_DEFAULT (docs/methods.md, eq. (M11)).
// Q(lambda) = (1 - lambda) Q1 + lambda Q2 is formed exactly (1 - lambda and
// the products are error-free transformations of the double inputs), then
// factored as L D L^T and solved in double-double: the relative error of phi
// is about kappa(Q) 2^-104 instead of kappa(Q) 2^-53.
#pragma once

#include "dd.hpp"
#include "sym3.hpp"

namespace pw85 {

struct FEvalDD {
  double f;    // f(lambda), rounded to double
  double df;   // f'(lambda), rounded to double
  double phi;  // r^T Q^{-1} r, rounded to double
};

inline bool f_eval_dd(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                      FEvalDD &out) noexcept {
  using namespace dd;
  DD const om = two_sum(1.0, -lambda);  // 1 - lambda, exactly
  DD q[kSym], dq[kSym];
  for (int i = 0; i < kSym; ++i) {
    // (1 - lambda) q1 exactly as a double-double: om.hi q1 + om.lo q1.
    DD a = two_prod(om.hi, q1[i]);
    a = add(a, om.lo * q1[i]);
    q[i] = add(a, two_prod(lambda, q2[i]));
    dq[i] = two_sum(q2[i], -q1[i]);  // D = Q2 - Q1, exactly
  }
  // L D L^T.
  if (!(q[0].hi > 0.0)) return false;
  DD const id0 = div(DD{1.0, 0.0}, q[0]);
  DD const l10 = mul(q[1], id0), l20 = mul(q[2], id0);
  DD const d1 = sub(q[3], mul(l10, q[1]));
  if (!(d1.hi > 0.0)) return false;
  DD const id1 = div(DD{1.0, 0.0}, d1);
  DD const e = sub(q[4], mul(l20, q[1]));
  DD const l21 = mul(e, id1);
  DD const d2 = sub(sub(q[5], mul(l20, q[2])), mul(l21, e));
  if (!(d2.hi > 0.0)) return false;
  DD const id2 = div(DD{1.0, 0.0}, d2);
  // y = L^{-1} r, z = D^{-1} y, s = L^{-T} z.
  DD const y0{r[0], 0.0};
  DD const y1 = sub(DD{r[1], 0.0}, mul(l10, r[0]));
  DD const y2 = sub(sub(DD{r[2], 0.0}, mul(l20, r[0])), mul(l21, y1));
  DD const z0 = mul(y0, id0), z1 = mul(y1, id1), z2 = mul(y2, id2);
  DD const phi = add(add(mul(y0, z0), mul(y1, z1)), mul(y2, z2));
  DD const s2 = z2;
  DD const s1 = sub(z1, mul(l21, s2));
  DD const s0 = sub(sub(z0, mul(l10, s1)), mul(l20, s2));
  // s^T D s.
  DD sds = add(add(mul(dq[0], mul(s0, s0)), mul(dq[3], mul(s1, s1))), mul(dq[5], mul(s2, s2)));
  DD const cross = add(add(mul(dq[1], mul(s0, s1)), mul(dq[2], mul(s0, s2))),
                       mul(dq[4], mul(s1, s2)));
  sds = add(sds, mul(cross, 2.0));
  // p = lambda (1 - lambda), p' = 1 - 2 lambda (exact: 2 lambda is exact).
  DD const p = mul(om, lambda);
  DD const p1 = add(om, -lambda);
  DD const f = mul(p, phi);
  DD const df = sub(mul(phi, p1), mul(p, sds));  // f' = p' phi + p phi', phi' = -s^T D s
  out.f = to_double(f);
  out.df = to_double(df);
  out.phi = to_double(phi);
  return std::isfinite(out.f) && std::isfinite(out.df);
}

}  // namespace pw85
