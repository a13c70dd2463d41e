#pragma once
// The analysis endpoints: each reads its JSON body (throwing InvalidField naming a bad field),
// runs the shared query the CLI runs, and returns the JSON text of the answer.
#include <string>
#include <string_view>

#include "specula/serve/api.h"

namespace specula::serve {

std::string models_endpoint();
/// The designer's engine terms (design::terms()): id, formula, variables, param, range, summary
/// and their reference rows (id, formula, source).
std::string terms_endpoint();
std::string eval_endpoint(std::string_view body, const Limits& limits);
/// f at Rusinkiewicz's half/difference angles: theta_h × theta_d at phi_d (default 90°).
std::string slice_endpoint(std::string_view body, const Limits& limits);
/// check --sampling at one angle: the χ² verdict, the observed and expected histograms, sampled directions.
/// f over the outgoing hemisphere at the incident θ_i: theta_o (default 0:90@46) × phi_o
/// (default 0:355@72) in degrees, {"theta_o_deg", "phi_o_deg", "values": [[f per φ_o] per θ_o]}.
std::string hemisphere_endpoint(std::string_view body, const Limits& limits);
/// Each published energy compensation's albedo against the random walk's at the μ values (default
/// 0.05 … 1) for a GGX model with its Fresnel (queries::verdict's cells for that one α and Fresnel).
std::string compensation_endpoint(std::string_view body, const Limits& limits);
std::string sampling_endpoint(std::string_view body, const Limits& limits);
std::string normalize_endpoint(std::string_view body, const Limits& limits);
std::string albedo_endpoint(std::string_view body, const Limits& limits);
std::string check_endpoint(std::string_view body, const Limits& limits);
std::string error_endpoint(std::string_view body, const Limits& limits);
std::string glsl_endpoint(std::string_view body, const Limits& limits);

}  // namespace specula::serve
