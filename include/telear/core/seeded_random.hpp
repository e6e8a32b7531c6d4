#pragma once
// The one seeded generator of telear: splitmix64 (Steele, Lea and Flood, "Fast splittable
// pseudorandom number generators", OOPSLA 2014). Its outputs are the same on every platform
// and compiler, which the std distributions are not: IK restarts, the renderer's sensor noise
// and anything else that must repeat from a seed draws from here. Not for secrets.

#include <cstdint>

namespace telear::core {

// Advances `state` and returns the next 64 random bits.
constexpr std::uint64_t next_random(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// Uniform in [0, 1) with 53 random bits; advances `state`.
constexpr double uniform01(std::uint64_t& state) {
  return static_cast<double>(next_random(state) >> 11) * 0x1.0p-53;
}

// `seed` mixed into well-spread bits (the first output of a generator seeded with it): derives
// independent seeds from related ones, e.g. one per frame and eye.
constexpr std::uint64_t mix_seed(std::uint64_t seed) {
  return next_random(seed);
}

}  // namespace telear::core
