#pragma once
// The first kDimensions of Sobol's sequence (Joe & Kuo 2008, new-joe-kuo-6.21201 direction
// numbers), each block of the walk taking its points 0 … 2^kBits − 1 under a random digital shift
// (an XOR per dimension): the block's points stay a (t, m, s)-net, so they stratify the first two
// bounces, and each block's mean is an unbiased estimate independent of the other blocks'.
#include <array>
#include <cstdint>

namespace specula::walk::detail {

inline constexpr int kSobolDimensions = 7;
inline constexpr int kSobolBits = 16;  // points per block at most 2^16

class SobolNet {
 public:
  constexpr SobolNet() noexcept {
    // s, a and m₁ … m_s of dimensions 2 … 7 (dimension 1 is the van der Corput sequence).
    struct Poly {
      int s;
      unsigned a;
      std::array<std::uint32_t, 4> m;
    };
    constexpr std::array<Poly, kSobolDimensions - 1> polys{{
        {1, 0, {1}}, {2, 1, {1, 3}}, {3, 1, {1, 3, 1}}, {3, 2, {1, 1, 1}}, {4, 1, {1, 1, 3, 3}}, {4, 4, {1, 3, 5, 13}}}};
    for (int b = 0; b < kSobolBits; ++b) v_[0][b] = std::uint32_t{1} << (31 - b);
    for (int d = 1; d < kSobolDimensions; ++d) {
      const Poly& p = polys[d - 1];
      std::array<std::uint32_t, kSobolBits> m{};
      for (int k = 0; k < kSobolBits; ++k) {
        if (k < p.s) {
          m[k] = p.m[k];
          continue;
        }
        // m_k = 2a₁m_{k−1} ⊕ 4a₂m_{k−2} ⊕ … ⊕ 2^s m_{k−s} ⊕ m_{k−s} (Bratley & Fox 1988).
        std::uint32_t next = m[k - p.s] ^ (m[k - p.s] << p.s);
        for (int j = 1; j < p.s; ++j)
          if ((p.a >> (p.s - 1 - j)) & 1u) next ^= m[k - j] << j;
        m[k] = next;
      }
      for (int b = 0; b < kSobolBits; ++b) v_[d][b] = m[b] << (31 - b);
    }
  }

  /// Coordinate d of point i under the shift, in (0, 1).
  double at(std::uint32_t i, int d, std::uint32_t shift) const noexcept {
    std::uint32_t x = 0;
    for (int b = 0; i; ++b, i >>= 1)
      if (i & 1u) x ^= v_[d][b];
    return (double(x ^ shift) + 0.5) * 0x1p-32;
  }

 private:
  std::array<std::array<std::uint32_t, kSobolBits>, kSobolDimensions> v_{};
};

}  // namespace specula::walk::detail
