/* The double Halley iteration shared by PW85_METHOD_NEWTON and
 * PW85_METHOD_DEFAULT (src/core/contact/newton.cpp, newton_iterate), tested
 * on the state it hands to its callers: every field of NewtonState is
 * written on every return, also when an evaluation of f fails after
 * successful ones (Q(lambda) not numerically positive definite), so that
 * the callers (contact_newton, DEFAULT's general method in default.hpp) never
 * read memory the iteration left unwritten. The state is filled with two
 * different byte patterns before the call; the two results must be
 * bitwise equal. Compiled with newton.cpp itself, since newton_iterate is
 * internal. */
#include <cstring>

#include <glib.h>

#include "contact/newton.hpp"

namespace {

struct Pair {
  double r[3], q1[6], q2[6];
};

// A pair whose iteration meets a failing evaluation after successful ones
// (tests/test-reliability-methods.c, first of `failing`), and a pair whose
// first evaluation fails (Q1 = Q2 singular: the C layer rejects it, the
// iteration alone meets a zero pivot at lambda = 1/2).
const Pair pairs[] = {
    {{0x1.8543a6eb49d34p-8, 0x1.242ae6631625dp-7, -0x1.3081ab6960afep-7},
     {0x1.3935685aae98p-52, -0x1.95e1d87c96fc8p-52, -0x1.14ecf6e05ae2fp-53,
      0x1.08007d9465d56p-51, 0x1.6599ff8ae5355p-53, 0x1.eb43520f47ec2p-55},
     {0x1.562956075544bp+31, -0x1.12bd33a5cc69ep+33, 0x1.2ff08adc4b9bap+35,
      0x1.b9344d344a511p+34, -0x1.e818f94abcc86p+36, 0x1.0dfcc77ee77edp+39}},
    {{1, 1, 1}, {1, 1, 0, 1, 0, 1}, {1, 1, 0, 1, 0, 1}},
};

void run(Pair const &p, unsigned char byte, pw85::NewtonState &st, int &iterations, bool &ok) {
  std::memset(static_cast<void *>(&st), byte, sizeof st);
  pw85::Vec3 const r = pw85::load_vec3(p.r);
  pw85::Sym3 const q1 = pw85::load_sym3(p.q1), q2 = pw85::load_sym3(p.q2);
  iterations = 0;
  ok = pw85::newton_iterate(r, q1, q2, pw85::difference(q2, q1), 0.5, st, iterations);
}

void test_state_written() {
  for (Pair const &p : pairs) {
    pw85::NewtonState a, b;
    int ia, ib;
    bool oka, okb;
    run(p, 0x00, a, ia, oka);
    run(p, 0xef, b, ib, okb);
    g_assert_false(oka);
    g_assert_true(oka == okb);
    g_assert_cmpint(ia, ==, ib);
    g_assert_true(std::memcmp(&a, &b, sizeof a) == 0);
  }
}

}  // namespace

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, nullptr);
  g_test_add_func("/pw85_contact_function_method/newton/failing_evaluation/state_written",
                  test_state_written);
  return g_test_run();
}
