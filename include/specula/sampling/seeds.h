#pragma once
// Seeded random streams: one independent stream of uniform numbers per (seed, index), so that work
// split into blocks, pixels or threads draws the same numbers however it is scheduled.
#include <cstdint>

namespace specula::sampling {

/// SplitMix64 (Steele, Lea & Flood 2014, "Fast Splittable Pseudorandom Number Generators"): the
/// state advanced by the golden gamma, then mixed.
constexpr std::uint64_t splitmix64(std::uint64_t x) noexcept {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// The key of stream `index` of the sequence `seed`.
constexpr std::uint64_t stream_key(std::uint64_t seed, std::uint64_t index) noexcept {
  return splitmix64(splitmix64(seed) + index);
}

/// The SplitMix64 generator started at a stream's key: uniform doubles in [0, 1) of 53 bits.
class SplitMixStream {
 public:
  explicit constexpr SplitMixStream(std::uint64_t key) noexcept : state_(key) {}

  constexpr double uniform() noexcept {
    const std::uint64_t bits = splitmix64(state_);
    state_ += 0x9e3779b97f4a7c15ULL;
    return double(bits >> 11) * 0x1p-53;
  }

 private:
  std::uint64_t state_;
};

}  // namespace specula::sampling
