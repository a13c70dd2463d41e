#include "specula/design/output.h"

#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "specula/catalogue/catalogue.h"
#include "specula/fit/fit.h"
#include "specula/io/files.h"

namespace specula::design {

namespace {

// Full precision: a rounded maximum could understate it.
std::string number(double v) { return std::isfinite(v) ? fmt::format("{:.17g}", v) : std::string(); }

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string toml_string(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

double log_ns(const Result& r) {
  for (const auto& l : r.references)
    if (l.id == "log") return l.ns_per_eval;
  return NAN;
}

// A member's normalization: its k(p) in closed form, else "quadrature"; empty for references.
std::string normalization_of(const Lobe& l) {
  if (l.reference) return {};
  return l.k_formula.empty() ? "quadrature" : l.k_formula;
}

std::string row(const Lobe& l, double log) {
  return fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", csv_field(l.id), l.reference ? "reference" : "member",
                     csv_field(l.formula), number(l.max_abs), number(l.argmax_c), number(l.argmax_param),
                     number(l.max_rel), number(l.ns_per_eval), number(l.ns_per_eval / log),
                     l.ops > 0 ? std::to_string(l.ops) : std::string(), number(l.spirv_instructions),
                     l.reference ? std::string() : std::to_string(l.model_cost), csv_field(l.shape), csv_field(l.timing),
                     number(l.k), csv_field(l.check), csv_field(normalization_of(l)));
}

// A member's formula with constants to 6 digits (the files hold them in full).
std::string shown(const Lobe& l) {
  if (l.reference) return l.formula;
  return expr::to_infix(fit::rounded(expr::parse(l.formula), 6));
}

}  // namespace

std::string front_csv(const Result& result) {
  std::string out =
      "id,kind,formula,max_abs_error,argmax_c,argmax_param,max_rel_error,ns_per_eval,cost_vs_log,ops,"
      "spirv_instructions,model_cost,shape,timing,k,check,normalization\n";
  const double log = log_ns(result);
  for (const auto& l : result.front) out += row(l, log);
  for (const auto& l : result.references) out += row(l, log);
  return out;
}

MemberModel member_model(const Result& result, const Lobe& l, bool normalized) {
  const Settings& s = result.settings;
  return {normalized ? l.id + "-normalized" : l.id,
          fmt::format("designed lobe {}{}", l.id, normalized ? ", normalized" : ""),
          fmt::format("max |F − {}| = {:.4g} over {} in [{:g}, {:g}]", s.target, l.max_abs, s.param, s.lo, s.hi),
          target_form(s),
          l.formula,
          normalized ? normalization_of(l) : "none",
          s.param,
          timing_param(s),
          s.lo,
          s.hi};
}

std::string models_toml(const Result& result) {
  const Settings& s = result.settings;
  std::string out = fmt::format("# Lobes designed by specula design against {} over {} in [{:g}, {:g}] ({}).\n",
                                s.target, s.param, s.lo, s.hi, to_string(s.objective));
  for (const auto& l : result.front) {
    for (bool normalized : {false, true}) {
      const MemberModel m = member_model(result, l, normalized);
      out += fmt::format(
          "\n[[model]]\nid = {}\nname = {}\nsource = \"specula design\"\nsummary = {}\nkind = \"lobe\"\nform = \"{}\"\n"
          "lobe = {}\nnormalization = {}\n[model.params.{}]\ndefault = {:.17g}\nmin = {:.17g}\nmax = {:.17g}\n",
          toml_string(m.id), toml_string(m.name), toml_string(m.summary), to_string(m.form), toml_string(m.lobe),
          toml_string(m.normalization), m.param, m.default_value, m.min, m.max);
    }
  }
  return out;
}

std::string front_table(const Result& result) {
  std::string out = fmt::format("{:<22} {:>10} {:>10} {:>9} {:>8} {:>4} {:>6} {:>6}  {}\n", "id", "max_abs", "max_rel",
                                "ns/eval", "vs log", "ops", "spirv", "check", "formula");
  const double log = log_ns(result);
  const auto line = [&](const Lobe& l) {
    out += fmt::format("{:<22} {:>10.4g} {:>10.4g} {:>9} {:>8} {:>4} {:>6} {:>6}  {}\n", l.id, l.max_abs, l.max_rel,
                       std::isfinite(l.ns_per_eval) ? fmt::format("{:.3f}", l.ns_per_eval) : "-",
                       std::isfinite(l.ns_per_eval / log) ? fmt::format("{:.2f}", l.ns_per_eval / log) : "-",
                       l.ops > 0 ? std::to_string(l.ops) : "-",
                       std::isfinite(l.spirv_instructions) ? fmt::format("{:g}", l.spirv_instructions) : "-",
                       l.reference || l.check.empty() ? "-" : l.check == "pass" ? "pass" : "FAIL", shown(l));
  };
  for (const auto& l : result.front) line(l);
  out += "references:\n";
  for (const auto& l : result.references) line(l);
  for (const auto& l : result.front)
    if (!l.check.empty() && l.check != "pass") out += fmt::format("{}: check {}\n", l.id, l.check);
  return out;
}

std::string design_json(const Result& result) {
  const Settings& s = result.settings;
  nlohmann::json ops = nlohmann::json::array();
  for (Operation op : s.operations) ops.push_back(to_string(op));
  nlohmann::json j{{"target", s.target}, {"params", s.params}, {"form", s.form ? to_string(*s.form) : ""},
                   {"param", s.param}, {"lo", s.lo}, {"hi", s.hi}, {"objective", to_string(s.objective)},
                   {"zone", s.zone}, {"ops", ops}, {"max_cost", s.max_cost}, {"seed", s.seed},
                   {"shard", s.shard}, {"shards", s.shards}, {"forms_screened", result.forms_screened},
                   {"forms_total", result.forms_total}, {"stopped", result.cancelled},
                   {"members", nlohmann::json::array()}};
  for (const Lobe& l : result.front)
    j["members"].push_back({{"id", l.id}, {"formula", l.formula}, {"shape", l.shape}, {"max_abs", l.max_abs},
                            {"argmax_c", l.argmax_c}, {"argmax_param", l.argmax_param}, {"max_rel", l.max_rel},
                            {"model_cost", l.model_cost}});
  return j.dump(2) + "\n";
}

Result read_design(const std::filesystem::path& dir) {
  const auto path = dir / "design.json";
  try {
    const nlohmann::json j = nlohmann::json::parse(io::read_file(path));
    Result r;
    Settings& s = r.settings;
    s.target = j.at("target").get<std::string>();
    for (const auto& [name, value] : j.at("params").items()) s.params[name] = value.get<double>();
    const std::string form = j.at("form").get<std::string>();
    if (!form.empty()) s.form = form_named(form);
    s.param = j.at("param").get<std::string>();
    s.lo = j.at("lo").get<double>();
    s.hi = j.at("hi").get<double>();
    const auto objective = objective_named(j.at("objective").get<std::string>());
    if (!objective) throw InvalidArgument("unknown objective");
    s.objective = *objective;
    s.zone = j.at("zone").get<double>();
    s.max_cost = j.at("max_cost").get<int>();
    s.seed = j.at("seed").get<std::uint64_t>();
    s.shard = j.at("shard").get<int>();
    s.shards = j.at("shards").get<int>();
    r.forms_screened = j.at("forms_screened").get<std::int64_t>();
    r.forms_total = j.at("forms_total").get<std::int64_t>();
    r.cancelled = j.at("stopped").get<bool>();
    validate(s);
    for (const auto& m : j.at("members")) {
      Lobe l;
      l.id = m.at("id").get<std::string>();
      l.formula = m.at("formula").get<std::string>();
      l.shape = m.at("shape").get<std::string>();
      l.max_abs = m.at("max_abs").get<double>();
      l.argmax_c = m.at("argmax_c").get<double>();
      l.argmax_param = m.at("argmax_param").get<double>();
      l.max_rel = m.at("max_rel").get<double>();
      l.model_cost = m.at("model_cost").get<int>();
      (void)expr::parse(l.formula, {"c", s.param});  // a formula in c and the parameter
      r.front.push_back(std::move(l));
    }
    return r;
  } catch (const std::exception& e) {
    throw InvalidField("merge", fmt::format("{}: {}", path.string(), e.what()));
  }
}

void write_files(const Result& result, const std::filesystem::path& dir) {
  io::write_file_atomically(dir / "design.json", design_json(result));
  io::write_file_atomically(dir / "front.csv", front_csv(result));
  io::write_file_atomically(dir / "models.toml", models_toml(result));
}

}  // namespace specula::design
