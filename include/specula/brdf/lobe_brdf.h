#pragma once
// A lobe used as a BRDF: f = k·F(R·V) in `rv` form, f = k·F(N·H) in `nh` form (docs/math.md §1).
#include "specula/brdf/directions.h"
#include "specula/lobes/lobe.h"

namespace specula {

/// The cosine a lobe sees in the given form; 0 when L or V is below the surface.
template <std::floating_point T>
T form_cosine(Form form, const Vec3T<T>& n, const Vec3T<T>& l, const Vec3T<T>& v) noexcept {
  if (dot(n, l) <= T(0) || dot(n, v) <= T(0)) return T(0);
  return form == Form::rv ? dot(reflect(l, n), v) : dot(n, half_vector(l, v));
}

template <class Lobe>
struct LobeBrdf {
  Lobe lobe;
  Form form = Form::rv;
  double k = 1;  ///< normalizing coefficient

  template <std::floating_point T>
  T operator()(const Vec3T<T>& n, const Vec3T<T>& l, const Vec3T<T>& v) const noexcept {
    return T(k) * lobe(form_cosine(form, n, l, v));
  }
};

}  // namespace specula
