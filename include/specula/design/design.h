#pragma once
// The lobe designer (docs/designer.md): searches cheap lobe shapes F(c; p) against a target lobe
// over a range of one of its parameters, fits each shape's constants per parameter value for the
// largest error, turns those constants into formulas in the parameter (fit::search), measures
// each finished lobe's largest error over the whole domain with the exact maxima of `specula
// error`, times it as native vectorized code beside the reference lobes, and keeps the Pareto
// front of cost against error. Deterministic for a seed and a form budget, for any thread count.
#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "specula/exceptions.h"
#include "specula/expr/expr.h"
#include "specula/models/model.h"

namespace specula::design {

/// The operations a designed lobe may use, with the search's cost model (float SIMD, in units of
/// one fused multiply-add). The front is timed afterwards; the cost model only orders the search.
///   fma   a·x + b with per-material a, b: 1       mul   x·y and x² (squaring): 1
///   add   x + y: 1                                 max   max(x, 0): 1
///   div   x / y: 4                                 sqrt  √x: 4
///   exp   eˣ: 10                                   log2  log₂ x: 10
enum class Operation { fma, mul, add, max, div, sqrt, exp, log2 };
inline constexpr std::size_t kOperationCount = static_cast<std::size_t>(Operation::log2) + 1;  // log2: the last
constexpr const char* to_string(Operation op) noexcept {
  switch (op) {
    case Operation::fma: return "fma";
    case Operation::mul: return "mul";
    case Operation::add: return "add";
    case Operation::max: return "max";
    case Operation::div: return "div";
    case Operation::sqrt: return "sqrt";
    case Operation::exp: return "exp";
    case Operation::log2: return "log2";
  }
  return "";
}
static_assert(names_complete<Operation, kOperationCount>([](Operation o) { return to_string(o); }));
int operation_cost(Operation op);
/// Parses "fma,mul,max" (names as above; "all" for every one). Throws InvalidField "ops".
std::vector<Operation> parse_operations(std::string_view text);

/// What a candidate is ranked by, each over the whole domain (every c ∈ [0, 1], every parameter
/// value in the range): the largest |F − target|; the largest |F − target|/target where the
/// target is ≥ `zone` (the paper's epicenter); or both, as two objectives.
enum class Objective { max_abs, max_rel, both };
inline constexpr std::size_t kObjectiveCount = static_cast<std::size_t>(Objective::both) + 1;  // both: the last
constexpr const char* to_string(Objective objective) noexcept {
  switch (objective) {
    case Objective::max_abs: return "max-abs";
    case Objective::max_rel: return "max-rel";
    case Objective::both: return "both";
  }
  return "";
}
static_assert(names_complete<Objective, kObjectiveCount>([](Objective o) { return to_string(o); }));
constexpr std::optional<Objective> objective_named(std::string_view name) {
  return enum_named<Objective, kObjectiveCount>(name, [](Objective o) { return to_string(o); });
}

/// The precision a member's constants and arithmetic are taken in (--precision): double as
/// computed, or as a GPU shader has them, float32 or binary16 (docs/designer.md, "Precision").
enum class Precision { f64, f32, f16 };
inline constexpr std::size_t kPrecisionCount = static_cast<std::size_t>(Precision::f16) + 1;  // f16: the last
constexpr const char* to_string(Precision p) noexcept {
  switch (p) {
    case Precision::f64: return "double";
    case Precision::f32: return "float";
    case Precision::f16: return "half";
  }
  return "";
}
static_assert(names_complete<Precision, kPrecisionCount>([](Precision p) { return to_string(p); }));
constexpr std::optional<Precision> precision_named(std::string_view name) {
  return enum_named<Precision, kPrecisionCount>(name, [](Precision p) { return to_string(p); });
}

/// The documented ranges of the options: anything outside is InvalidField named by its key.
struct Ranges {
  static constexpr int max_cost = 24;                 ///< max_cost in [1, 24]
  static constexpr int member_cost = 200;             ///< a member's model_cost, at most (an engine's form refitted may pass max_cost)
  static constexpr std::int64_t forms = 1'000'000;    ///< max_forms in [1, 10⁶]
  static constexpr double time_s = 86'400;            ///< time_s in (0, 86400]
  static constexpr int threads = 1024;                ///< threads in [0, 1024]
  static constexpr int shards = 10'000;               ///< shard count in [1, 10000]
  static constexpr double range_ratio = 1e12;         ///< hi / lo of the range (lo > 0), at most
  static constexpr double target_max = 1e100;         ///< the target's values, at most (the fits square its errors)
  static constexpr std::size_t front_members = 80;    ///< members of one front (40 candidates, 2 objectives), at most
  static constexpr std::size_t design_json_bytes = std::size_t{1} << 20;  ///< a design.json --merge reads: 1 MiB
};

/// A term of a microfacet BRDF that engines approximate by hand, as a target of the designer
/// besides lobes (docs/designer.md, "Targets beyond lobes"): a function of c = cos θ ∈ (0, 1],
/// exact as written, with its usual range parameter and the engines' approximations of it.
/// How a term is computed: its formula, or one of the split-sum terms tabulated from specula's
/// cubature (docs/designer.md, "The environment BRDF").
/// split_sum_ab: both, as a target of two outputs (A at output = 0, B at output = 1).
enum class Tabulation { none, split_sum_a, split_sum_b, split_sum_ab };

struct Term {
  std::string_view id;       ///< the target's name: "fresnel-dielectric"
  std::string_view formula;  ///< the exact term in c and the parameters (specula's expressions); a tabulated term's description
  std::string_view param;    ///< the range parameter ("" for none)
  double lo = 0, hi = 0;     ///< its default range
  std::string_view summary;
  std::string_view variables = "c";  ///< its per-pixel variables, comma-separated
  Tabulation tabulation = Tabulation::none;
  std::string_view model = {};  ///< a tabulated term's microfacet model ("ggx-schlick")
};

/// An engine's approximation of a term: a reference row of the front, timed and measured as the
/// members are.
struct TermReference {
  std::string_view term;     ///< the Term's id
  std::string_view id;       ///< "schlick", "unreal-exp2"
  std::string_view formula;  ///< in c and the term's parameters
  std::string_view source;   ///< who uses it, and where it was published
};

/// The built-in terms, and every engine approximation of them the designer measures.
std::span<const Term> terms();
std::span<const TermReference> term_references();

/// Whether `target` is a function of c rather than a lobe: "expr: FORMULA" or a Term's id. A
/// function target is measured on all of c ∈ (0, 1] (not in u around a peak), its members are not
/// normalized or energy-checked (they are not lobes), and its references are its engines'.
bool is_function_target(std::string_view target);
/// The formula of a function target: the text after "expr:", or the Term's formula.
std::string function_formula(std::string_view target);
/// The built-in term of that id, or nullptr.
const Term* term_named(std::string_view id);
/// Whether `target` is a tabulated term (no formula: its values are interpolated).
bool is_tabulated(std::string_view target);

/// The most per-pixel variables a function target may have (its output index included).
inline constexpr std::size_t kMaxVariables = 3;

/// A target of several outputs fitted together (docs/designer.md, "Several outputs"): the split
/// sum's (A, B) ("env-brdf-ggx"), or "expr: F0; F1; …". It is one function of its variables and a
/// last one, `output`, that takes only the values 0, 1, …, outputs − 1: the target is output i's
/// formula there (written (1 − output)·F0 + output·F1 for two), and a member is one formula in the
/// same variables, whose outputs share what they compute (cost and timing count both outputs
/// together, as a shader computing both does).
inline constexpr std::string_view kOutputVariable = "output";
inline constexpr int kMaxOutputs = 4;
/// The outputs of a target: 2 for the split sum's pairs, the parts of "expr: F0; F1", else 1.
int output_count(std::string_view target);
/// Each output of a target of several outputs as a target of its own ("env-brdf-a-ggx",
/// "expr: F1"); a target of one output: itself.
std::vector<std::string> output_targets(std::string_view target);
/// Formulas F0, F1, … (in the same variables) as one formula in `output` that is Fi at output = i:
/// (1 - output)*(F0) + output*(F1) for two, the Lagrange basis of 0, 1, … for more; F0 for one.
std::string stacked_formula(const std::vector<std::string>& parts);
/// The per-pixel variables a target is searched in: `given` (the user's), or default_variables
/// when none are given; for a target of several outputs, `output` appended where not named last.
std::vector<std::string> target_variables(std::string_view target, std::vector<std::string> given);

/// The per-pixel variables of a target when none are given: a Term's, c otherwise.
std::vector<std::string> default_variables(std::string_view target);

/// The range a target is searched over when none is given: the Term's, n = 1:1000 for a lobe or
/// an expression with n, none ("" and 1:1) for an expression without parameters.
struct DefaultRange {
  std::string param;
  double lo = 1, hi = 1;
};
/// `variables`: the target's per-pixel variables (the free names of an expression that are not
/// parameters).
DefaultRange default_range(std::string_view target, const std::vector<std::string>& variables = {"c"});

/// A function for the GPU cost axis: GLSL defining `float specula_term(…)` of `variables` per-pixel
/// variables and then the parameter (if has_param) at `param`.
struct GpuFunction {
  std::string glsl;
  int variables = 1;
  bool has_param = false;
  double param = 0;
};
/// What a GPU timer found: picoseconds per evaluation of each function (NaN: not timed), and the
/// device, or why none (then `ps` is empty).
struct GpuTiming {
  std::vector<double> ps;
  std::string device;
};
using GpuTimer = std::function<GpuTiming(const std::vector<GpuFunction>&)>;

struct Settings {
  /// A lobe model (id, "lobe: …" or a model-file id), or a function of c: "expr: FORMULA" or a
  /// Term's id (is_function_target).
  std::string target = "phong";
  ParamValues params;            ///< the target's other parameters
  std::optional<Form> form;      ///< the target's form (default: its own)
  /// The per-pixel variables, each over (0, 1]: c for a lobe; a function target may have several
  /// (NoV, NoL), at most kMaxVariables.
  std::vector<std::string> variables{"c"};
  std::string param = "n";       ///< the range parameter; "" where the target has none (then lo = hi)
  double lo = 1, hi = 1000;      ///< its range
  Objective objective = Objective::max_abs;
  double zone = 0.5;             ///< the epicenter of max_rel: target ≥ zone
  std::vector<Operation> operations = parse_operations("all");
  int max_cost = 6;              ///< shapes up to this cost model
  std::optional<std::int64_t> max_forms;  ///< the first this many shapes by cost, all shards together (deterministic budget)
  double time_s = 540;           ///< wall-clock budget of the screening
  std::uint64_t seed = 1;
  int threads = 0;               ///< 0: all cores
  int shard = 0, shards = 1;     ///< this run screens the forms i with i mod shards = shard
  bool measure_cost = true;      ///< time the front as native code (else the cost model only)
  /// The members' per-pixel constants rounded to this and adjusted one ulp at a time, their
  /// arithmetic evaluated in it (double: as fitted).
  Precision precision = Precision::f64;
  /// Finishes each evaluable reference's own form, its constants freed, as a member (reference_seeds;
  /// docs/designer.md, "The engines' forms refitted").
  bool refit_references = true;
  /// Bounds each member's and evaluable reference's error of a function target with a formula by
  /// interval arithmetic (Lobe::max_abs_bound; docs/designer.md, "A certified bound").
  bool certify = true;
  /// Times the front and the references on a GPU (the CLI's is made through specula_gl: the GPU,
  /// or llvmpipe without one); empty: no GPU axis. Used only when measure_cost.
  GpuTimer gpu_timer;
  const std::atomic<bool>* cancel = nullptr;
};

/// Whether per-pixel variable v of the settings is the output index (a target of several outputs:
/// the last variable, named `output`).
bool is_output_variable(const Settings& s, std::size_t v);

/// One lobe on the front, or a reference lobe.
struct Lobe {
  std::string id;
  bool reference = false;
  bool evaluable = false;       ///< references: `formula` is code (compiled and timed), not a description
  std::string formula;          ///< F in c and the parameter
  std::string shape;            ///< the structure searched, constants as k ("" for references)
  double max_abs = 0;           ///< over the whole domain
  double argmax_c = 0, argmax_param = 0;
  double max_rel = 0;           ///< in the epicenter, over the whole domain
  int ops = 0;                  ///< operations per evaluation (free: the parameter's subexpressions)
  int model_cost = 0;           ///< the cost model's units
  double ns_per_eval = NAN;     ///< measured, float, one core, in cache; NaN if not measured
  std::string timing;           ///< how ns_per_eval was measured ("native", "bench fast tier", …)
  double spirv_instructions = NAN;  ///< the lobe's SPIR-V instructions beyond F = c's (glslang); NaN if unavailable
  double k = NAN;               ///< members: k at timing_param
  std::string k_formula;        ///< members: k(p) in closed form, where one is derived; else empty (quadrature)
  std::string check;            ///< members: "pass", or what `specula check` finds failing, and where
  /// members, with --precision float or half: the largest error on the fits' rows with the
  /// arithmetic in that precision (NaN otherwise), and a note where that is past the error the
  /// member had before its constants were rounded.
  double precision_error = NAN;
  std::string precision_note;
  /// A function target with a formula: an upper bound on max_abs over [10⁻⁶, 1] per per-pixel
  /// variable and the whole range, certified by interval arithmetic (docs/designer.md, "A certified
  /// bound"); inf where the budget ran out first; NaN where not certified (lobes, tabulated terms).
  double max_abs_bound = NAN;
  double gpu_ps_per_eval = NAN;  ///< measured by Settings::gpu_timer, beyond F = its first variable; NaN if not
  bool gpu_front = false;        ///< members: on the front of GPU cost against error among the front's members
};

struct Result {
  Settings settings;
  std::vector<Lobe> front;       ///< members, cheapest first, each more accurate than the cheaper
  std::vector<Lobe> references;  ///< the target's usual approximations, measured in the same run
  /// Members that would be on the front but whose normalized twin fails `specula check` (`check`
  /// says what and where): kept out of the front, which is taken again without them.
  std::vector<Lobe> refused;
  std::int64_t forms_screened = 0;
  std::int64_t forms_total = 0;  ///< this shard's shapes within max_cost and max_forms
  /// Of those screened, the shapes that computed at the range's middle what a cheaper shape of
  /// this shard computed there (the same values on the rows): not screened further.
  std::int64_t forms_same = 0;
  double seconds = 0;
  bool cancelled = false;
  std::string cost_note;         ///< how the costs were obtained (compiler, or why the model)
  std::string spirv_note;        ///< how the SPIR-V counts were obtained, or why not
  std::string gpu_note;          ///< the GPU axis: the device it was timed on, or why not
  std::string source;            ///< the design.json it was read from (read_design): merge's messages name it
};

/// What design() reports as it goes, from one thread at a time.
struct Progress {
  std::string_view phase;  ///< screening shapes, finishing lobes, timing, checking, done
  std::int64_t done = 0, total = 0;
  /// While finishing: the front (on the cost model's axis) of the lobes finished so far, their
  /// ids unset; at done: the final front. Valid during the call only; else nullptr.
  const std::vector<Lobe>* front = nullptr;
  /// The shapes screened so far and this shard's shapes in all (set from the first report on).
  std::int64_t forms_screened = 0, forms_total = 0;
};

/// Runs the designer. Throws InvalidArgument / InvalidField on bad settings (target not a lobe,
/// or somewhere on the domain not finite, negative or above Ranges::target_max; range outside the
/// parameter's, empty or reversed, budgets out of range).
Result design(const Settings& settings, const std::function<void(const Progress&)>& progress = {});

/// What a merge takes from the command line rather than from the shards.
struct MergeOptions {
  bool measure_cost = true;  ///< time the front as native code (else the cost model only)
  int threads = 0;           ///< for the measuring; 0: all cores
  const std::atomic<bool>* cancel = nullptr;
};

/// One front from the fronts of shards of one search (the same target, parameters, form, range,
/// objective and zone; InvalidField "merge" naming both values otherwise): their members' union,
/// each member measured again over the whole domain as design() measures a finished lobe (the
/// errors a shard claims are not used; a member that is not finite somewhere is InvalidField
/// "merge" naming its file and index), the references measured again, timed as `options` says,
/// the Pareto front taken anew.
Result merge(const std::vector<Result>& shards, const MergeOptions& options = {},
             const std::function<void(const Progress&)>& progress = {});

/// Whether a range is spanned in log p (lo > 0 and hi/lo ≥ 4) rather than in p: the grids of
/// parameter values, the search for the worst one and the range's middle all follow it.
bool log_spaced(double lo, double hi);
/// The middle of [lo, hi] in that spacing (geometric when log-spaced).
double middle(double lo, double hi);

/// The parameter value lobes are timed and normalized at: 20 (the benchmark's n) where the range
/// holds it, else the range's middle.
double timing_param(const Settings& s);

/// A lobe target at value p of the range parameter, its other parameters the settings' (a
/// function target is evaluated as an expression: function_expression). Throws InvalidField
/// "target" if the model is not a lobe.
Model target_at(const Settings& s, double p);
/// The target's form: the settings', else the target model's own.
Form target_form(const Settings& s);
/// The variables of a lobe's or function's formula: the per-pixel variables, then the range
/// parameter (if any).
std::vector<std::string> formula_variables(const Settings& s);
/// `formula` with each of `params` (a target's fixed parameters, κ) written as its value.
std::string with_values(std::string_view formula, const ParamValues& params);
/// A function target's formula (or a member's, a reference's, with `formula` given) as an
/// expression in formula_variables(s), the target's other parameters written as their values.
expr::Expression function_expression(const Settings& s, std::string_view formula = {});
/// What a shader computes for a member of a function target (or a reference, `formula` given): a
/// target of several outputs' formula at output = 0, 1, … each simplified (expr::simplify), summed
/// in one expression over the other variables (then the parameter), so that what the outputs share
/// is computed once where it is timed; a target of one output's expression as function_expression.
expr::Expression shader_expression(const Settings& s, std::string_view formula = {});
/// The per-pixel variables a shader reads: the settings' without the output index.
std::size_t shader_variables(const Settings& s);

/// A function target's values: f(point), the point being its per-pixel variables and then its
/// range parameter (if any) — its expression evaluated (function_expression), or a tabulated term
/// interpolated. Valid while `s` lives.
std::function<double(std::span<const double>)> target_function(const Settings& s);
/// The same at many points at once: columns[v][r] is variable v (then the parameter) at row r
/// (an expression evaluated in batches, as expr::evaluate_batch).
std::vector<double> target_values(const Settings& s, const std::vector<std::vector<double>>& columns);

/// Whether l is a formula (every member, and the evaluable references: the spherical Gaussian,
/// the engines' approximations of a term) rather than a built-in model's id.
bool is_formula(const Lobe& l);
/// Lobe l (a member or a reference) as a model at each value of the range parameter, in the
/// target's form, bare (normalization none). The model definition is read once.
std::function<Model(double)> lobe_at(const Lobe& l, const Settings& s);

/// The parameter values every member is checked at: the range's ends and timing_param.
std::vector<double> check_params(const Settings& s);

/// Throws what design() throws for `settings`, doing no work.
void validate(const Settings& settings);

}  // namespace specula::design
