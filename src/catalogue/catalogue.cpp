// The model catalogue (catalogue/catalogue.h): the built-in models of every family
// (include/specula/families/), then those registered from model files, and M+ms for any of them.
#include "specula/catalogue/catalogue.h"

#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <map>
#include <mutex>
#include <span>

#include "specula/analysis/energy.h"
#include "specula/analysis/fresnel.h"
#include "specula/exceptions.h"
#include "specula/families/families.h"
#include "specula/catalogue/model_file.h"

namespace specula {
namespace {

/// A lobe model's k at parameter values `p`, as its normalization says.
double lobe_coefficient(const families::Family& family, const families::ModelDefinition& model,
                        std::span<const double> p) {
  switch (model.normalization) {
    case Normalization::exact: return family.closed_form.in(model.form)(p[0]);
    case Normalization::formula: return model.coef(p[0]);
    case Normalization::none:
    case Normalization::quadrature: break;  // quadrature: user lobes only
  }
  return 1;
}

/// The registry entry of one model of a built-in family (families/<family>.h).
ModelInfo builtin_info(const families::Family& family, const families::ModelDefinition& model) {
  ModelInfo info{std::string(model.id), std::string(model.name), std::string(model.summary),
                 std::string(model.source), family.kind, model.form, model.normalization,
                 std::string(model.coef_text), {}, {}, nullptr, {}};
  for (const auto& p : families::params_of(family, model))
    info.params.push_back({std::string(p.name), p.default_value, p.min, p.max, p.min_exclusive, std::string(p.meaning)});
  if (family.kind == ModelKind::brdf)
    info.make = [&model](std::span<const double> p) -> ModelImpl { return model.make_brdf(p); };
  else
    info.make = [&family, &model](std::span<const double> p) -> ModelImpl {
      return LobeModel{family.make_lobe(p), model.form, lobe_coefficient(family, model, p)};
    };
  return info;
}

std::deque<ModelInfo> build_catalogue() {
  std::deque<ModelInfo> catalogue;
  for (const families::Family* family : families::kFamilies)
    for (const auto& model : family->models) catalogue.push_back(builtin_info(*family, model));
  return catalogue;
}

struct Catalogue {
  std::deque<ModelInfo> models = build_catalogue();
  const std::size_t builtin_count = models.size();
};

Catalogue& catalogue() {
  static Catalogue c;
  return c;
}

/// The compensated models looked up so far ("M+ms", "M+cycles", …: models/compensated.h), by id.
struct CompensatedInfos {
  std::mutex mutex;
  std::map<std::string, std::unique_ptr<const ModelInfo>, std::less<>> infos;
};

CompensatedInfos& compensated_infos() {
  static CompensatedInfos c;
  return c;
}

/// M with F ≡ 1, the model of M's energy table: M itself at F0 = 1 where that makes F ≡ 1 (Schlick's
/// F0, Cook-Torrance 1982's dielectric); else the first model of M's family (its Schlick F0 one:
/// families/fresnel.h) at M's roughness and F0 = 1. M itself where it has no Fresnel.
Model white_model(const std::shared_ptr<const ModelInfo>& base, ParamValues params,
                  const std::optional<fresnel::Channel>& f) {
  if (!f || f->is_one()) return make_model(base, params);
  if (base->find_param("f0")) {
    params["f0"] = 1;
    Model at_one = make_model(base, params);
    if (const auto g = fresnel_of(at_one); g && g->is_one()) return at_one;
  }
  const families::Family* family = families::family_of(*base);
  const std::string roughness(base->params.front().name);
  const std::string white(family ? family->models.front().id : std::string_view(base->id));
  return make_model(white, {{roughness, params.at(roughness)}, {"f0", 1}});
}

/// The F_s of a scaled scheme with a constant one (models/compensated.h), from M's Fresnel `f` and
/// its white table's E_avg.
double scale_fresnel(CompensationScheme scheme, const fresnel::Channel& f, double e_avg) {
  const double f_avg = analysis::fresnel_average(f).value;
  switch (scheme) {
    case CompensationScheme::turquin_f0: return f(1.0);
    case CompensationScheme::turquin_favg: return f_avg;
    case CompensationScheme::cycles: return cycles_fresnel(f_avg, e_avg);
    default: return 1;
  }
}

/// The table and Fresnel factor of M compensated by `scheme` (models/compensated.h). M+ms for GGX
/// with any Fresnel below 1: the random walk's own multiply scattered albedo (analysis::ggx_walk_table
/// at analysis::walk_equivalent_f0), F_ms = 1.
/// Every other case: the cached energy table of M with F = 1 (analysis/energy.h: the table is M's
/// albedo, which is why the catalogue sits above analysis), and the scheme's factor from M's
/// Fresnel (F ≡ 1 where M has none).
Compensated compensation_of(const ModelInfo& base, const ParamValues& params, std::shared_ptr<const Model> model,
                            CompensationScheme scheme) {
  const std::shared_ptr<const ModelInfo> listed(std::shared_ptr<const ModelInfo>(), &base);
  const std::optional<fresnel::Channel> f = fresnel_of(*model);
  if (const auto* ggx = f ? std::get_if<Ggx>(&model->brdf()) : nullptr; ggx && scheme == CompensationScheme::shipped)
    if (const double f0 = analysis::walk_equivalent_f0(ggx->fresnel); f0 < 1)
      return {scheme, std::move(model), std::make_shared<const EnergyTable>(analysis::ggx_walk_table(ggx->alpha, f0)),
              1.0, std::nullopt};
  auto table = analysis::cached_energy_table(white_model(listed, params, f));
  Compensated c{scheme, std::move(model), std::move(table), 1.0, std::nullopt};
  if (!f) return c;
  if (scheme == CompensationScheme::turquin_f)
    c.fresnel = *f;
  else if (scales(scheme))
    c.fresnel_scale = scale_fresnel(scheme, *f, c.table->e_avg);
  else
    c.fresnel_scale = kulla_conty_fresnel(analysis::fresnel_average(*f).value, c.table->e_avg);
  return c;
}

/// What each scheme's model is called and says of itself.
struct SchemeText {
  const char* name;     ///< appended to M's name
  const char* summary;  ///< after "M with "
  const char* source;
};

constexpr SchemeText scheme_text(CompensationScheme scheme) noexcept {
  switch (scheme) {
    case CompensationScheme::shipped:
      return {" + multiple scattering", "energy compensation: the random walk's multiple scattering (GGX, F0 < 1), else Kulla-Conty's",
              "Kulla & Conty 2017; Heitz et al. 2016"};
    case CompensationScheme::kulla_conty:
      return {" + Kulla-Conty", "Kulla-Conty's added lobe, F_ms = F_avg^2 E_avg / (1 - F_avg (1 - E_avg))", "Kulla & Conty 2017"};
    case CompensationScheme::turquin_f0:
      return {" scaled by Turquin (F0)", "Turquin's scale 1 + F0 (1 - E)/E at N.V (Filament, three.js, Unreal); not reciprocal",
              "Turquin 2019"};
    case CompensationScheme::turquin_f:
      return {" scaled by Turquin (F)", "Turquin's scale with F(N.V): 1 + F (1 - E)/E (libbsdl); not reciprocal", "Turquin 2019"};
    case CompensationScheme::turquin_favg:
      return {" scaled by Turquin (F_avg)", "Turquin's scale with F_avg: 1 + F_avg (1 - E)/E (MaterialX); not reciprocal",
              "Turquin 2019"};
    case CompensationScheme::cycles:
      return {" scaled as Cycles", "Cycles' albedo scaling 1 + F_ms (1 - E)/E, F_ms = F_avg E_avg / (1 - F_avg (1 - E_avg)); not reciprocal",
              "Blender Cycles (microfacet_ggx_preserve_energy)"};
  }
  return {"", "", ""};
}

/// M compensated by `scheme`: M's parameters; made as M at the same values with compensation_of's
/// table and factor.
ModelInfo compensated_info(const ModelInfo& base, CompensationScheme scheme) {
  const SchemeText text = scheme_text(scheme);
  ModelInfo info{base.id + std::string(suffix_of(scheme)), base.name + text.name,
                 fmt::format("{} with {}", base.id, text.summary), base.source + "; " + text.source, ModelKind::brdf,
                 base.form, Normalization::none, "1", base.params, {}, nullptr, base.origin};
  info.make = [&base, scheme](std::span<const double> values) -> ModelImpl {
    ParamValues params;
    for (std::size_t i = 0; i < values.size(); ++i) params[base.params[i].name] = values[i];
    // Registry entries live as long as the process (user ones until cleared, with this entry).
    const std::shared_ptr<const ModelInfo> listed(std::shared_ptr<const ModelInfo>(), &base);
    return compensation_of(base, params, std::make_shared<const Model>(make_model(listed, params)), scheme);
  };
  return info;
}

const ModelInfo* find_listed(std::string_view id) noexcept {
  for (const auto& m : models())
    if (m.id == id) return &m;
  return nullptr;
}

const ModelInfo* find_compensated(std::string_view id) noexcept {
  const ModelInfo* base = find_listed(compensated_base_id(id));
  if (!base || !compensated_base_id(base->id).empty()) return nullptr;  // no M+ms+ms
  CompensatedInfos& c = compensated_infos();
  const std::lock_guard lock(c.mutex);
  auto found = c.infos.find(id);
  if (found == c.infos.end())
    found = c.infos.emplace(std::string(id), std::make_unique<const ModelInfo>(compensated_info(*base, compensation_scheme_of(id)))).first;
  return found->second.get();
}

}  // namespace

std::optional<fresnel::Channel> fresnel_of(const Model& model) {
  if (model.is_lobe() || model.compensated() || !model.info().is_builtin()) return std::nullopt;
  const FullBrdf& brdf = model.brdf();
  if (const auto* m = std::get_if<Ggx>(&brdf)) return m->fresnel;
  if (const auto* m = std::get_if<Beckmann>(&brdf)) return m->fresnel;
  if (const auto* m = std::get_if<CookTorrance>(&brdf)) return fresnel::Channel{fresnel::Kind::schlick, m->f0};
  if (const auto* m = std::get_if<CookTorrance1982>(&brdf)) {
    if (m->f0 >= 1) return fresnel::Channel{};
    const double r = std::sqrt(m->f0);
    return fresnel::Channel{.kind = fresnel::Kind::dielectric, .eta = (1 + r) / (1 - r)};
  }
  return std::nullopt;
}

const std::deque<ModelInfo>& models() { return catalogue().models; }

void register_models(std::vector<ModelInfo> infos) {
  for (std::size_t i = 0; i < infos.size(); ++i) {
    const std::string origin = to_string(infos[i].origin);
    if (const ModelInfo* taken = find_model(infos[i].id))
      throw InvalidArgument(fmt::format("{}: model id '{}' is already taken ({})", origin, infos[i].id,
                                        taken->is_builtin() ? "a built-in model" : to_string(taken->origin)));
    for (std::size_t j = 0; j < i; ++j)
      if (infos[j].id == infos[i].id)
        throw InvalidArgument(fmt::format("{}: model id '{}' is defined twice (first at {})", origin, infos[i].id,
                                          to_string(infos[j].origin)));
  }
  for (auto& info : infos) catalogue().models.push_back(std::move(info));
}

void clear_registered_models() {
  {
    CompensatedInfos& compensated = compensated_infos();
    const std::lock_guard lock(compensated.mutex);
    std::erase_if(compensated.infos, [](const auto& entry) { return !entry.second->is_builtin(); });
  }
  analysis::clear_energy_tables();
  auto& c = catalogue();
  c.models.erase(c.models.begin() + static_cast<std::ptrdiff_t>(c.builtin_count), c.models.end());
}

const ModelInfo* find_model(std::string_view id) noexcept {
  if (const ModelInfo* listed = find_listed(id)) return listed;
  try {
    return find_compensated(id);
  } catch (...) {  // out of memory: as unknown
    return nullptr;
  }
}

namespace {

std::string model_ids() {
  std::vector<std::string_view> ids;
  for (const auto& m : models()) ids.push_back(m.id);
  return fmt::format("{}; any of them compensated: ID{} (or ID{})", fmt::join(ids, ", "), kCompensatedSuffix,
                     fmt::join(std::span(kCompensationSuffixes).subspan(1), ", ID"));
}

}  // namespace

std::shared_ptr<const ModelInfo> model_definition(std::string_view id, const ParamValues& params) {
  if (is_inline_model(id)) return inline_model(id, params);
  const ModelInfo* info = find_model(id);
  if (!info) throw InvalidField("model", fmt::format("unknown model '{}' (known: {})", id, model_ids()));
  // Registry entries live as long as the process: shared without ownership.
  return std::shared_ptr<const ModelInfo>(std::shared_ptr<const ModelInfo>(), info);
}

Model make_model(std::string_view id, const ParamValues& params, std::optional<Form> form) {
  return make_model(model_definition(id, params), params, form);
}

}  // namespace specula
