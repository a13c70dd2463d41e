// specula walk: the random walk on the Smith microsurface (walk/walk.h), the reference for the
// energy a rough conductor reflects after 1, 2, 3 and more bounces.
#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "cli.h"
#include "specula/catalogue/fresnel_spec.h"
#include "specula/exceptions.h"
#include "specula/walk/walk.h"

namespace specula::cli {
namespace {

// The documented caps: cells (α × θ) and paths over all cells; Ctrl-C stops any walk.
constexpr std::size_t kMaxCells = 10'000;
constexpr std::size_t kMaxChannels = 16;
constexpr std::uint64_t kProgressFrom = std::uint64_t{1} << 22;  // paths in all: smaller walks end first

struct WalkOptions {
  std::string distribution = "ggx";
  std::string alpha = "0.5";
  std::string theta = "0,30,60,80";
  std::vector<std::string> fresnel;
  std::string outgoing;
  std::optional<double> dielectric;
  std::uint64_t paths = std::uint64_t{1} << 20;
  std::uint64_t seed = 1;
  bool quiet = false;
  OutputOptions output;
};

struct Cells {
  std::vector<double> alpha, theta_deg;
  std::vector<fresnel::Channel> channels;
  std::optional<Vec3> outgoing;
};

Vec3 direction_deg(double theta, double phi) {
  const double t = theta * std::numbers::pi / 180, p = phi * std::numbers::pi / 180;
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

Cells cells_of(const WalkOptions& o) {
  Cells c{option_values("--alpha", o.alpha, kMaxCells), option_values("--theta", o.theta, kMaxCells), {}, {}};
  if (c.alpha.size() * c.theta_deg.size() > kMaxCells)
    throw InvalidArgument(fmt::format("--alpha × --theta is {} cells, more than {}", c.alpha.size() * c.theta_deg.size(), kMaxCells));
  for (double t : c.theta_deg)
    if (!(t >= 0 && t < 90)) throw InvalidArgument(fmt::format("--theta {} is outside [0, 90)", t));
  if (o.fresnel.size() > kMaxChannels) throw InvalidArgument(fmt::format("at most {} --fresnel channels", kMaxChannels));
  for (const auto& spec : o.fresnel) c.channels.push_back(parse_fresnel(spec));
  if (c.channels.empty()) c.channels.push_back({});
  if (o.dielectric && (!o.fresnel.empty() || !o.outgoing.empty()))
    throw InvalidArgument("--dielectric walks an interface: it takes neither --fresnel nor --outgoing");
  if (!o.outgoing.empty()) {
    const std::vector<double> v = option_values("--outgoing", o.outgoing, 2);
    if (v.size() != 2 || !(v[0] >= 0 && v[0] < 90))
      throw InvalidArgument("--outgoing takes THETA,PHI in degrees, THETA in [0, 90)");
    c.outgoing = direction_deg(v[0], v[1]);
  }
  const double total = double(o.paths) * double(c.alpha.size() * c.theta_deg.size());
  if (total > double(walk::kMaxPaths))
    throw InvalidArgument(fmt::format("--paths {} over {} cells is more than {} paths in all", o.paths,
                                      c.alpha.size() * c.theta_deg.size(), walk::kMaxPaths));
  return c;
}

std::function<void(double)> progress_of(const WalkOptions& o, std::size_t cell, std::size_t cells) {
  if (o.quiet || double(o.paths) * double(cells) < double(kProgressFrom)) return {};
  return [cell, cells, next = 1](double done) mutable {
    const double overall = (double(cell) + done) / double(cells);
    if (overall * 10 < next) return;
    fmt::print(stderr, "walk: {:.0f}% (cell {}/{})\n", overall * 100, cell + 1, cells);
    next = int(overall * 10) + 1;
  };
}

io::Table walk_table(const WalkOptions& o) {
  const Cells c = cells_of(o);
  const walk::Distribution distribution = o.distribution == "ggx" ? walk::Distribution::ggx : walk::Distribution::beckmann;
  io::Table t;
  t.columns = {"alpha", "theta", "mu", "channel"};
  for (const char* name : {"order1", "order2", "order3", "order4plus", "total", "multiple"})
    t.columns.insert(t.columns.end(), {name, fmt::format("{}_se", name)});
  t.key_columns = 4;
  t.meta = {{"distribution", o.distribution},
            {"quantity", c.outgoing ? "BRDF f(wi, wo) by next-event estimation" : "directional albedo"},
            {"surface", o.dielectric ? fmt::format("dielectric interface, eta = {}", *o.dielectric) : "conductor"},
            {"paths", std::to_string(o.paths)},
            {"seed", std::to_string(o.seed)}};
  if (o.dielectric) {
    const char* sides[] = {"reflection", "transmission", "reflection + transmission"};
    for (int k = 0; k < 3; ++k) t.meta.emplace_back(fmt::format("channel {}", k), sides[k]);
  } else {
    for (std::size_t k = 0; k < c.channels.size(); ++k) t.meta.emplace_back(fmt::format("channel {}", k), to_spec(c.channels[k]));
  }
  const std::size_t cells = c.alpha.size() * c.theta_deg.size();
  for (std::size_t a = 0; a < c.alpha.size(); ++a)
    for (std::size_t i = 0; i < c.theta_deg.size(); ++i) {
      const walk::Microsurface surface{distribution, c.alpha[a]};
      walk::Options options{o.paths, o.seed, progress_of(o, a * c.theta_deg.size() + i, cells), {}};
      const Vec3 wi = direction_deg(c.theta_deg[i], 0);
      std::vector<walk::Albedo> result;
      if (o.dielectric) {
        const walk::DielectricAlbedo d = walk::dielectric_albedo(surface, *o.dielectric, wi.z, options);
        result = {d.reflection, d.transmission, d.energy};
      } else {
        result = c.outgoing ? walk::conductor_brdf_cos(surface, c.channels, wi, *c.outgoing, options)
                            : walk::conductor_albedo(surface, c.channels, wi.z, options);
      }
      const double scale = c.outgoing ? 1 / c.outgoing->z : 1;  // f·μ_o → f
      for (std::size_t k = 0; k < result.size(); ++k) {
        std::vector<double> row{c.alpha[a], c.theta_deg[i], wi.z, double(k)};
        for (const walk::Estimate& e : result[k].order) row.insert(row.end(), {e.value * scale, e.error * scale});
        for (const walk::Estimate& e : {result[k].total, result[k].multiple})
          row.insert(row.end(), {e.value * scale, e.error * scale});
        t.rows.push_back(std::move(row));
      }
    }
  return t;
}

}  // namespace

void add_walk_command(CLI::App& app) {
  auto o = std::make_shared<WalkOptions>();
  auto* cmd = app.add_subcommand("walk", "The random walk on the Smith microsurface: albedo by bounce order, the reference");
  cmd->add_option("--distribution,-d", o->distribution, "ggx or beckmann")->capture_default_str()->check(CLI::IsMember({"ggx", "beckmann"}));
  cmd->add_option("--alpha,-a", o->alpha, "Roughness α in [0.001, 4]: list or range")->capture_default_str();
  cmd->add_option("--theta,-t", o->theta, "Incidence angles in degrees, [0, 90): list or range")->capture_default_str();
  cmd->add_option("--fresnel,-f", o->fresnel,
                  "A Fresnel channel, repeatable (default: one): one, schlick:f0=0.04[,f90=1,p=5], f82:f0=..,tint=.., "
                  "dielectric:eta=1.5, conductor:eta=..,kappa=.. (docs/fresnel.md)");
  cmd->add_option("--outgoing", o->outgoing, "THETA,PHI (degrees): the BRDF f(wi, wo) toward this direction instead of the albedo");
  cmd->add_option("--dielectric", o->dielectric,
                  "ETA = n_below/n_above: walk a rough dielectric interface instead (rows: 0 reflection, 1 transmission, 2 their sum)");
  cmd->add_option("--paths,-n", o->paths, fmt::format("Paths per cell, [{}, {}], rounded up to blocks of {}", walk::kMinPaths,
                                                      walk::kMaxPaths, walk::kBlockPaths))
      ->capture_default_str()->check(CLI::Range(walk::kMinPaths, walk::kMaxPaths));
  cmd->add_option("--seed", o->seed, "The walk's seed: the same seed and paths give the same numbers on any machine's thread count")->capture_default_str();
  cmd->add_flag("--quiet,-q", o->quiet, "No progress on stderr");
  o->output.add_to(*cmd);
  cmd->footer(
      "Heitz et al. 2016: a path enters along -wi, meets the microsurface at a height drawn from Smith's\n"
      "masking, reflects about a visible normal with the Fresnel of each channel, and leaves or meets it\n"
      "again. Each column has its standard error (_se): order1 is the single-scattering albedo, multiple\n"
      "what it misses. docs/random-walk.md. Examples:\n"
      "  specula walk --alpha 1 --theta 0:80:20                       # F = 1: total = 1 within its error\n"
      "  specula walk -a 0.5 -t 60 -f schlick:f0=0.04 -f f82:f0=0.9,tint=0.8 --paths 4000000\n"
      "  specula walk -d beckmann -a 0.3 -t 30 --outgoing 50,120 -f conductor:eta=0.2,kappa=3.1\n"
      "  specula walk -a 0.3 -t 0:80:20 --dielectric 1.5                # rough glass, light from the air");
  cmd->callback([o] { o->output.emit(walk_table(*o)); });
}

}  // namespace specula::cli
