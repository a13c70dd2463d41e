#include "specula/design/output.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <nlohmann/json.hpp>

#include "specula/catalogue/catalogue.h"
#include "specula/fit/fit.h"
#include "specula/io/files.h"

namespace specula::design {

namespace {

using Json = nlohmann::json;

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

// A member's normalization: its k(p) in closed form, else "quadrature"; empty for references and
// for a function's members (check "-": not lobes, nothing to normalize).
std::string normalization_of(const Lobe& l) {
  if (l.reference || l.check == "-") return {};
  return l.k_formula.empty() ? "quadrature" : l.k_formula;
}

std::string row(const Lobe& l, double log, std::string_view kind) {
  return fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", csv_field(l.id), kind,
                     csv_field(l.formula), number(l.max_abs), number(l.argmax_c), number(l.argmax_param),
                     number(l.max_rel), number(l.ns_per_eval), number(l.ns_per_eval / log),
                     l.ops > 0 ? std::to_string(l.ops) : std::string(), number(l.spirv_instructions),
                     l.reference ? std::string() : std::to_string(l.model_cost), csv_field(l.shape), csv_field(l.timing),
                     number(l.k), csv_field(l.check), csv_field(normalization_of(l)), number(l.precision_error),
                     csv_field(l.precision_note), number(l.gpu_ps_per_eval),
                     l.reference || std::isnan(l.gpu_ps_per_eval) ? std::string() : l.gpu_front ? "yes" : "no",
                     std::isinf(l.max_abs_bound) ? std::string("inf") : number(l.max_abs_bound));
}

// A member's formula with constants to 6 digits (the files hold them in full).
std::string shown(const Lobe& l) {
  if (l.reference) return l.formula;
  return expr::to_infix(fit::rounded(expr::parse(l.formula), 6));
}

// design.json as --merge reads it back: each key of its type, each setting validated as the CLI
// validates it, each claim possible; every failure one line naming the file and the key, as
// "merge: FILE: 'members'[3].'formula' must be a string".
class DesignReader {
 public:
  explicit DesignReader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(std::string_view key, std::string_view message) const {
    throw InvalidField("merge", fmt::format("merge: {}: {}{}{}", file_, key, key.empty() ? "" : " ", message));
  }

  Result result(const Json& j) const {
    if (!j.is_object()) fail("", "must hold a JSON object");
    Result r;
    r.settings = settings(j);
    r.forms_total = count(j, "forms_total");
    r.forms_screened = count(j, "forms_screened");
    if (r.forms_screened > r.forms_total)
      fail("'forms_screened'", fmt::format("({}) is more than 'forms_total' ({})", r.forms_screened, r.forms_total));
    r.forms_same = j.contains("forms_same") ? count(j, "forms_same") : 0;  // absent from earlier files
    if (r.forms_same > r.forms_screened)
      fail("'forms_same'", fmt::format("({}) is more than 'forms_screened' ({})", r.forms_same, r.forms_screened));
    r.cancelled = flag(j, "stopped");
    const Json& members = value(j, "", "members");
    if (!members.is_array()) fail("'members'", "must be an array");
    if (members.size() > Ranges::front_members)
      fail("'members'", fmt::format("holds {} members: a front has at most {}", members.size(), Ranges::front_members));
    for (std::size_t i = 0; i < members.size(); ++i) r.front.push_back(member(members[i], fmt::format("'members'[{}].", i), r.settings));
    return r;
  }

 private:
  std::string file_;

  const Json& value(const Json& object, std::string_view prefix, std::string_view key) const {
    const auto found = object.find(key);
    if (found == object.end()) fail(fmt::format("{}'{}'", prefix, key), "is missing");
    return *found;
  }

  std::string text(const Json& object, std::string_view key, std::string_view prefix = "") const {
    const Json& v = value(object, prefix, key);
    if (!v.is_string()) fail(fmt::format("{}'{}'", prefix, key), "must be a string");
    return v.get<std::string>();
  }

  double number(const Json& object, std::string_view key, std::string_view prefix = "") const {
    const Json& v = value(object, prefix, key);
    if (!v.is_number() || !std::isfinite(v.get<double>())) fail(fmt::format("{}'{}'", prefix, key), "must be a finite number");
    return v.get<double>();
  }

  // An integer that an int holds; its documented range is validate()'s to check.
  int small_integer(const Json& object, std::string_view key) const {
    const Json& v = value(object, "", key);
    if (!v.is_number_integer() || v.get<double>() < std::numeric_limits<int>::min() ||
        v.get<double>() > std::numeric_limits<int>::max())
      fail(fmt::format("'{}'", key), "must be an integer");
    return v.get<int>();
  }

  std::int64_t count(const Json& object, std::string_view key) const {
    const Json& v = value(object, "", key);
    if (!v.is_number_integer() || v.get<double>() < 0 || v.get<double>() > static_cast<double>(Ranges::forms))
      fail(fmt::format("'{}'", key), fmt::format("must be an integer in [0, {}]", Ranges::forms));
    return v.get<std::int64_t>();
  }

  bool flag(const Json& object, std::string_view key) const {
    const Json& v = value(object, "", key);
    if (!v.is_boolean()) fail(fmt::format("'{}'", key), "must be true or false");
    return v.get<bool>();
  }

  // A claimed error: a number ≥ 0, or null where it is not finite (JSON has no inf).
  double error(const Json& object, std::string_view key, std::string_view prefix) const {
    const Json& v = value(object, prefix, key);
    if (v.is_null()) return INFINITY;
    if (!v.is_number() || !(v.get<double>() >= 0))
      fail(fmt::format("{}'{}'", prefix, key), "must be a number ≥ 0 (or null: not finite)");
    return v.get<double>();
  }

  // Wraps what a named parser or validate() throws, naming the key.
  template <class Parse>
  auto parsed(std::string_view key, const Parse& parse) const {
    try {
      return parse();
    } catch (const InvalidArgument& e) {
      fail(key, e.what());
    }
  }

  Settings settings(const Json& j) const {
    Settings s;
    s.target = text(j, "target");
    if (j.contains("variables")) {  // written since the function targets; c before
      const Json& variables = value(j, "", "variables");
      if (!variables.is_array()) fail("'variables'", "must be an array of names");
      s.variables.clear();
      for (const Json& v : variables) {
        if (!v.is_string()) fail("'variables'", "must be an array of names");
        s.variables.push_back(v.get<std::string>());
      }
    }
    const Json& params = value(j, "", "params");
    if (!params.is_object()) fail("'params'", "must be an object of numbers");
    for (const auto& [name, v] : params.items()) s.params[name] = number(params, name, "'params'.");
    const std::string form = text(j, "form");
    if (!form.empty()) s.form = parsed("'form':", [&] { return parse_form(form); });
    s.param = text(j, "param");
    s.lo = number(j, "lo");
    s.hi = number(j, "hi");
    const std::string objective = text(j, "objective");
    s.objective = parsed("", [&] {
      return choice_named<Objective, kObjectiveCount>("objective", objective, Spelling::key);
    });
    s.zone = number(j, "zone");
    const std::string precision = j.contains("precision") ? text(j, "precision") : "double";  // absent from earlier files
    s.precision = parsed("", [&] { return choice_named<Precision, kPrecisionCount>("precision", precision, Spelling::key); });
    s.operations = operations(j);
    s.max_cost = small_integer(j, "max_cost");
    const Json& seed = value(j, "", "seed");
    if (!seed.is_number_unsigned()) fail("'seed'", "must be an unsigned integer");
    s.seed = seed.get<std::uint64_t>();
    s.shard = small_integer(j, "shard");
    s.shards = small_integer(j, "shards");
    s.measure_cost = false;  // a merge's timing is its own (MergeOptions), not the shard's
    parsed("", [&] { validate(s); });
    return s;
  }

  std::vector<Operation> operations(const Json& j) const {
    const Json& ops = value(j, "", "ops");
    if (!ops.is_array()) fail("'ops'", "must be an array of operation names");
    std::vector<Operation> out;
    for (std::size_t i = 0; i < ops.size(); ++i) {
      const std::string key = fmt::format("'ops'[{}]", i);
      if (!ops[i].is_string()) fail(key, "must be a string");
      for (Operation op : parsed(key + ":", [&] { return parse_operations(ops[i].get<std::string>()); }))
        if (std::ranges::find(out, op) == out.end()) out.push_back(op);
    }
    return out;
  }

  Lobe member(const Json& m, const std::string& prefix, const Settings& s) const {
    const std::string_view where = std::string_view(prefix).substr(0, prefix.size() - 1);
    if (!m.is_object()) fail(where, "must be an object");
    Lobe l;
    l.id = text(m, "id", prefix);
    l.formula = text(m, "formula", prefix);
    l.shape = text(m, "shape", prefix);
    l.max_abs = error(m, "max_abs", prefix);
    l.max_rel = error(m, "max_rel", prefix);
    const char* kept = s.objective == Objective::max_rel ? "max_rel" : "max_abs";  // what the search keeps finite
    if (!std::isfinite(s.objective == Objective::max_rel ? l.max_rel : l.max_abs))
      fail(fmt::format("{}'{}'", prefix, kept), fmt::format("must be finite: a front keeps no lobe whose {} is not", kept));
    l.argmax_c = number(m, "argmax_c", prefix);
    l.argmax_param = number(m, "argmax_param", prefix);
    if (!(std::abs(l.argmax_c) <= 1)) fail(fmt::format("{}'argmax_c'", prefix), "must be a cosine, in [-1, 1]");
    if (!(l.argmax_param >= s.lo && l.argmax_param <= s.hi))
      fail(fmt::format("{}'argmax_param'", prefix), fmt::format("must be in the range [{}, {}]", s.lo, s.hi));
    const Json& cost = value(m, prefix, "model_cost");
    if (!cost.is_number_integer() || cost.get<double>() < 0 || cost.get<double>() > Ranges::member_cost)
      fail(fmt::format("{}'model_cost'", prefix), fmt::format("must be an integer in [0, {}]", Ranges::member_cost));
    l.model_cost = cost.get<int>();
    parsed(fmt::format("{}'formula':", prefix), [&] {
      (void)expr::parse(l.formula, formula_variables(s));     // a formula in the variables and the parameter
      if (!is_function_target(s.target)) (void)lobe_at(l, s);  // … that is a lobe model
    });
    return l;
  }
};

}  // namespace

std::string front_csv(const Result& result) {
  std::string out =
      "id,kind,formula,max_abs_error,argmax_c,argmax_param,max_rel_error,ns_per_eval,cost_vs_log,ops,"
      "spirv_instructions,model_cost,shape,timing,k,check,normalization,precision_error,precision_note,gpu_ps_per_eval,"
      "gpu_front,max_abs_bound\n";
  const double log = log_ns(result);
  for (const auto& l : result.front) out += row(l, log, "member");
  for (const auto& l : result.references) out += row(l, log, "reference");
  for (const auto& l : result.refused) out += row(l, log, "refused");
  return out;
}

// "n in [1, 1000]", or "c in (0, 1]" for a target without parameters.
std::string domain_text(const Settings& s) {
  return s.param.empty() ? std::string("c in (0, 1]") : fmt::format("{} in [{:g}, {:g}]", s.param, s.lo, s.hi);
}

MemberModel member_model(const Result& result, const Lobe& l, bool normalized) {
  const Settings& s = result.settings;
  return {normalized ? l.id + "-normalized" : l.id,
          fmt::format("designed lobe {}{}", l.id, normalized ? ", normalized" : ""),
          fmt::format("max |F − {}| = {:.4g} over {}", s.target, l.max_abs, domain_text(s)),
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
  std::string out = fmt::format("# Lobes designed by specula design against {} over {} ({}).\n", s.target,
                                domain_text(s), to_string(s.objective));
  if (result.front.empty()) return out + "\nmodel = []  # the front is empty: no lobe was finished\n";
  // A function of c (not a lobe) is written bare only: a normalized twin would mean nothing.
  const std::vector<bool> twins = is_function_target(s.target) ? std::vector<bool>{false} : std::vector<bool>{false, true};
  for (const auto& l : result.front) {
    for (bool normalized : twins) {
      const MemberModel m = member_model(result, l, normalized);
      out += fmt::format(
          "\n[[model]]\nid = {}\nname = {}\nsource = \"specula design\"\nsummary = {}\nkind = \"lobe\"\nform = \"{}\"\n"
          "lobe = {}\nnormalization = {}\n",
          toml_string(m.id), toml_string(m.name), toml_string(m.summary), to_string(m.form), toml_string(m.lobe),
          toml_string(m.normalization));
      if (!m.param.empty())
        out += fmt::format("[model.params.{}]\ndefault = {:.17g}\nmin = {:.17g}\nmax = {:.17g}\n", m.param, m.default_value, m.min, m.max);
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
                       l.reference || l.check.empty() || l.check == "-" ? "-" : l.check == "pass" ? "pass" : "FAIL", shown(l));
  };
  for (const auto& l : result.front) line(l);
  out += "references:\n";
  for (const auto& l : result.references) line(l);
  for (const auto& l : result.front)
    if (!l.check.empty() && l.check != "pass" && l.check != "-") out += fmt::format("{}: check {}\n", l.id, l.check);
  if (!result.refused.empty()) out += "refused (their normalized twin fails specula check):\n";
  for (const auto& l : result.refused) out += fmt::format("{:<22} {:>10.4g}  {}: {}\n", l.id, l.max_abs, shown(l), l.check);
  return out;
}

std::string design_json(const Result& result) {
  const Settings& s = result.settings;
  nlohmann::json ops = nlohmann::json::array();
  for (Operation op : s.operations) ops.push_back(to_string(op));
  nlohmann::json j{{"target", s.target}, {"variables", s.variables}, {"params", s.params}, {"form", s.form ? to_string(*s.form) : ""},
                   {"param", s.param}, {"lo", s.lo}, {"hi", s.hi}, {"objective", to_string(s.objective)},
                   {"zone", s.zone}, {"precision", to_string(s.precision)}, {"ops", ops}, {"max_cost", s.max_cost}, {"seed", s.seed},
                   {"shard", s.shard}, {"shards", s.shards}, {"forms_screened", result.forms_screened},
                   {"forms_same", result.forms_same}, {"forms_total", result.forms_total}, {"stopped", result.cancelled},
                   {"members", nlohmann::json::array()}};
  for (const Lobe& l : result.front)
    j["members"].push_back({{"id", l.id}, {"formula", l.formula}, {"shape", l.shape}, {"max_abs", l.max_abs},
                            {"argmax_c", l.argmax_c}, {"argmax_param", l.argmax_param}, {"max_rel", l.max_rel},
                            {"model_cost", l.model_cost}});
  return j.dump(2) + "\n";
}

Result read_design(const std::filesystem::path& dir) {
  const auto path = dir / "design.json";
  std::string text;
  try {
    text = io::read_file(path, Ranges::design_json_bytes);
  } catch (const InvalidArgument& e) {
    throw InvalidField("merge", fmt::format("merge: {}", e.what()));
  }
  const DesignReader reader(path.string());
  Result r;
  try {
    r = reader.result(nlohmann::json::parse(text));
  } catch (const nlohmann::json::parse_error& e) {
    reader.fail("", fmt::format("not JSON (at byte {})", e.byte));
  }
  r.source = path.string();
  return r;
}

void write_files(const Result& result, const std::filesystem::path& dir) {
  io::write_file_atomically(dir / "design.json", design_json(result));
  io::write_file_atomically(dir / "front.csv", front_csv(result));
  io::write_file_atomically(dir / "models.toml", models_toml(result));
}

}  // namespace specula::design
