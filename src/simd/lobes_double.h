#pragma once
// The double-array half of the batch lobe evaluation (lobes_double.cpp), for lobes.cpp's API.
#include <cstddef>

#include "specula/simd/lobes.h"

namespace specula::simd {

/// out[i] = the lobe at c[i], i < count, by the best kernel of this CPU (not the formula family).
void eval_lobe_double(const LobeSpec& lobe, Tier tier, const double* c, std::size_t count, double* out) noexcept;

/// The double kernel's vector operations per value on this CPU's target.
double ops_per_value_double(const LobeSpec& lobe, Tier tier);

}  // namespace specula::simd
