// The promise checks shared by the files of the fuzz target (fuzz_pw85.cpp,
// fuzz_scene.cpp): a violated promise prints its name and calls
// __builtin_trap(); every status and verdict met is folded into a digest
// (record()), which fuzz-replay prints so that .ci/run can compare the
// builds and instruction-set variants on the corpus.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <initializer_list>

namespace fuzz {

enum Check {
  kStatus,       // the status is one the function documents
  kFinite,       // the estimates documented as written are finite
  kNan,          // outputs are NaN on the errors documented so
  kLambda,       // lambda in [0, 1] whenever a result is written
  kSwap,         // pw85_overlap's verdict unchanged when the ellipsoids swap
  kBatch,        // the batch, pairs and scene calls equal the one-pair calls
  kDeterminism,  // the same call twice gives the same bits
  kUntouched,    // outputs left as they were where the header says nothing is written
  kSpd,          // one positive-definiteness decision across the calls
  kImage,        // periodic scenes: the image of the header's wrap
  kTime,         // pw85_contact_time's certificate at t = 0 and its bounds
  kAxes,         // pw85_ellipsoid_axes's outputs give q back
  kAnswers,      // the derivatives answer where DEFAULT does and they are representable
  kChecks
};
extern char const *const check_name[kChecks];
extern bool skip_check[kChecks];
extern int current_method;  // the method of the call checked, printed with a violation

[[noreturn]] void violated(Check c, char const *fn, int status);

// Inside namespace fuzz: check is a Check.
#define CHECK(check, cond, fn, status)                              \
  do {                                                              \
    if (!skip_check[check] && !(cond)) violated(check, fn, status); \
  } while (0)

// Folds (fn, value) into the digest of the statuses and verdicts (and the
// few integer outputs that the header promises the same on every CPU).
void record(char const *fn, long long value);
std::uint64_t digest();
// fuzz-replay --trace: every recorded (fn, value) is also printed.
extern std::FILE *trace;

// The positive-definiteness decision of the current pair (1: q1 or q2
// refused, 0: both accepted, -1: not applicable), set by check_one_pair;
// spd_decision(fn, status) checks that a call on the pair took it.
extern int spd_expected;
void spd_decision(char const *fn, int status);

inline bool in_list(int s, std::initializer_list<int> l) {
  for (int x : l)
    if (s == x) return true;
  return false;
}
inline bool all_nan(double const *v, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isnan(v[i])) return false;
  return true;
}
inline bool all_finite(double const *v, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}
inline bool same_bits(void const *a, void const *b, std::size_t n) {
  return std::memcmp(a, b, n) == 0;
}
inline bool lambda_ok(double l) { return l >= 0.0 && l <= 1.0; }

// The decoded input: a pair and the scalars of every call.
struct Input {
  double r[3], q1[6], q2[6];
  int method;
  double lambda, theta;
  // periodic box {Lx, Ly, Lz, xy, xz, yz}, used when has_box
  bool has_box;
  double box[6];
  // contact time: velocity, angular velocities, horizon; called when with_time
  bool with_time;
  double v12[3], w1[3], w2[3], t_max;
  double scale;  // pw85_configuration_pairs's s
};

void check_one_pair(Input const &in);
void check_batch(Input const &in);
void check_pairs(Input const &in);
void check_scene(Input const &in);
void check_configuration(Input const &in);
void check_derivatives(Input const &in);
void check_contact_time(Input const &in);

}  // namespace fuzz
