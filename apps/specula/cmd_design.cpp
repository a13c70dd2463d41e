// specula design: the lobe designer (docs/designer.md).
#include <fmt/format.h>
#include <tuple>
#include <functional>
#include <iostream>
#include <optional>
#include <unistd.h>

#include "cli.h"
#include "gpu_timer.h"
#include "specula/design/design.h"
#include "specula/design/output.h"
#include "specula/interrupt/interrupt.h"
#include "specula/io/files.h"
#include "specula/report/design_page.h"

namespace specula::cli {
namespace {

struct DesignOptions {
  std::string target = "phong";
  std::vector<std::string> params;
  std::string form, range, vars, objective = "max-abs", ops = "all", shard = "0/1", out, precision = "double";
  design::Settings settings;
  std::optional<std::int64_t> max_forms;
  std::vector<std::string> merge;
  bool quiet = false;
  bool gpu_timing = true;
};

// "NAME=LO:HI".
void read_range(const std::string& text, design::Settings& s) {
  const auto eq = text.find('=');
  const auto colon = text.find(':', eq == std::string::npos ? 0 : eq);
  if (eq == std::string::npos || colon == std::string::npos || eq == 0)
    throw InvalidArgument(fmt::format("--range must be NAME=LO:HI, e.g. n=1:1000, got '{}'", text));
  s.param = text.substr(0, eq);
  const auto number = [&](std::string_view part) {
    const auto values = option_values("--range", part, 1);
    return values.at(0);
  };
  s.lo = number(std::string_view(text).substr(eq + 1, colon - eq - 1));
  s.hi = number(std::string_view(text).substr(colon + 1));
}

// "NoV,NoL".
std::vector<std::string> split_names(const std::string& text) {
  std::vector<std::string> out;
  for (std::size_t start = 0; start <= text.size();) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    out.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

// "I/N".
void read_shard(const std::string& text, design::Settings& s) {
  const auto slash = text.find('/');
  const auto i = strict_integer<int>(std::string_view(text).substr(0, slash));
  const auto n = slash == std::string::npos ? std::nullopt : strict_integer<int>(std::string_view(text).substr(slash + 1));
  if (!i || !n) throw InvalidArgument(fmt::format("--shard must be I/N, two whole numbers with 0 ≤ I < N, got '{}'", text));
  s.shard = *i;
  s.shards = *n;
}

design::Settings settings_of(const DesignOptions& o) {
  design::Settings s = o.settings;
  s.target = o.target;
  ModelOptions model;
  model.params = o.params;
  s.params = model.param_values();
  if (!o.form.empty()) s.form = form_named(o.form);
  s.variables = design::target_variables(s.target, o.vars.empty() ? std::vector<std::string>{} : split_names(o.vars));
  if (o.range.empty()) {  // the target's own: n = 1:1000 for a lobe, a term's, none for an expression without parameters
    const design::DefaultRange r = design::default_range(s.target, s.variables);
    std::tie(s.param, s.lo, s.hi) = std::tie(r.param, r.lo, r.hi);
  } else {
    read_range(o.range, s);
  }
  s.objective = choice_named<design::Objective, design::kObjectiveCount>("objective", o.objective, Spelling::option);
  s.precision = choice_named<design::Precision, design::kPrecisionCount>("precision", o.precision, Spelling::option);
  s.operations = design::parse_operations(o.ops);
  s.max_forms = o.max_forms;
  if (o.gpu_timing) s.gpu_timer = time_on_gpu;
  read_shard(o.shard, s);
  return s;
}

class ProgressPrinter {
 public:
  void operator()(const design::Progress& p) {
    std::cerr << fmt::format("\r\033[K{}: {}/{}", p.phase, p.done, p.total) << std::flush;
  }
  ~ProgressPrinter() { std::cerr << "\r\033[K" << std::flush; }
};

design::Result merged(const DesignOptions& o, const std::function<void(const design::Progress&)>& progress) {
  std::vector<design::Result> shards;
  for (const auto& dir : o.merge) shards.push_back(design::read_design(dir));
  design::Result r = design::merge(shards, {o.settings.measure_cost, o.settings.threads, nullptr}, progress);
  return r;
}

void run(const DesignOptions& o) {
  design::Settings s;
  if (o.merge.empty()) {
    s = settings_of(o);
    design::validate(s);
  }
  if (o.out.empty()) throw InvalidArgument("--out DIR is required: the directory the front is written to");
  io::StagedDirectory staged(o.out, {"design", "design.json"});  // a --out it may not replace fails here, before the search
  std::function<void(const design::Progress&)> progress;
  std::optional<ProgressPrinter> printer;
  if (!o.quiet && isatty(STDERR_FILENO)) {
    printer.emplace();
    progress = std::ref(*printer);
  }
  design::Result result = o.merge.empty() ? design::design(s, progress) : merged(o, progress);
  printer.reset();
  const int signal = stop_requested();
  clear_stop_request();  // what was found is written, then the stop goes on
  design::write_files(result, staged.path());
  report::write_design_pictures(result, staged.path());
  staged.commit();
  std::cout << design::front_table(result)
            << fmt::format("{} of {} shapes screened in {:.1f} s ({} computed what a cheaper shape computes){}; {}\n",
                           result.forms_screened, result.forms_total, result.seconds, result.forms_same,
                           result.cancelled ? " (stopped)" : "", result.cost_note)
            << (result.gpu_note.empty() ? std::string() : result.gpu_note + "\n");
  if (signal != 0) {
    request_stop(signal);
    throw Interrupted(Interrupted::Reason::signal, signal);
  }
}

}  // namespace

void add_design_command(CLI::App& app) {
  auto o = std::make_shared<DesignOptions>();
  auto* cmd = app.add_subcommand("design", "Search cheap lobes against a target lobe; write their Pareto front");
  cmd->add_option("--target", o->target,
                  "What to approximate: a lobe (an id, 'lobe: FORMULA' or a model file's id), a function of\n"
                  "c = cos θ in (0, 1] ('expr: FORMULA', e.g. 'expr: (1 - c)^5'), or an engine term:\n"
                  "fresnel-dielectric (eta), fresnel-conductor (eta; -p kappa=…), schlick-weight,\n"
                  "smith-g2-ggx, smith-g2-beckmann (NoV, NoL; alpha), the split-sum terms env-brdf-a-ggx,\n"
                  "env-brdf-b-ggx, env-brdf-a-beckmann, env-brdf-b-beckmann (NoV, r; tabulated)")
      ->capture_default_str();
  cmd->add_option("--param,-p", o->params, "The target's other parameters, NAME=VALUE (repeatable)");
  cmd->add_option("--form", o->form, "The target's form, rv or nh (default: its own)")->check(CLI::IsMember({"rv", "nh"}));
  cmd->add_option("--vars", o->vars, "A function target's per-pixel variables, each over (0, 1], e.g. NoV,NoL (default: c,\n"
                  "or the term's); every other name in its formula is a parameter");
  cmd->add_option("--range", o->range, "The parameter the lobes follow and its range, NAME=LO:HI (default: the target's:\n"
                  "n=1:1000 for a lobe, eta=1.2:2.5 for fresnel-dielectric, eta=0.1:3 for fresnel-conductor,\n"
                  "alpha=0.05:1 for smith-g2-ggx and smith-g2-beckmann,\n"
                  "none for a target without parameters)");
  cmd->add_option("--objective", o->objective, "max-abs: the largest |F − target|; max-rel: the largest relative error "
                  "where the target ≥ --zone; both: the two as objectives")
      ->capture_default_str()->check(one_of<design::Objective, design::kObjectiveCount>());
  cmd->add_option("--zone", o->settings.zone, "The epicenter of max-rel: where the target ≥ zone, in (0, 1)")->capture_default_str()
      ->check(CLI::Range(1e-9, 1 - 1e-9));
  cmd->add_option("--ops", o->ops, "Operations the lobes may use: all, or a list of fma, mul, add, max, div, sqrt, exp, log2")
      ->capture_default_str();
  cmd->add_option("--max-cost", o->settings.max_cost, "Shapes up to this cost model (fma = mul = add = max = 1, div = sqrt = 4, "
                  "exp = log2 = 10), in [1, 24]; 7 and up take long")->capture_default_str()
      ->check(CLI::Range(1, design::Ranges::max_cost));
  cmd->add_option("--max-forms", o->max_forms, "Screen the first this many shapes in order of cost (all shards together; "
                  "default and most 10^6), a budget that gives the same front on any machine")
      ->check(CLI::Range(std::int64_t{1}, design::Ranges::forms));
  cmd->add_option("--time", o->settings.time_s, "Seconds for the screening (it stops there; the finishing takes a minute more), in (0, 86400]")
      ->capture_default_str()->check(CLI::Range(1e-3, design::Ranges::time_s));
  cmd->add_option("--seed", o->settings.seed, "Seed of the constants' random starts")->capture_default_str();
  cmd->add_option("--threads", o->settings.threads, "Threads, 0 = all cores, in [0, 1024]")->capture_default_str()
      ->check(CLI::Range(0, design::Ranges::threads));
  cmd->add_option("--shard", o->shard, "Screen shard I of N (shapes i with i mod N = I), e.g. 0/4")->capture_default_str();
  cmd->add_flag("!--no-timing", o->settings.measure_cost, "Do not time the front (cost = the cost model)");
  cmd->add_flag("!--no-refit", o->settings.refit_references,
                "Do not refit the engines' own forms (Schlick's, the fast Smith, Lazarov's) as members");
  cmd->add_flag("!--no-certify", o->settings.certify,
                "Do not bound the errors of a function target's front by interval arithmetic (front.csv max_abs_bound)");
  cmd->add_flag("!--no-gpu-timing", o->gpu_timing, "Do not time the front on the GPU (the GPU axis: an offscreen GL context,\n"
                "the GPU or Mesa's llvmpipe without one)");
  cmd->add_option("--precision", o->precision, "The members' constants and arithmetic: double (as fitted), or as a shader\n"
                  "has them, float or half: constants rounded, then moved one ulp at a time for the lowest\n"
                  "error, every operation rounded, the error measured again")
      ->capture_default_str()->check(one_of<design::Precision, design::kPrecisionCount>());
  cmd->add_option("--out", o->out, "The directory to write: front.csv, models.toml, design.json, front.svg, front-gpu.svg, index.html "
                  "(swapped in whole)");
  cmd->add_option("--merge", o->merge, "Instead of a search: merge the fronts of these --out directories (shards of "
                  "one search), measuring every lobe again here and timing it (unless --no-timing)")->expected(1, 10'000);
  cmd->add_flag("--quiet,-q", o->quiet, "No progress on stderr");
  cmd->footer(
      "Fits each shape's constants per value of the range parameter for the largest error, gives\n"
      "them laws in the parameter (specula fit), measures each lobe's error over the whole domain\n"
      "(the exact maxima of specula error, refined over the parameter), times the front and the\n"
      "reference lobes as native code in one run, and writes the Pareto front. Examples:\n"
      "  specula design --target phong --range n=1:1000 --out designed\n"
      "  specula --models designed/models.toml error --model phong-d1 --reference phong --n 1:1000@20:log\n"
      "  specula design --target phong --range n=1:1000 --ops fma,mul,max --max-cost 8 --out cheap\n"
      "  specula design --target fresnel-dielectric --out fresnel     # beside Schlick's and Unreal's\n"
      "  specula design --target 'expr: (1 - c)^5' --ops fma,mul,add,max,exp --out weight\n"
      "  specula design --target smith-g2-ggx --max-cost 5 --out smith           # G2(NoV, NoL; alpha)\n"
      "  specula design --target env-brdf-b-ggx --max-cost 5 --out envb    # beside Karis's EnvBRDFApprox\n"
      "Shards of one search on several machines, then one front (GNU parallel; a Slurm array runs\n"
      "the same command with I = $SLURM_ARRAY_TASK_ID):\n"
      "  parallel specula design --shard {}/4 --out shard{} ::: 0 1 2 3\n"
      "  specula design --merge shard0 shard1 shard2 shard3 --out designed");
  cmd->callback([o] { run(*o); });
}

}  // namespace specula::cli
