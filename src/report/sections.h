#pragma once
// The report's sections, in page order. Each computes its data with the library, writes its
// tables and figures through the Context, and records what the claims table checks.
#include <optional>
#include <vector>

#include "context.h"
#include "specula/models/model.h"
#include "specula/render/panel.h"

namespace specula::report {

/// n from 1 to 1000, log-spaced (`count` values, ends included).
std::vector<double> log_spaced(double lo, double hi, int count);

// The paper, figure by figure (docs/math.md §5).
Section lobes_section(Context& context);          ///< Figs. 2-4: the lobes and their errors vs c^n
Section normalization_section(Context& context);  ///< Figs. 5, 8, 9: the table, the fit, Δ(n)
Section shader_section(Context& context);         ///< Figs. 10-11: the GLSL and the spheres

// Beyond the paper.
Section energy_section(Context& context);        ///< albedo ρ(θ_i), conservation table, polar plots
Section compensation_section(Context& context);  ///< which energy compensation is right: against the walk
Section fitted_norms_section(Context& context);  ///< exact vs fitted k; fits where no closed form
Section cost_section(Context& context);          ///< evaluation cost against accuracy
Section differences_section(Context& context);   ///< log lobes against Blinn-Phong, as images
Section designed_section(Context& context);      ///< the lobe designer on the paper's problem
Section engine_terms_section(Context& context);  ///< the designer on Fresnel, Smith G₂ and the split sum

/// The default comparison sphere (render::default_scene) shaded with `model`, size × size pixels.
render::Image sphere(const Model& model, int size);
/// Composes the panels (render::compose_comparison), writes name.png and returns its <figure>.
std::string panel_figure(Context& context, const std::string& name, const std::vector<render::LabelledImage>& panels,
                         const std::optional<render::HeatMaps>& heat_maps, const std::string& caption,
                         const std::string& command);

/// Each claim of the paper with specula's verdict, from context.findings (runs last, shown first).
Section claims_section(const Context& context);

}  // namespace specula::report
