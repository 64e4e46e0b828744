/* The random numbers of the demonstration programs (pw85_mc, pw85_md):
 * splitmix64 (Steele, Lea & Flood, OOPSLA 2014), uniform doubles on
 * [0, 1) from its top 53 bits, normal deviates by Box-Muller. Seeded
 * streams, the same on every platform. */
#ifndef PW85_DEMO_RNG_H
#define PW85_DEMO_RNG_H

#include <math.h>
#include <stdint.h>

typedef struct {
  uint64_t s;
} rng_t;

static inline uint64_t rng_next(rng_t *g) {
  uint64_t z = (g->s += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

static inline double rng_uniform(rng_t *g) { return (double)(rng_next(g) >> 11) * 0x1p-53; }

static inline double rng_normal(rng_t *g) {
  double const u1 = rng_uniform(g) + 0x1p-60, u2 = rng_uniform(g);
  return sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
}

#endif
