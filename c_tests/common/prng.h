/* The one pseudo-random generator of the C tests, the demo and the benchmark.
 *
 * splitmix64 (Steele, Lea, Flood 2014; public-domain reference by S. Vigna): a 64-bit state
 * advanced by a Weyl increment and finalized by a mixing function. Every program seeds it with
 * a fixed constant, so every run sees the same points. Header-only on purpose: one definition,
 * identical in every program. */
#ifndef DELMESH_C_TESTS_PRNG_H
#define DELMESH_C_TESTS_PRNG_H

#include <stdint.h>

typedef struct Prng {
  uint64_t state;
} Prng;

static inline Prng prng_new(uint64_t seed) {
  Prng g;
  g.state = seed;
  return g;
}

static inline uint64_t prng_next(Prng *g) {
  uint64_t z = (g->state += UINT64_C(0x9E3779B97F4A7C15));
  z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
  z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
  return z ^ (z >> 31);
}

/* Uniform in [0, 1): the top 53 bits scaled by 2^-53, exactly representable. */
static inline double prng_uniform(Prng *g) {
  return (double)(prng_next(g) >> 11) * 0x1.0p-53;
}

/* Uniform integer in [0, bound), 0 < bound <= 2^32 (multiply-shift of the top 32 bits; the
 * bias, below bound / 2^32, does not matter for test inputs). */
static inline uint32_t prng_below(Prng *g, uint64_t bound) {
  return (uint32_t)(((prng_next(g) >> 32) * bound) >> 32);
}

#endif
