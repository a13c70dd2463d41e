// specula lut: energy-compensation tables, the directional albedo E(μ, p) of a model on a grid of
// μ = cos θ_i and one parameter p, with E_avg(p), as CSV/JSON, an image or ready-to-paste code.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "build_info.h"
#include "cli.h"
#include "lut_code.h"
#include "specula/analysis/energy.h"
#include "specula/catalogue/catalogue.h"
#include "specula/exceptions.h"
#include "specula/expr/comment.h"
#include "specula/io/sha256.h"
#include "specula/io/values.h"
#include "specula/render/image_io.h"

namespace specula::cli {
namespace {

// The documented caps (analysis/energy.h); Ctrl-C stops any table.
using analysis::kMaxLutAxisValues, analysis::kMaxLutCells, analysis::kMaxLutAverages;
constexpr std::size_t kProgressFrom = 256;  // cells: smaller tables finish before progress matters

struct LutOptions {
  ModelOptions model;
  std::vector<std::string> sweeps;  ///< at most two: the rows' parameter p, then the slices' q
  std::string mu = "0.03125:1@32";
  bool average = false;
  bool schlick_split = false;
  std::string format = "csv";
  std::optional<int> round;
  std::string out;
  bool quiet = false;
};

struct Sweep {
  std::string name;  ///< empty: one row at the model's values
  std::vector<double> values;
  double power = 1;  ///< the values are evenly spaced in p^(1/power) (io::spacing_power)
};

void require_increasing(std::string_view option, const std::vector<double>& v) {
  for (std::size_t i = 1; i < v.size(); ++i)
    if (!(v[i] > v[i - 1])) throw InvalidArgument(fmt::format("{}: values must increase ({} after {})", option, v[i], v[i - 1]));
}

/// The code formats' lookups compute the cell: the values evenly spaced in x^(1/power).
void require_even_spacing(std::string_view option, const std::vector<double>& values, double power, std::string_view format) {
  if (values.size() < 3) return;
  std::vector<double> v;
  for (const double x : values) v.push_back(std::pow(x, 1 / power));
  const double step = (v.back() - v.front()) / static_cast<double>(v.size() - 1);
  for (std::size_t i = 1; i + 1 < v.size(); ++i)
    if (std::abs(v[i] - (v.front() + step * static_cast<double>(i))) > 1e-9 * (std::abs(v.front()) + std::abs(v.back())))
      throw InvalidArgument(
          fmt::format("{}: --format {} needs evenly spaced values (use a:b@count or a:b@count:powK)", option, format));
}

/// The `index`th --sweep, or one row at the model's values where there is none.
Sweep sweep_of(const LutOptions& o, std::size_t index) {
  if (o.sweeps.size() <= index) return {"", {0.0}};
  const std::string& text = o.sweeps[index];
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InvalidArgument(fmt::format("malformed --sweep '{}': expected NAME=LIST", text));
  const std::string_view list = std::string_view(text).substr(eq + 1);
  Sweep s{text.substr(0, eq), option_values("--sweep", list, kMaxLutAxisValues), io::spacing_power(list)};
  if (o.model.param_values().contains(s.name))
    throw InvalidArgument(fmt::format("--sweep {} is also given as --param {}", s.name, s.name));
  require_increasing("--sweep", s.values);
  return s;
}

/// The model at the sweep's value p, with the parameters in `fixed` set too (--schlick-split's f0,
/// a slice's q).
analysis::ModelAt model_at(const LutOptions& o, const Sweep& sweep, const ParamValues& fixed = {}) {
  return [spec = o.model.spec(), name = sweep.name, fixed](double p) {
    queries::ModelSpec at = spec;
    if (!name.empty()) at.params[name] = p;
    for (const auto& [param, value] : fixed) at.params[param] = value;
    return queries::make(at, queries::Spelling::option);
  };
}

/// One table of the output: the plain E, E at one end of F0 with --schlick-split, or one slice of
/// a second --sweep.
struct Channel {
  std::string suffix;  ///< "", "_f0_0" or "_f0_1"
  analysis::ModelAt at;
  analysis::AlbedoLut lut;
};

/// A second --sweep: one table per value q of its parameter, all on the first's grid.
std::vector<Channel> slices_of(const LutOptions& o, const Sweep& sweep, const Sweep& slices) {
  if (o.schlick_split) throw InvalidArgument("--schlick-split takes one --sweep (its two tables are the F0 axis)");
  if (slices.name == sweep.name) throw InvalidArgument(fmt::format("--sweep {} is given twice", sweep.name));
  std::vector<Channel> channels;
  for (const double q : slices.values) channels.push_back({"", model_at(o, sweep, {{slices.name, q}}), {}});
  return channels;
}

/// --schlick-split (Filament's DFG split, Karis 2013): where the model's Fresnel is Schlick's,
/// F = F0 + (F90 − F0)(1 − c)^p is linear in F0, and so is E: E(F0) = E(0) + F0 (E(1) − E(0))
/// exactly. Refused for any other model and where f0 is given or swept.
std::vector<Channel> channels_of(const LutOptions& o, const Sweep& sweep, const Sweep& slices) {
  if (!slices.name.empty()) return slices_of(o, sweep, slices);
  if (!o.schlick_split) return {{"", model_at(o, sweep), {}}};
  if (sweep.name == "f0" || o.model.param_values().contains("f0"))
    throw InvalidArgument("--schlick-split tabulates E at f0 = 0 and f0 = 1 itself: give f0 neither to --sweep nor to --param");
  const std::optional<fresnel::Channel> f = fresnel_of(model_at(o, sweep)(sweep.values.front()));
  if (!f || f->kind != fresnel::Kind::schlick)
    throw InvalidArgument(fmt::format("--schlick-split: {} has no Schlick Fresnel in f0 (E is linear in F0 only for "
                                      "Schlick's: ggx, cook-torrance)",
                                      o.model.id));
  return {{"_f0_0", model_at(o, sweep, {{"f0", 0.0}}), {}}, {"_f0_1", model_at(o, sweep, {{"f0", 1.0}}), {}}};
}

/// Progress lines on stderr at every tenth of a long table (off with --quiet).
analysis::Progress progress_of(const LutOptions& o, std::string_view what) {
  if (o.quiet) return {};
  return [what = std::string(what), next = std::size_t{1}](std::size_t done, std::size_t total) mutable {
    if (total < kProgressFrom || done * 10 < next * total) return;
    fmt::print(stderr, "lut: {} {}% ({}/{})\n", what, done * 100 / total, done, total);
    next = done * 10 / total + 1;
  };
}

/// A second --sweep's table: columns Q, P, mu, E (and E_avg), one row per cell, q-major.
io::Table sliced_table(const std::vector<Channel>& slices, const Sweep& sweep, const Sweep& q) {
  const analysis::AlbedoLut& lut = slices.front().lut;
  io::Table t;
  t.columns.push_back(q.name);
  if (!sweep.name.empty()) t.columns.push_back(sweep.name);
  t.columns.insert(t.columns.end(), {"mu", "E"});
  if (!lut.e_avg.empty()) t.columns.push_back("E_avg");
  t.key_columns = sweep.name.empty() ? 2 : 3;
  for (std::size_t k = 0; k < slices.size(); ++k)
    for (std::size_t i = 0; i < lut.p.size(); ++i)
      for (std::size_t j = 0; j < lut.mu.size(); ++j) {
        std::vector<double> row{q.values[k]};
        if (!sweep.name.empty()) row.push_back(lut.p[i]);
        row.insert(row.end(), {lut.mu[j], slices[k].lut.at(i, j)});
        if (!lut.e_avg.empty()) row.push_back(slices[k].lut.e_avg[i]);
        t.rows.push_back(std::move(row));
      }
  return t;
}

io::Table lut_table(const std::vector<Channel>& channels, const Sweep& sweep, const Sweep& slices) {
  if (!slices.name.empty()) return sliced_table(channels, sweep, slices);
  const analysis::AlbedoLut& lut = channels.front().lut;
  io::Table t;
  if (!sweep.name.empty()) t.columns.push_back(sweep.name);
  t.columns.push_back("mu");
  for (const Channel& c : channels) t.columns.push_back("E" + c.suffix);
  if (!lut.e_avg.empty())
    for (const Channel& c : channels) t.columns.push_back("E_avg" + c.suffix);
  t.key_columns = sweep.name.empty() ? 1 : 2;
  for (std::size_t i = 0; i < lut.p.size(); ++i)
    for (std::size_t j = 0; j < lut.mu.size(); ++j) {
      std::vector<double> row;
      if (!sweep.name.empty()) row.push_back(lut.p[i]);
      row.push_back(lut.mu[j]);
      for (const Channel& c : channels) row.push_back(c.lut.at(i, j));
      if (!lut.e_avg.empty())
        for (const Channel& c : channels) row.push_back(c.lut.e_avg[i]);
      t.rows.push_back(std::move(row));
    }
  return t;
}

std::string joined(const std::vector<double>& v) {
  std::string text;
  for (const double x : v) {
    if (!text.empty()) text += ',';
    text += io::format_number(x);
  }
  return text;
}

/// Where a table came from, in every file: the command that makes it again, specula's version and
/// the SHA-256 of its values (E p-major, then E_avg, as little-endian doubles: io/sha256.h).
struct Provenance {
  std::string command, version, sha256;
};

/// One line (an inline formula's line breaks made spaces), for a comment.
std::string provenance_line(const Provenance& p) {
  return expr::comment_text(fmt::format("{}; specula {}; sha256 of the values {}", p.command, p.version, p.sha256));
}

render::Metadata image_metadata(const LutOptions& o, const std::vector<Channel>& channels, const Sweep& sweep,
                                const Sweep& slices, const Provenance& provenance, const std::string& layout) {
  const analysis::AlbedoLut& lut = channels.front().lut;
  render::Metadata meta{{"Software", "specula " + provenance.version}, {"command", provenance.command},
                        {"sha256", provenance.sha256}, {"model", o.model.id}, {"layout", layout}, {"mu", joined(lut.mu)}};
  for (const auto& p : o.model.params) meta.emplace_back("param", p);
  if (!sweep.name.empty()) meta.emplace_back(sweep.name, joined(lut.p));
  if (!slices.name.empty()) meta.emplace_back(slices.name, joined(slices.values));
  for (std::size_t k = 0; k < channels.size(); ++k)
    if (!channels[k].lut.e_avg.empty())
      meta.emplace_back(slices.name.empty() ? "E_avg" + channels[k].suffix
                                            : fmt::format("E_avg at {} = {}", slices.name, io::format_number(slices.values[k])),
                        joined(channels[k].lut.e_avg));
  return meta;
}

std::string sweep_axis(const Sweep& sweep) { return sweep.name.empty() ? std::string("-") : sweep.name; }

/// A second --sweep's tables one below the other in an image: the layout, in words.
std::string slices_layout(const Sweep& sweep, const Sweep& slices, std::size_t rows) {
  return fmt::format("x: mu, y: {} (top row first) in blocks of {} rows, one per {} (first value on top): row "
                     "k * {} + i is {}_k, {}_i",
                     sweep_axis(sweep), rows, slices.name, rows, slices.name, sweep_axis(sweep));
}

/// The plain table in every channel; --schlick-split's E at f0 = 0 in R and at f0 = 1 in G; a
/// second --sweep's tables one below the other (slices_layout).
void write_exr_lut(const LutOptions& o, const std::vector<Channel>& channels, const Sweep& sweep, const Sweep& slices,
                   const Provenance& provenance) {
  const analysis::AlbedoLut& lut = channels.front().lut;
  const std::size_t blocks = slices.name.empty() ? 1 : channels.size(), rows = lut.p.size();
  render::Image image(static_cast<int>(lut.mu.size()), static_cast<int>(rows * blocks));
  for (std::size_t k = 0; k < blocks; ++k)
    for (std::size_t i = 0; i < rows; ++i)
      for (std::size_t j = 0; j < lut.mu.size(); ++j) {
        const double e = channels[k].lut.at(i, j);
        const bool split = slices.name.empty() && channels.size() > 1;
        image.set(static_cast<int>(j), static_cast<int>(k * rows + i),
                  split ? render::Rgb{e, channels[1].lut.at(i, j), 0} : render::Rgb{e, e, e});
      }
  std::string layout = slices.name.empty() ? "x: mu, y: " + sweep_axis(sweep) + " (top row first)"
                                           : slices_layout(sweep, slices, rows);
  if (slices.name.empty() && channels.size() > 1) layout += "; R: E at f0 = 0, G: E at f0 = 1, E(f0) = R + f0 (G - R)";
  render::write_exr(o.out, image, o.format == "exr-half" ? render::ExrPixel::half : render::ExrPixel::float32,
                    image_metadata(o, channels, sweep, slices, provenance, layout));
}

/// 16-bit codes round(65535 E / scale), scale = 1, or max E when a model reflects more than it
/// receives; the scale is in the metadata and on stderr. --schlick-split's two tables one below
/// the other (a gray image has one channel): E at f0 = 0 on top.
void write_png16_lut(const LutOptions& o, const std::vector<Channel>& channels, const Sweep& sweep, const Sweep& slices,
                     const Provenance& provenance) {
  double scale = 1;
  for (const Channel& c : channels) scale = std::max(scale, *std::max_element(c.lut.e.begin(), c.lut.e.end()));
  std::vector<std::uint16_t> codes;
  for (const Channel& c : channels)
    for (const double e : c.lut.e)
      codes.push_back(static_cast<std::uint16_t>(std::lround(std::clamp(e / scale, 0.0, 1.0) * 65535)));
  const analysis::AlbedoLut& lut = channels.front().lut;
  std::string layout = slices.name.empty() ? "x: mu, y: " + sweep_axis(sweep) + " (top row first)"
                                           : slices_layout(sweep, slices, lut.p.size());
  if (slices.name.empty() && channels.size() > 1)
    layout += fmt::format("; rows 0-{0}: E at f0 = 0, rows {1}-{2}: E at f0 = 1, E(f0) = E0 + f0 (E1 - E0)",
                          lut.p.size() - 1, lut.p.size(), 2 * lut.p.size() - 1);
  render::Metadata meta = image_metadata(o, channels, sweep, slices, provenance, layout);
  meta.emplace_back("scale", fmt::format("E = code / 65535 * {}", io::format_number(scale)));
  render::write_png16(o.out, static_cast<int>(lut.mu.size()), static_cast<int>(lut.p.size() * channels.size()), codes, meta);
  if (!o.quiet) fmt::print(stderr, "lut: 16-bit codes, E = code / 65535 * {}\n", io::format_number(scale));
}

std::string describe_model(const LutOptions& o) {
  std::string text = o.model.id;
  for (const auto& p : o.model.params) text += " " + p;
  return text;
}

std::string command_line(const LutOptions& o) {
  std::string text = fmt::format("specula lut --model {}", o.model.id);
  for (const auto& p : o.model.params) text += " -p " + p;
  for (const std::string& sweep : o.sweeps) text += " --sweep " + sweep;
  text += " --mu " + o.mu + (o.average ? " --average" : "") + (o.schlick_split ? " --schlick-split" : "") +
          " --format " + o.format;
  return text;
}

/// NumPy's .npy (format 1.0): E as little-endian float64 of shape (p, mu), or (mu) for one row;
/// --schlick-split's two tables as a first axis of 2 (E at f0 = 0, then at f0 = 1), a second
/// --sweep's as a first axis of its values: (q, p, mu). Its header takes no other keys, so the
/// provenance goes to stderr (unless --quiet).
std::string npy_of(const std::vector<Channel>& channels, const Sweep& sweep, const Sweep& slices) {
  const analysis::AlbedoLut& lut = channels.front().lut;
  std::string shape = sweep.name.empty() ? fmt::format("{},", lut.mu.size()) : fmt::format("{}, {}", lut.p.size(), lut.mu.size());
  shape = channels.size() > 1 || !slices.name.empty() ? fmt::format("({}, {})", channels.size(), shape) : "(" + shape + ")";
  std::string header = fmt::format("{{'descr': '<f8', 'fortran_order': False, 'shape': {}, }}", shape);
  header.append(63 - (10 + header.size()) % 64, ' ');  // the data starts on a multiple of 64 bytes
  header += '\n';
  std::string out = "\x93NUMPY";
  out += '\x01';
  out += '\x00';
  out += static_cast<char>(header.size() & 0xff);
  out += static_cast<char>(header.size() >> 8);
  std::vector<double> e;
  for (const Channel& c : channels) e.insert(e.end(), c.lut.e.begin(), c.lut.e.end());
  return out + header + io::little_endian_bytes(e);
}

/// The values hashed: each channel's E p-major, then each channel's E_avg.
Provenance provenance_of(const LutOptions& o, const std::vector<Channel>& channels) {
  std::vector<double> values;
  for (const Channel& c : channels) values.insert(values.end(), c.lut.e.begin(), c.lut.e.end());
  for (const Channel& c : channels) values.insert(values.end(), c.lut.e_avg.begin(), c.lut.e_avg.end());
  return {command_line(o), std::string(build_version()), io::sha256_of_doubles(values)};
}

/// The code formats' lookup error: each table's at its cells' centres, or a second --sweep's
/// trilinear lookup's at the centres of its cells in (q, p, μ).
std::vector<LutChannel> code_channels(const LutOptions& o, const std::vector<Channel>& channels, const Sweep& sweep,
                                      const Sweep& slices) {
  std::vector<LutChannel> code;
  if (slices.name.empty()) {
    for (const Channel& c : channels)
      code.push_back({c.suffix, &c.lut, analysis::lut_interpolation_error(c.lut, c.at, progress_of(o, "interpolation error" + c.suffix))});
    return code;
  }
  std::vector<analysis::AlbedoLut> tables;
  for (const Channel& c : channels) tables.push_back(c.lut);
  const analysis::LutError error = analysis::lut_interpolation_error(
      tables, slices.values, slices.power,
      [&o, &sweep, &slices](double q) { return model_at(o, sweep, {{slices.name, q}}); },
      progress_of(o, "interpolation error"));
  for (const Channel& c : channels) code.push_back({c.suffix, &c.lut, error});
  return code;
}

void run(const LutOptions& o) {
  if ((o.format == "exr" || o.format == "exr-half" || o.format == "png16" || o.format == "npy") && o.out.empty())
    throw InvalidArgument(fmt::format("--format {} needs --out FILE", o.format));
  if (o.sweeps.size() > 2) throw InvalidArgument("--sweep: at most two axes (p, then q)");
  const Sweep sweep = sweep_of(o, 0), slices = sweep_of(o, 1);
  const std::vector<double> mu = option_values("--mu", o.mu, kMaxLutAxisValues);
  require_increasing("--mu", mu);
  for (const double m : mu)
    if (!(m >= analysis::kMinMu && m <= 1))
      throw InvalidArgument(fmt::format("--mu: {} is outside [{:g}, 1]", m, analysis::kMinMu));
  // The cells' cost counts each table: --schlick-split's two, a second --sweep's one per value.
  const std::size_t tables = o.schlick_split ? 2 : slices.values.size();
  const std::string of_tables = tables > 1 ? fmt::format("{} tables of ", tables) : "";
  if (tables * sweep.values.size() * mu.size() > kMaxLutCells)
    throw InvalidArgument(fmt::format("{}{} x {} cells is more than {}", of_tables, sweep.values.size(), mu.size(), kMaxLutCells));
  if (o.average && tables * sweep.values.size() > kMaxLutAverages)
    throw InvalidArgument(fmt::format("--average: {}{} values of {} is more than {} (each E_avg costs 100-400 cells)",
                                      of_tables, sweep.values.size(), sweep.name, kMaxLutAverages));
  const bool code = o.format == "cpp" || o.format == "glsl" || o.format == "hlsl";
  const double mu_power = io::spacing_power(o.mu);
  if (code) {
    require_even_spacing("--mu", mu, mu_power, o.format), require_even_spacing("--sweep", sweep.values, sweep.power, o.format);
    require_even_spacing("--sweep", slices.values, slices.power, o.format);
  }
  std::vector<Channel> channels = channels_of(o, sweep, slices);
  for (const Channel& c : channels) c.at(sweep.values.front());  // a bad model or parameter fails before any work
  // A second --sweep's tables report the cells of all of them as each table finishes.
  const analysis::Progress all_cells = slices.name.empty() ? analysis::Progress{} : progress_of(o, "cells");
  const std::size_t per_table = sweep.values.size() * mu.size();
  for (std::size_t k = 0; k < channels.size(); ++k) {
    Channel& c = channels[k];
    c.lut = analysis::albedo_lut(c.at, sweep.values, mu, o.average,
                                 slices.name.empty() ? progress_of(o, "cells" + c.suffix) : analysis::Progress{});
    c.lut.p_power = sweep.power, c.lut.mu_power = mu_power;  // how the code's lookup interpolates
    if (all_cells) all_cells((k + 1) * per_table, channels.size() * per_table);
  }
  const Provenance provenance = provenance_of(o, channels);
  if (o.format == "exr" || o.format == "exr-half") return write_exr_lut(o, channels, sweep, slices, provenance);
  if (o.format == "png16") return write_png16_lut(o, channels, sweep, slices, provenance);
  if (o.format == "npy") {
    write_output(o.out, npy_of(channels, sweep, slices));
    if (!o.quiet) fmt::print(stderr, "lut: {}\n", provenance_line(provenance));
    return;
  }
  if (!code) {
    io::Table table = lut_table(channels, sweep, slices);
    table.meta = {{"model", o.model.id}, {"command", provenance.command}, {"version", provenance.version},
                  {"sha256", provenance.sha256}};
    if (o.format == "json") return write_output(o.out, io::to_json(table, o.round));
    return write_output(o.out, "# " + provenance_line(provenance) + "\n" + io::to_csv(table, o.round));
  }
  const LutDescription description{provenance_line(provenance), describe_model(o), sweep.name, mu_power, sweep.power,
                                   slices.name, slices.values, slices.power};
  const std::vector<LutChannel> tables_in_code = code_channels(o, channels, sweep, slices);
  if (o.format == "cpp") return write_output(o.out, lut_cpp(tables_in_code, description));
  write_output(o.out, o.format == "glsl" ? lut_glsl(tables_in_code, description) : lut_hlsl(tables_in_code, description));
}

}  // namespace

void add_lut_command(CLI::App& app) {
  auto o = std::make_shared<LutOptions>();
  auto* cmd = app.add_subcommand("lut", "Energy-compensation tables: the albedo E(μ, p) and E_avg(p) of a model");
  o->model.add_to(*cmd);
  cmd->add_option("--sweep", o->sweeps,
                  "The table's parameter axis: NAME=LIST (e.g. alpha=0.05:1@32, or alpha=0.01:1@32:pow2 uniform in "
                  "sqrt(alpha); at most 1024 values, increasing); without it, one row at the model's values. Given "
                  "twice, the second is a third axis q: one table per value (e.g. --sweep alpha=... --sweep f0=...)")
      ->type_name("NAME=LIST")->expected(1)->take_all();
  cmd->add_option("--mu", o->mu, "μ = cos θ_i values, in [1e-9, 1], increasing: list or range, at most 1024 (a:b@count:pow3 crowds them toward grazing)")
      ->capture_default_str();
  cmd->add_flag("--average", o->average,
                "Also E_avg(p) = 2∫₀¹ E(μ) μ dμ (by quadrature in μ, not from the grid); at most 256 values of p");
  cmd->add_flag("--schlick-split", o->schlick_split,
                "Two tables, E at f0 = 0 and at f0 = 1, for a model with Schlick's Fresnel (ggx, cook-torrance): E is "
                "linear in F0, E(F0) = E0 + F0 (E1 - E0) exactly (Filament's DFG split); every format holds both");
  cmd->add_option("--format", o->format, "csv, json, exr (float), exr-half, png16 (16-bit gray), npy (NumPy float64), "
                                         "cpp, glsl or hlsl (arrays with their bilinear lookup and its measured error)")
      ->capture_default_str()->check(CLI::IsMember({"csv", "json", "exr", "exr-half", "png16", "npy", "cpp", "glsl", "hlsl"}));
  cmd->add_option("--round", o->round, "csv/json: print numbers with this many decimals")->check(CLI::Range(0, 17));
  cmd->add_option("--out,-o", o->out, "Write to FILE (atomically) instead of stdout; needed for exr, exr-half, png16 and npy");
  cmd->add_flag("--quiet,-q", o->quiet, "No progress on stderr");
  cmd->footer(
      "E(μ, p) = ρ(acos μ) by the deterministic cubature (≥ 8 digits), every cell in parallel; at most\n"
      "65536 cells. CSV: columns PARAM,mu,E (and E_avg, repeated on each row of its p), one row per cell,\n"
      "p-major. Images: μ along x, p along y (first value at the top). npy: E of shape (p, μ). cpp, glsl\n"
      "and hlsl state the bilinear lookup's error measured against the cubature at the cells' centres\n"
      "(which doubles the work). Every file says where it came from: the command, specula's version and\n"
      "the SHA-256 of its values (E p-major, then E_avg, as little-endian doubles): CSV on a first line\n"
      "'# ...', JSON and image metadata as keys, code in its header comment; npy's header takes no other\n"
      "keys, so npy prints it on stderr.\n"
      "--schlick-split: CSV and JSON columns E_f0_0, E_f0_1 (and E_avg_f0_0, E_avg_f0_1); EXR in R and G; png16\n"
      "the two tables one below the other; npy of shape (2, p, mu); code has both and energy(mu, p, f0).\n"
      "A second --sweep q (a third axis where E is not linear in it, e.g. cook-torrance-1982's f0): CSV/JSON\n"
      "columns Q,P,mu,E, q-major; images the tables one below the other; npy (q, p, mu); code a trilinear\n"
      "energy(mu, p, q) with its measured error. At most 65536 cells in all.\n"
      "Other parameters take -p NAME=VALUE. Examples:\n"
      "  specula lut --model ggx --sweep alpha=0.05:1@32 --mu 0.03125:1@32 --average --out ggx_E.csv\n"
      "  specula lut --model ggx --sweep alpha=0.05:1@16 --mu 0.05:1@16 --average --format glsl -o ggx_E.glsl\n"
      "  specula lut --model lambert -p rho=0.5 --mu 0.1:1@10 --average\n"
      "  specula lut --model ggx --sweep alpha=0.05:1@64 --mu 0.015625:1@64 --format png16 -o ggx_E.png\n"
      "  specula lut --model ggx --sweep alpha=0.05:1@32 --mu 0.03125:1@32 --schlick-split --format glsl -o dfg.glsl\n"
      "  specula lut --model ggx --sweep alpha=0.01:1@32:pow2 --mu 0.001:1@32:pow3 --format cpp -o ggx_E.h   # spaced for accuracy");
  cmd->callback([o] { run(*o); });
}

}  // namespace specula::cli
