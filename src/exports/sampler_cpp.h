#pragma once
// Private to src/exports: the C++ header's sample() and pdf(), sampling::Sampler's algorithms for
// the model written out (its tables as arrays).
#include <string>

#include "specula/models/model.h"

namespace specula::exports {

/// The sampler's C++, both parts inside the header's namespace: `prelude`, first, is the text of
/// include/specula/lobes/portable/directions.h (and radial.h where a radial density is drawn
/// from) in a namespace `radial`; `body`, after f, defines `Sample`, `sample(wi, u1, u2)` and `pdf(wi, wo)` with
/// sampling::Sampler's conventions and numbers for `model`; for M+ms, M's sampler (in namespace
/// `base`) mixed with cosine-weighted sampling by the energy table.
struct CppSampler {
  std::string prelude;
  std::string body;
};
CppSampler cpp_sampler(const Model& model);

}  // namespace specula::exports
