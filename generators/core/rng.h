// Small deterministic random numbers. std:: distributions differ between standard libraries,
// so every random choice of a generator goes through this: same seed -> same tree everywhere.
#pragma once
#include <cstdint>

namespace forest {

// SplitMix64 finalizer: a good bit mixer, also used to derive independent stream seeds.
inline uint64_t mix64(uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// Stateless hash of up to three integers: lattice noise and per-item variation.
inline uint64_t hash64(uint64_t a, uint64_t b = 0, uint64_t c = 0) {
  return mix64(mix64(mix64(a) ^ b) ^ c);
}

// PCG32 (XSH RR), seeded through SplitMix64 so nearby seeds give unrelated streams.
// `stream` separates the passes of one generator (rewriting, turtle, leaves...), so adding a
// random draw to one pass does not shift the numbers of another.
struct Rng {
  uint64_t state = 0;
  uint64_t inc = 1;

  explicit Rng(uint64_t seed, uint64_t stream = 0) {
    inc = (mix64(stream ^ 0xDA3E39CB94B95BDBull) << 1u) | 1u;
    state = 0;
    next_u32();
    state += mix64(seed);
    next_u32();
  }

  uint32_t next_u32() {
    uint64_t old = state;
    state = old * 6364136223846793005ull + inc;
    uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = uint32_t(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }
  // Uniform in [0, 1) with 53 random bits.
  double uniform() {
    uint64_t hi = next_u32(), lo = next_u32();
    return double(((hi << 32) | lo) >> 11) * 0x1.0p-53;
  }
  // Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Uniform in [-1, 1): the unit of every "jitter" parameter.
  double symmetric() { return 2.0 * uniform() - 1.0; }
};

}  // namespace forest
