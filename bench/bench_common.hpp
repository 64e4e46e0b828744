// Pieces shared by the benchmark programs bench_contact and bench_overlap:
// the seeded generator of the scenes (so both draw the same kind of
// ellipsoids from a seed) and the machine description of the CSV header;
// bench_dca too takes the common options (common_option).
// Benchmarks only, not part of the library.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace bench {

// The options every benchmark takes: --n N, --reps R, --seed S. Returns the
// number of entries of argv consumed at argv[i] (2), or 0 when argv[i] is
// none of them (or its value is missing).
inline int common_option(int argc, char **argv, int i, int &n, int &reps, uint64_t &seed) {
  if (i + 1 >= argc) return 0;
  if (!std::strcmp(argv[i], "--n"))
    n = std::atoi(argv[i + 1]);
  else if (!std::strcmp(argv[i], "--reps"))
    reps = std::atoi(argv[i + 1]);
  else if (!std::strcmp(argv[i], "--seed"))
    seed = std::strtoull(argv[i + 1], nullptr, 10);
  else
    return 0;
  return 2;
}

struct Rng {  // splitmix64
  uint64_t s;
  uint64_t next() {
    uint64_t z = (s += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  double uniform() { return (double)(next() >> 11) * 0x1p-53; }
  double normal() {
    double const u1 = uniform() + 0x1p-60, u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }
};

// Random ellipsoid: semi-axes a[k] log-uniform in [lo, hi] along the columns
// k of rot, a rotation from a uniformly random unit quaternion.
inline void random_axes(Rng &g, double lo, double hi, double a[3], double rot[3][3]) {
  for (int k = 0; k < 3; ++k)
    a[k] = std::exp(std::log(lo) + (std::log(hi) - std::log(lo)) * g.uniform());
  double w = g.normal(), x = g.normal(), y = g.normal(), z = g.normal();
  double const n = std::sqrt(w * w + x * x + y * y + z * z);
  w /= n, x /= n, y /= n, z /= n;
  double const m[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                          {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                          {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
  std::memcpy(rot, m, sizeof m);
}

// Upper triangle of Q = sum_k a_k^2 v_k v_k^T, v_k = column k of rot.
inline void q_from_axes(double const a[3], double const rot[3][3], double q[6]) {
  int idx = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      double s = 0.0;
      for (int k = 0; k < 3; ++k) s += a[k] * a[k] * rot[i][k] * rot[j][k];
      q[idx++] = s;
    }
}

// Centre offset of a random pair: uniformly random direction, length
// reach 10^U(-2, -2 + span) with reach = a1max + a2max (the sum of the
// largest semi-axes). bench_contact's scenes use span = kContactSpan
// (from deep overlap to 3.2 times reach); bench_overlap times those same pairs
// and its older, wider scenes (span 3: up to 10 times reach).
constexpr double kContactSpan = 2.5;
inline void random_offset(Rng &g, double reach, double span, double r[3]) {
  double dir[3] = {g.normal(), g.normal(), g.normal()};
  double const nd = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  double const dist = reach * std::pow(10.0, -2.0 + span * g.uniform());
  for (int k = 0; k < 3; ++k) r[k] = dist * dir[k] / nd;
}

// Output of a shell command (first lines, trailing newlines removed).
inline std::string run_command(char const *cmd) {
  std::string out;
  FILE *f = popen(cmd, "r");
  if (!f) return "unknown";
  char buf[512];
  while (fgets(buf, sizeof buf, f)) out += buf;
  pclose(f);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

// "model name" of /proc/cpuinfo.
inline std::string cpu_model() {
  FILE *f = std::fopen("/proc/cpuinfo", "r");
  if (!f) return "unknown";
  char line[512];
  std::string m = "unknown";
  while (std::fgets(line, sizeof line, f)) {
    if (std::strncmp(line, "model name", 10) == 0) {
      char const *c = std::strchr(line, ':');
      if (c) {
        m = c + 2;
        while (!m.empty() && m.back() == '\n') m.pop_back();
      }
      break;
    }
  }
  std::fclose(f);
  return m;
}

}  // namespace bench
