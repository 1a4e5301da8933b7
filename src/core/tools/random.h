// The one random generator of the project (scenes, tests, fuzzers, soak checker): splitmix64
// (Steele, Lea & Flood, "Fast splittable pseudorandom number generators", 2014). Tiny, fast and
// bit for bit the same on every platform, unlike the std:: distributions, whose output each
// standard library defines its own way; a scene or test case is reproducible from its seed.
#pragma once

#include <cstdint>

namespace sap_broadphase {

class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t inSeed) : state_(inSeed) {}
  /// The next 64 random bits.
  uint64_t bits() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1): the top 53 bits, so every value is a multiple of 2^-53.
  double unit() { return static_cast<double>(bits() >> 11) * 0x1.0p-53; }
  /// Uniform in [inLow, inHigh).
  double between(double inLow, double inHigh) { return inLow + (inHigh - inLow) * unit(); }
  /// Uniform integer in [0, inBound) (0 when inBound is 0; the modulo bias is negligible for
  /// the small bounds used here).
  uint64_t below(uint64_t inBound) { return inBound == 0 ? 0 : bits() % inBound; }
  /// True with probability inChance.
  bool chance(double inChance) { return unit() < inChance; }

 private:
  uint64_t state_;
};

}  // namespace sap_broadphase
