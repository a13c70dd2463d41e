// specula compare: spheres shaded with several models side by side, labelled, optionally with
// heat maps of each one's luminance difference against a reference model (the paper's Fig. 11).
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <iostream>
#include <map>
#include <set>

#include "cli.h"
#include "specula/catalogue/catalogue.h"
#include "specula/catalogue/model_file.h"
#include "specula/gl/render_gl.h"
#include "scene_options.h"
#include "specula/exceptions.h"
#include "specula/render/image_io.h"
#include "specula/render/panel.h"
#include "specula/render/render.h"

namespace specula::cli {
namespace {

struct CompareOptions {
  std::string models = "log-normalized,log,schlick";
  std::vector<std::string> params;
  std::string form;
  std::string diff;
  SceneOptions scene;  ///< --size, --light, the colours, --exposure, --tonemap
  std::optional<double> scale;
  std::string backend = "cpu";
  std::string out;
  bool quiet = false;
};

// The definition `id` names (InvalidField "unknown model …" listing the known ids); a bad inline
// definition's error after the option and the text it is in.
std::shared_ptr<const ModelInfo> definition_of(std::string_view option, const std::string& id) {
  try {
    return model_definition(id);
  } catch (const InvalidField& e) {
    if (!is_inline_model(id)) throw;
    throw InvalidArgument(fmt::format("{} '{}': {}", option, id, e.what()));
  }
}

std::vector<std::string> model_ids(const std::string& list) {
  std::vector<std::string> ids;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string id = list.substr(start, comma - start);
    if (id.empty()) throw InvalidArgument(fmt::format("--models '{}' has an empty model id", list));
    definition_of("--models", id);
    ids.push_back(id);
    start = comma + 1;
  }
  return ids;
}

// `id` (given to `option`) with the given parameters it has and the form if it is a lobe; `used`
// collects the names.
Model model_with(std::string_view option, const std::string& id, const ParamValues& values,
                 const std::optional<Form>& form, std::set<std::string>& used) {
  const auto definition = definition_of(option, id);  // an inline model's parameters: its formula's names
  ParamValues own;
  for (const auto& [name, value] : values)
    if (definition->find_param(name)) {
      own[name] = value;
      used.insert(name);
    }
  return make_model(id, own, definition->kind == ModelKind::lobe ? form : std::nullopt);
}

struct Models {
  std::vector<Model> panels;
  std::optional<Model> reference;
};

Models models_of(const CompareOptions& o) {
  if (o.models.empty()) throw InvalidArgument("--models is empty: name at least one model, e.g. --models log,schlick");
  ModelOptions parsed;
  parsed.params = o.params;
  const ParamValues values = parsed.param_values();
  const std::optional<Form> form = o.form.empty() ? std::nullopt : std::optional(parse_form(o.form));
  std::set<std::string> used;
  Models m;
  for (const auto& id : model_ids(o.models)) m.panels.push_back(model_with("--models", id, values, form, used));
  if (!o.diff.empty()) m.reference = model_with("--diff", o.diff, values, form, used);
  for (const auto& [name, value] : values)
    if (!used.contains(name))
      throw InvalidArgument(fmt::format("--param {}: no model in this comparison has a parameter '{}'", name, name));
  return m;
}

std::string parameters_text(const Model& m, std::string_view equals, std::string_view separator) {
  std::vector<std::string> parts;
  for (std::size_t i = 0; i < m.params().size(); ++i)
    parts.push_back(fmt::format("{}{}{}", m.info().params[i].name, equals, io::format_number(m.params()[i])));
  return fmt::format("{}", fmt::join(parts, separator));
}

// e.g. "log-normalized  n = 50", with "  (nh)" when --form chose the form.
std::string label_of(const Model& m, bool form_given) {
  std::string label = fmt::format("{}  {}", m.id(), parameters_text(m, " = ", ", "));
  if (form_given && m.is_lobe()) label += fmt::format("  ({})", to_string(m.form()));
  return label;
}

render::Scene scene_of(const Model& model, const CompareOptions& o) {
  render::Scene scene = render::make_scene(model, o.scene.description());
  render::validate(scene);
  return scene;
}

// Each distinct model id is rendered once (the same id has the same parameters here); the GL
// backend creates one context for all of them.
std::map<std::string, render::Image, std::less<>> render_all(const Models& m, const CompareOptions& o,
                                                             const render::RenderSettings& settings) {
  std::optional<gl::Context> context;
  std::optional<gl::Renderer> renderer;
  if (parse_backend(o.backend) == render::Backend::gl) renderer.emplace(context.emplace());
  std::map<std::string, render::Image, std::less<>> images;
  std::vector<const Model*> all;
  for (const auto& model : m.panels) all.push_back(&model);
  if (m.reference) all.push_back(&*m.reference);
  for (const Model* model : all) {
    if (images.contains(model->id())) continue;
    const render::Scene scene = scene_of(*model, o);
    images.emplace(std::string(model->id()),
                   renderer ? renderer->render(scene, settings) : render::render_cpu(scene, settings));
  }
  return images;
}

render::Metadata metadata_of(const Models& m, const CompareOptions& o, const render::Scene& scene, double scale_max) {
  std::vector<std::string> ids, params;
  for (const auto& model : m.panels) {
    ids.emplace_back(model.id());
    params.push_back(fmt::format("{}: {}", model.id(), parameters_text(model, "=", ",")));
  }
  render::Metadata meta{{"Software", "specula"},
          {"figure", "compare"},
          {"models", fmt::format("{}", fmt::join(ids, ","))},
          {"parameters", fmt::format("{}", fmt::join(params, "; "))},
          {"form", o.form.empty() ? "each model's own" : o.form},
          {"reference", m.reference ? std::string(m.reference->id()) : "-"},
          {"heatmap", m.reference ? "abs difference of linear luminance Y = 0.2126 R + 0.7152 G + 0.0722 B" : "-"},
          {"scale_max", m.reference ? io::format_number(scale_max) : "-"},
          {"renderer", o.backend},
          {"size", o.scene.size}};
  const render::Metadata lit = scene_metadata(scene);
  meta.insert(meta.end(), lit.begin(), lit.end());
  meta.insert(meta.end(), {{"exposure", io::format_number(o.scene.exposure)}, {"tonemap", o.scene.tone_map}});
  return meta;
}

std::string summary_line(const Model& model, const render::Image& image, const render::LuminanceDifference* d,
                         std::string_view reference) {
  double peak = 0, sum = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const double l = render::luminance(image.at(x, y));
      peak = std::max(peak, l);
      sum += l;
    }
  std::string line = fmt::format("{} ({}): luminance peak {:.4g}, mean {:.4g}", model.id(),
                                 parameters_text(model, "=", ","), peak, sum / (image.width() * image.height()));
  if (d) line += fmt::format("; |ΔL| vs {}: max {:.4g}, mean {:.4g}", reference, d->max, d->mean);
  return line;
}

// The output, the display and the heat maps' scale: what needs no model. Returns the display.
render::Display check_plain_options(const CompareOptions& o) {
  if (render::image_format(o.out) != render::ImageFormat::png)
    throw InvalidArgument(fmt::format("compare writes an 8-bit PNG: '{}' is not a .png file name", o.out));
  const render::Display display = o.scene.display();
  if (o.scale && o.diff.empty()) throw InvalidArgument("--scale sets the heat maps' scale: it needs --diff REF");
  if (o.scale && !(std::isfinite(*o.scale) && *o.scale > 0))
    throw InvalidArgument(fmt::format("--scale {} must be finite and > 0", *o.scale));
  return display;
}

// PanelGeometry refuses a figure too large to write: find out before rendering.
void check_figure_fits(const Models& m, const render::RenderSettings& settings) {
  [[maybe_unused]] const render::PanelGeometry geometry(static_cast<int>(m.panels.size()), settings.width, settings.height,
                                                        m.reference.has_value(), render::PanelLayout{});
}

void run_compare(const CompareOptions& o) {
  const render::Display display = check_plain_options(o);
  const render::RenderSettings settings = o.scene.settings();
  const Models m = models_of(o);
  const render::Scene scene = scene_of(m.panels.front(), o);  // checks lights and colours before any work
  check_figure_fits(m, settings);

  const auto images = render_all(m, o, settings);
  std::vector<render::LabelledImage> panels;
  for (const auto& model : m.panels) panels.push_back({images.find(model.id())->second, label_of(model, !o.form.empty())});
  std::optional<render::HeatMaps> heat_maps;
  if (m.reference)
    heat_maps = render::HeatMaps{images.find(m.reference->id())->second, o.scale,
                                 fmt::format("|ΔL| vs {}, linear luminance", m.reference->id())};
  const render::ComparisonPanel figure = render::compose_comparison(panels, display, {}, heat_maps);
  render::write_png(o.out, figure.image, metadata_of(m, o, scene, figure.scale_max));
  if (o.quiet) return;
  for (std::size_t i = 0; i < m.panels.size(); ++i)
    std::cout << summary_line(m.panels[i], panels[i].image, m.reference ? &figure.differences[i] : nullptr,
                              m.reference ? m.reference->id() : "")
              << '\n';
}

}  // namespace

void add_compare_command(CLI::App& app) {
  auto o = std::make_shared<CompareOptions>();
  auto* cmd = app.add_subcommand("compare", "Spheres shaded with several models side by side, with difference heat maps");
  cmd->add_option("--models", o->models, "Model ids, comma-separated (lobes and full BRDFs)")->capture_default_str();
  cmd->add_option("--param,-p", o->params,
                  "NAME=VALUE for every model that has the parameter, repeatable (e.g. -p n=50)");
  cmd->add_option("--form", o->form, "rv or nh for the lobe models; default: each model's own")
      ->check(one_of<Form, kFormCount>());
  cmd->add_option("--diff", o->diff, "Reference model id: add heat maps of each panel's |ΔL| against it");
  o->scene.add_to(*cmd, Picture::compare);
  cmd->add_option("--scale", o->scale, "Top of the heat maps' colour scale (default: the largest |ΔL| shown)");
  cmd->add_option("--backend", o->backend, "cpu (the reference renderer) or gl (OpenGL through EGL: a GPU, or Mesa's llvmpipe)")
      ->capture_default_str()
      ->check(one_of<render::Backend, render::kBackendCount>());
  cmd->add_option("--out,-o", o->out, "Output image FILE.png (8-bit sRGB)")->required();
  cmd->add_flag("--quiet,-q", o->quiet, "Print nothing on success");
  cmd->footer(
      "Each model shades the default sphere (as `specula render`) with the same lights and material;\n"
      "labels name the model and its parameters. With --diff, a second row shows per pixel |ΔL|, the\n"
      "absolute difference of linear luminance Y = 0.2126 R + 0.7152 G + 0.0722 B against the reference,\n"
      "in viridis on one shared scale, with a colour bar. Prints one summary line per model. Examples:\n"
      "  specula compare --out fig11.png                       # log-normalized, log, schlick at n = 20\n"
      "  specula compare -p n=50 --diff log-normalized --out fig11-diff.png\n"
      "  specula compare --models phong-normalized,ggx -p n=100 -p alpha=0.15 --size 256x256 --out pair.png");
  cmd->callback([o] { run_compare(*o); });
}

}  // namespace specula::cli
