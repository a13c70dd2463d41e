#include "design_job.h"

#include <cmath>
#include <fmt/format.h>
#include <tuple>

#include "fields.h"
#include "specula/design/design.h"
#include "specula/design/output.h"
#include "specula/exceptions.h"
#include "specula/queries/queries.h"
#include "specula/expr/expr.h"
#include "specula/fit/fit.h"

namespace specula::serve {

namespace {

using Json = nlohmann::ordered_json;

Json number_or_null(double x) { return std::isfinite(x) ? Json(x) : Json(); }

/// A member as the page's model editor sends it: a definition object (docs/models.md).
Json definition(const design::MemberModel& m) {
  return Json{{"id", m.id},
              {"name", m.name},
              {"summary", m.summary},
              {"kind", "lobe"},
              {"lobe", m.lobe},
              {"form", to_string(m.form)},
              {"normalization", m.normalization},
              {"params", m.param.empty() ? Json::object()
                                         : Json{{m.param, Json{{"default", m.default_value}, {"min", m.min}, {"max", m.max}}}}}};
}

struct DesignJob final : Job {
  design::Settings settings;
  // Guarded by `mutex`:
  std::string phase = "starting";
  std::int64_t done = 0, total = 0;
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
  design::Result result;  ///< settings, and the front so far (provisional until phase done)
  bool final = false;

  std::string run() override {
    design::Result r = design::design(settings, [this](const design::Progress& p) {
      const std::lock_guard lock(mutex);
      phase = p.phase;
      done = p.done;
      total = p.total;
      result.forms_screened = p.forms_screened;
      result.forms_total = p.forms_total;
      if (p.front) {
        result.front = *p.front;
        for (std::size_t i = 0; i < result.front.size(); ++i)
          if (result.front[i].id.empty()) result.front[i].id = fmt::format("candidate-{}", i + 1);
      }
    });
    const std::lock_guard lock(mutex);
    const bool stopped_short = r.cancelled && !cancel;
    result = std::move(r);
    final = true;
    phase = "done";
    return cancel ? "cancelled" : stopped_short ? "stopped" : "done";
  }

  Json lobe_json(const design::Lobe& l) const {
    Json out{{"id", l.id},
             {"kind", l.reference ? "reference" : "member"},
             {"formula", l.formula},
             {"display", l.reference ? l.formula : expr::to_infix(fit::rounded(expr::parse(l.formula), 6))},
             {"max_abs_error", l.max_abs},
             {"max_abs_bound", number_or_null(l.max_abs_bound)},
             {"argmax_param", l.argmax_param},
             {"max_rel_error", l.max_rel},
             {"ns_per_eval", number_or_null(l.ns_per_eval)},
             {"ops", l.ops > 0 ? Json(l.ops) : Json()},
             {"spirv_instructions", number_or_null(l.spirv_instructions)},
             {"model_cost", l.reference ? Json() : Json(l.model_cost)},
             {"k", number_or_null(l.k)},
             {"k_formula", l.k_formula},
             {"check", l.check}, {"precision_note", l.precision_note}};
    if (!l.reference && !design::is_function_target(result.settings.target)) {  // a lobe: a model card can take it
      out["definition"] = definition(design::member_model(result, l, false));
      out["definition_normalized"] = definition(design::member_model(result, l, true));
    }
    return out;
  }

  void describe(Json& out) const override {
    const design::Settings& s = settings;
    out["target"] = s.target;
    out["param"] = s.param;
    out["range"] = {s.lo, s.hi};
    out["objective"] = to_string(s.objective);
    out["max_cost"] = s.max_cost;
    out["phase"] = phase;
    out["done"] = done;
    out["total"] = total;
    out["elapsed_s"] = final ? result.seconds : std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    out["final"] = final;
    out["forms_screened"] = result.forms_screened;
    out["forms_total"] = result.forms_total;
    out["forms_same"] = result.forms_same;
    out["front"] = Json::array();
    for (const auto& l : result.front) out["front"].push_back(lobe_json(l));
    out["references"] = Json::array();
    for (const auto& l : result.references) out["references"].push_back(lobe_json(l));
    out["refused"] = Json::array();
    for (const auto& l : result.refused) {
      Json refused = lobe_json(l);
      refused["kind"] = "refused";  // off the front: its normalized twin fails check (its `check` says why)
      out["refused"].push_back(std::move(refused));
    }
    out["cost_note"] = result.cost_note;
    out["spirv_note"] = result.spirv_note;
  }
};

[[noreturn]] void fail(std::string_view field, const std::string& message) { throw InvalidField(std::string(field), message); }

void read_range(const Fields& f, design::Settings& s) {
  s.variables = design::target_variables(s.target, f.has("vars") ? f.names("vars") : std::vector<std::string>{});
  if (!f.has("param") && !f.has("range")) {  // the target's own range
    const design::DefaultRange r = design::default_range(s.target, s.variables);
    std::tie(s.param, s.lo, s.hi) = std::tie(r.param, r.lo, r.hi);
    return;
  }
  s.param = f.text_or("param", "n");
  if (!f.has("range")) return;
  const nlohmann::json& range = f.raw("range");
  const auto lo = range.is_array() && range.size() == 2 ? finite_number(range[0]) : std::nullopt;
  const auto hi = range.is_array() && range.size() == 2 ? finite_number(range[1]) : std::nullopt;
  if (!lo || !hi) fail("range", fmt::format("range must be [lo, hi], two finite numbers, such as [1, 1000]"));
  s.lo = *lo;
  s.hi = *hi;
}

}  // namespace

std::shared_ptr<Job> design_job(std::string_view body, const Limits& limits) {
  const Fields f(body, {"target", "vars", "params", "form", "param", "range", "objective", "zone", "ops", "max_cost", "max_forms",
                        "time", "seed", "timing", "precision"});
  auto job = std::make_shared<DesignJob>();
  design::Settings& s = job->settings;
  s.target = f.text_or("target", "phong");
  s.params = f.params();
  if (f.has("form")) s.form = queries::form_named(f.text("form"), Spelling::key);
  read_range(f, s);
  s.objective = choice_named<design::Objective, design::kObjectiveCount>("objective", f.text_or("objective", "max-abs"),
                                                                         Spelling::key);
  s.operations = design::parse_operations(f.text_or("ops", "all"));
  s.zone = f.number_or("zone", s.zone);
  s.max_cost = static_cast<int>(f.integer_or("max_cost", std::min(4, limits.max_design_cost), 1, limits.max_design_cost));
  if (f.has("max_forms")) s.max_forms = f.integer_or("max_forms", 0, 1, design::Ranges::forms);
  s.time_s = f.number_or("time", limits.max_design_seconds);
  if (!(s.time_s > 0 && s.time_s <= limits.max_design_seconds))
    fail("time", fmt::format("time {} is outside (0, {}] seconds", s.time_s, limits.max_design_seconds));
  s.seed = static_cast<std::uint64_t>(f.integer_or("seed", 1, 0, std::int64_t{1} << 53));
  s.measure_cost = f.flag_or("timing", true);
  s.precision = choice_named<design::Precision, design::kPrecisionCount>("precision", f.text_or("precision", "double"),
                                                                         Spelling::key);
  s.threads = 1;  // a job never takes more than one core from the requests
  s.cancel = &job->cancel;
  design::validate(s);  // its InvalidFields name the request's keys
  job->result.settings = s;
  job->deadline = deadline_in(s.time_s + limits.design_grace_seconds);
  return job;
}

}  // namespace specula::serve
