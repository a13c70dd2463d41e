#pragma once
// Private to src/exports: the C++ header's sample() and pdf(), sampling::Sampler's algorithms for
// the model written out (its tables as arrays).
#include <string>

#include "specula/models/model.h"

namespace specula::exports {

/// C++ (inside the header's namespace, after f) defining `Sample`, `sample(wi, u1, u2)` and
/// `pdf(wi, wo)` with sampling::Sampler's conventions and numbers for `model`; for M+ms, M's
/// sampler (in namespace `base`) mixed with cosine-weighted sampling by the energy table.
std::string cpp_sampler(const Model& model);

}  // namespace specula::exports
