// SplitMix64 (Steele, Lea, Flood 2014): a fixed, portable sequence of 64-bit
// numbers from a seed, unlike the standard library's distributions, whose
// output differs between implementations. The game draws its passes and the
// report its random scenes with it. FNV-1a (64-bit): a fixed digest of a
// text, for the game's pitch fingerprint and an atlas spec's identity.
#pragma once

#include <cstdint>
#include <string_view>

namespace contact2d {

inline std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// Uniform in [0, 1): the top 53 bits.
inline double next_uniform(std::uint64_t& state) {
  return static_cast<double>(splitmix64(state) >> 11) * 0x1.0p-53;
}

// FNV-1a, 64-bit: offset basis 14695981039346656037, prime 1099511628211.
inline std::uint64_t fnv1a(std::string_view bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace contact2d
