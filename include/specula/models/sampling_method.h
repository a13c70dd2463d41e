#pragma once
// How a model family is importance-sampled (docs/sampling.md): the method each family states in its
// header (families/family.h, `sampling`), read by sampling::Sampler. Vocabulary, below the
// families: the samplers themselves are in sampling/.
#include <cstddef>

#include "specula/exceptions.h"

namespace specula::sampling {

enum class Method {
  /// A tabulated inverse CDF of the lobe in y = −ln cos (angle from its axis), built when the
  /// sampler is made, with a cosine-weighted share mixed in for the tail the table leaves out.
  /// Every user-defined model is sampled this way.
  tabulated,
  /// pdf (n + 1)/(2π) cosⁿ about the lobe's axis: cos = u^(1/(n+1)) (Lafortune & Willems 1994).
  power_cosine,
  /// The log lobe's own density in t = −n log₂ cos: Newton on its closed-form CDF (docs/math.md §3).
  log_t_space,
  /// Beckmann's D(H) cos θ_H: tan²θ_H = −α² ln(1 − u) (Walter et al. 2007; Walter 2005 for Ward).
  beckmann,
  /// GGX's visible normals seen from the light (Heitz 2018).
  ggx_visible_normals,
  /// Cosine-weighted over the hemisphere (Lambert).
  cosine,
};
inline constexpr std::size_t kMethodCount = static_cast<std::size_t>(Method::cosine) + 1;  // cosine: the last

constexpr const char* to_string(Method method) noexcept {
  switch (method) {
    case Method::tabulated: return "tabulated inverse CDF";
    case Method::power_cosine: return "power-cosine (closed form)";
    case Method::log_t_space: return "log lobe in t-space (Newton on the closed-form CDF)";
    case Method::beckmann: return "Beckmann D·cos (closed form)";
    case Method::ggx_visible_normals: return "GGX visible normals (Heitz 2018)";
    case Method::cosine: return "cosine-weighted";
  }
  return "";
}
static_assert(names_complete<Method, kMethodCount>([](Method m) { return to_string(m); }));

}  // namespace specula::sampling
