/* PW85_METHOD_DEFAULT on a pair whose matrices lie 2^951 apart (magnitudes
 * 2^-476 and 2^475, input 37208 of tests/determinism/calls.c): the same
 * status on every instruction-set variant (include/pw85.h, "every status
 * ... the same on every CPU"), and mu2 against an independent reference.
 *
 * The library rescales the pair (src/core/contact/methods.cpp): r by
 * 2^164, both matrices by 2^-476, so that the smaller matrix is 2^-951 and
 * f(lambda) is 2^804 times that of the inputs. Near the maximiser Q(lambda)
 * is as small as the smaller matrix and the terms s^T D s of f' reach
 * 2^1004, beyond the 2^996 where Dekker's product (the double-double
 * kernels of CPUs without a fused multiply-add) splits its factors into an
 * overflow. Checked, through the table of each variant the CPU runs
 * (dispatch/kernels.hpp, kernels_of):
 *  - the double-double evaluation of f (kernels_of(v).dd->f_eval) at a
 *    lambda of that region: it succeeds on every variant (the portable one
 *    is Dekker's product) and its f matches the reference;
 *  - DEFAULT's kernel (kernels_of(v).contact_default) on the rescaled pair:
 *    PW85_OK on every variant, mu2 within 1e-14 of the reference;
 *  - the public calls pw85_contact_function_method, pw85_dca and
 *    pw85_contact: PW85_OK and their values within 1e-14; with Q1 and Q2
 *    exchanged, a status that matches the error bound, which holds.
 * The program also runs under valgrind (x86-64-v3 and FMA variants) and in
 * the isa_dispatch=false build (portable kernels behind every call).
 *
 * Reference (mpmath, 60 digits): f(lambda) = lambda (1 - lambda) r^T
 * ((1 - lambda) Q1 + lambda Q2)^{-1} r by LU solve, maximised by golden
 * section over log2(lambda) in [-1100, -100] (400 steps); f is flat there
 * (maximiser near 2^-708): mu2 = 6.19188091785396798062219168694e-235,
 * f(0x1.dcb6e00690e9fp-477) equal to it to 30 digits, and the distance of
 * closest approach along r12, |r12| / mu, 4.05673493288534178325134167097e67. */
#include <cmath>
#include <cstdio>
#include <initializer_list>

#include <glib.h>

#include "common/scaling.hpp"
#include "dispatch/kernels.hpp"
#include "eval/f_dd.hpp"
#include "pw85.h"

namespace {

double const kR[3] = {0x1.c896ae92330f4p-166, -0x1.188b103b5ef5fp-165, 0x1.ede1d361e9f4fp-167};
double const kQ1[6] = {0x1.361e5fea3c9a5p-476, -0x1.b04ac0ed564d2p-477, -0x1.05efdd04cb96ap-477,
                       0x1.2d4c566ae01b7p-477, 0x1.6d20fa4077bf8p-478, 0x1.ba7b6a2f52d83p-479};
double const kQ2[6] = {0x1.220ae782e9ddfp+475, -0x1.473d63600b07p+475, 0x1.6d94fbcd0241p+473,
                       0x1.717748056093cp+475, -0x1.9be4fa9f2f592p+473, 0x1.ce100bb18dc57p+471};
double const kMu2 = 6.19188091785396798062219168694e-235;
double const kDca = 4.05673493288534178325134167097e67;
double const kLambda = 0x1.dcb6e00690e9fp-477;  // f(kLambda) = kMu2 to 30 digits
// The rescaling of methods.cpp: r' = 2^kEr r, Q' = 2^kEq Q, f' = 2^kEf f.
int const kEr = 164, kEq = -476, kEf = 2 * kEr - kEq;
double const kTol = 1e-14;  // DEFAULT's documented accuracy (pw85.h)

void near(double x, double ref, char const *what) {
  if (!(std::fabs(x - ref) <= kTol * ref))
    std::fprintf(stderr, "%s: %.17g, reference %.17g\n", what, x, ref);
  g_assert_cmpfloat(std::fabs(x - ref), <=, kTol * ref);
}

void rescaled(pw85::Vec3 &r, pw85::Sym3 &q1, pw85::Sym3 &q2) {
  pw85::Vec3 const r0{{kR[0], kR[1], kR[2]}};
  pw85::Sym3 const a{{kQ1[0], kQ1[1], kQ1[2], kQ1[3], kQ1[4], kQ1[5]}};
  pw85::Sym3 const b{{kQ2[0], kQ2[1], kQ2[2], kQ2[3], kQ2[4], kQ2[5]}};
  pw85::scale_pair(r0, a, b, kEr, kEq, r, q1, q2);
}

// check(variant's table, r, q1, q2) for every variant the CPU runs, on the
// rescaled pair.
template <class Check>
void each_variant(Check check) {
  pw85::Vec3 r;
  pw85::Sym3 q1, q2;
  rescaled(r, q1, q2);
  for (pw85::Variant v : {pw85::Variant::portable, pw85::Variant::fma, pw85::Variant::v3,
                          pw85::Variant::v4})
    if (pw85::variant_runs(v)) check(pw85::kernels_of(v), r, q1, q2);
}

void test_dd_evaluation(void) {
  each_variant([](pw85::Kernels const &k, pw85::Vec3 const &r, pw85::Sym3 const &q1,
                  pw85::Sym3 const &q2) {
    pw85::FEvalDD fd;
    g_assert_true(k.dd->f_eval(kLambda, r, q1, q2, fd));
    near(std::ldexp(fd.f, -kEf), kMu2, "f_eval");
  });
}

void test_default_kernel(void) {
  each_variant([](pw85::Kernels const &k, pw85::Vec3 const &r, pw85::Sym3 const &q1,
                  pw85::Sym3 const &q2) {
    pw85::MethodResult res;
    res.iterations = 0;
    g_assert_cmpint(k.contact_default->contact(r, q1, q2, res), ==, PW85_OK);
    near(std::ldexp(res.mu2, -kEf), kMu2, "contact_default");
  });
}

void test_public_calls(void) {
  pw85_result res;
  g_assert_cmpint(pw85_contact_function_method(kR, kQ1, kQ2, PW85_METHOD_DEFAULT, &res), ==,
                  PW85_OK);
  near(res.mu2, kMu2, "pw85_contact_function_method");
  g_assert_cmpfloat(res.mu2_error, <=, kTol * res.mu2);
  // Q1 and Q2 exchanged, r12 reversed: the same f, its maximiser 1 - 2^-708
  // (not a double apart from 1). The status must match the error bound,
  // and the bound must hold.
  double const rn[3] = {-kR[0], -kR[1], -kR[2]};
  int const s = pw85_contact_function_method(rn, kQ2, kQ1, PW85_METHOD_DEFAULT, &res);
  g_assert_true(s == PW85_OK || s == PW85_ERR_INACCURATE);
  g_assert_cmpint(s == PW85_OK, ==, res.mu2_error <= kTol * res.mu2);
  g_assert_cmpfloat(std::fabs(res.mu2 - kMu2), <=, res.mu2_error + kTol * kMu2);
  double d;
  g_assert_cmpint(pw85_dca(kR, kQ1, kQ2, PW85_METHOD_DEFAULT, &d), ==, PW85_OK);
  near(d, kDca, "pw85_dca");
  pw85_contact_t c;
  g_assert_cmpint(pw85_contact(kR, kQ1, kQ2, &c), ==, PW85_OK);
  near(c.mu2, kMu2, "pw85_contact");
}

}  // namespace

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, nullptr);
  g_test_add_func("/default_variants/matrices_far_apart/dd_evaluation", test_dd_evaluation);
  g_test_add_func("/default_variants/matrices_far_apart/default_kernel", test_default_kernel);
  g_test_add_func("/default_variants/matrices_far_apart/public_calls", test_public_calls);
  return g_test_run();
}
