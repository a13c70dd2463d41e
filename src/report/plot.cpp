#include "specula/report/plot.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numbers>
#include <string_view>
#include <utility>

#include "specula/exceptions.h"
#include "specula/render/canvas.h"

namespace specula::report {
namespace {

constexpr double kLeft = 74, kRight = 18, kTop = 36, kBottom = 54;
constexpr const char* kFont = "font-family=\"Helvetica, Arial, sans-serif\"";
constexpr const char* kGrid = "#e3e3e3";
constexpr const char* kInk = "#222";
constexpr double kLabelCharWidth = 5.6;  // a 10 px sans-serif character, on average

/// Characters (code points) of UTF-8 text, for estimating its drawn width.
std::size_t glyphs(std::string_view text) {
  return static_cast<std::size_t>(std::count_if(text.begin(), text.end(), [](char ch) { return (ch & 0xC0) != 0x80; }));
}

bool usable(double v, Scale scale) { return std::isfinite(v) && (scale == Scale::linear || v > 0); }

/// FNV-1a of the text: ids that stay unique when several charts share one HTML page.
std::string id_of(std::string_view text) {
  std::uint64_t h = 1469598103934665603ull;
  for (const char ch : text) h = (h ^ static_cast<unsigned char>(ch)) * 1099511628211ull;
  return fmt::format("c{:016x}", h);
}

std::string dash_attribute(Stroke stroke) {
  switch (stroke) {
    case Stroke::dashed: return " stroke-dasharray=\"7 4\"";
    case Stroke::dotted: return " stroke-dasharray=\"2 3\"";
    case Stroke::solid:
    case Stroke::none: return "";
  }
  unreachable();
}

// One axis mapped onto pixels, with its ticks.
class AxisMap {
 public:
  AxisMap(const Axis& axis, double data_lo, double data_hi, double px_lo, double px_hi)
      : scale_(axis.scale), px_lo_(px_lo), px_hi_(px_hi) {
    if (scale_ == Scale::log) {
      lo_ = axis.min.value_or(std::pow(10, std::floor(std::log10(data_lo))));
      hi_ = axis.max.value_or(std::pow(10, std::ceil(std::log10(data_hi))));
      if (hi_ <= lo_) hi_ = lo_ * 10;
      ticks_ = log_ticks(lo_, hi_);
    } else {
      if (data_hi <= data_lo) {
        const double pad = data_lo == 0 ? 1 : std::abs(data_lo) * 0.1;
        data_lo -= pad;
        data_hi += pad;
      }
      const auto padded = linear_ticks(data_lo, data_hi);
      lo_ = axis.min.value_or(padded.front());
      hi_ = axis.max.value_or(padded.back());
      if (hi_ <= lo_) hi_ = lo_ + 1;
      ticks_ = linear_ticks(lo_, hi_);
      step_ = ticks_.size() > 1 ? ticks_[1] - ticks_[0] : 1;
    }
    std::erase_if(ticks_, [&](double t) { return t < lo_ * (1 - 1e-12) - 1e-300 || t > hi_ * (1 + 1e-12) + 1e-300; });
  }

  double operator()(double v) const {
    const double f = scale_ == Scale::log ? (std::log10(v) - std::log10(lo_)) / (std::log10(hi_) - std::log10(lo_))
                                          : (v - lo_) / (hi_ - lo_);
    return px_lo_ + f * (px_hi_ - px_lo_);
  }
  const std::vector<double>& ticks() const { return ticks_; }
  bool major(double tick) const {
    if (scale_ == Scale::linear) return true;
    const double e = std::log10(tick);
    return std::abs(e - std::round(e)) < 1e-9;
  }
  /// A tick label as plain text (log decades beyond 10^±3 as 1e-6).
  std::string plain_label(double tick) const {
    if (scale_ == Scale::linear) return tick_text(tick, step_);
    const int e = static_cast<int>(std::lround(std::log10(tick)));
    if (e >= -3 && e <= 4) return tick_text(tick, std::pow(10, std::min(e, 0)));
    return fmt::format("1e{}", e);
  }
  /// SVG text content of a tick label (log decades beyond 10^±3 as 10 with a superscript).
  std::string label(double tick) const {
    if (scale_ == Scale::linear) return tick_text(tick, step_);
    const int e = static_cast<int>(std::lround(std::log10(tick)));
    if (e >= -3 && e <= 4) return tick_text(tick, std::pow(10, std::min(e, 0)));
    return fmt::format("10<tspan dy=\"-6\" font-size=\"8\">{}</tspan>", e < 0 ? fmt::format("\u2212{}", -e) : std::to_string(e));
  }

 private:
  Scale scale_;
  double lo_ = 0, hi_ = 1, step_ = 1;
  double px_lo_, px_hi_;
  std::vector<double> ticks_;
};

std::pair<double, double> data_range(const Chart& chart, bool x_axis) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& s : chart.series)
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
      if (usable(s.x[i], chart.x.scale) && usable(s.y[i], chart.y.scale)) {
        const double v = x_axis ? s.x[i] : s.y[i];
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
  return {lo, hi};
}

}  // namespace

bool has_points(const Chart& chart) {
  const auto [lo, hi] = data_range(chart, true);
  return lo <= hi;
}

namespace {

void validate(const Chart& chart) {
  for (const auto& s : chart.series) {
    if (s.x.size() != s.y.size())
      throw InvalidArgument(fmt::format("chart '{}': series '{}' has {} x and {} y values", chart.title, s.name,
                                        s.x.size(), s.y.size()));
    if (!s.point_labels.empty() && s.point_labels.size() != s.x.size())
      throw InvalidArgument(fmt::format("chart '{}': series '{}' has {} points and {} labels", chart.title, s.name,
                                        s.x.size(), s.point_labels.size()));
  }
  if (!has_points(chart)) throw InvalidArgument(fmt::format("chart '{}' has no point to draw", chart.title));
}

std::string svg_open(int width, int height, const std::string& title) {
  return fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" {2} "
      "font-size=\"11\" role=\"img\" aria-label=\"{3}\">\n<title>{3}</title>\n"
      "<rect width=\"{0}\" height=\"{1}\" fill=\"#fff\"/>\n",
      width, height, kFont, xml_escape(title));
}

std::string axes_svg(const Chart& chart, const AxisMap& xs, const AxisMap& ys, double x0, double x1, double y0,
                     double y1) {
  std::string out;
  for (const double t : xs.ticks()) {
    const double px = xs(t);
    out += fmt::format("<line x1=\"{0:.2f}\" y1=\"{1:.2f}\" x2=\"{0:.2f}\" y2=\"{2:.2f}\" stroke=\"{3}\"/>\n", px, y0, y1,
                       xs.major(t) ? kGrid : "#f2f2f2");
    out += fmt::format("<line x1=\"{0:.2f}\" y1=\"{1:.2f}\" x2=\"{0:.2f}\" y2=\"{2:.2f}\" stroke=\"{3}\"/>\n", px, y0,
                       y0 + (xs.major(t) ? 5 : 3), kInk);
    if (xs.major(t))
      out += fmt::format("<text x=\"{:.2f}\" y=\"{:.2f}\" text-anchor=\"middle\">{}</text>\n", px, y0 + 18, xs.label(t));
  }
  for (const double t : ys.ticks()) {
    const double py = ys(t);
    out += fmt::format("<line x1=\"{0:.2f}\" y1=\"{1:.2f}\" x2=\"{2:.2f}\" y2=\"{1:.2f}\" stroke=\"{3}\"/>\n", x0, py, x1,
                       ys.major(t) ? kGrid : "#f2f2f2");
    out += fmt::format("<line x1=\"{0:.2f}\" y1=\"{1:.2f}\" x2=\"{2:.2f}\" y2=\"{1:.2f}\" stroke=\"{3}\"/>\n",
                       x0 - (ys.major(t) ? 5 : 3), py, x0, kInk);
    if (ys.major(t))
      out += fmt::format("<text x=\"{:.2f}\" y=\"{:.2f}\" text-anchor=\"end\">{}</text>\n", x0 - 8, py + 4, ys.label(t));
  }
  out += fmt::format("<rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" fill=\"none\" stroke=\"{}\"/>\n",
                     x0, y1, x1 - x0, y0 - y1, kInk);
  out += fmt::format("<text x=\"{:.2f}\" y=\"{}\" text-anchor=\"middle\" font-size=\"13\">{}</text>\n", (x0 + x1) / 2,
                     chart.height - 12, xml_escape(chart.x.label));
  out += fmt::format(
      "<text transform=\"translate(16 {:.2f}) rotate(-90)\" text-anchor=\"middle\" font-size=\"13\">{}</text>\n",
      (y0 + y1) / 2, xml_escape(chart.y.label));
  out += fmt::format("<text x=\"{:.2f}\" y=\"22\" text-anchor=\"middle\" font-size=\"14\" font-weight=\"bold\">{}</text>\n",
                     (x0 + x1) / 2, xml_escape(chart.title));
  return out;
}

std::string series_svg(const Chart& chart, const Series& s, const AxisMap& xs, const AxisMap& ys) {
  std::string out, points;
  auto flush = [&] {
    if (s.stroke != Stroke::none && points.find(' ') != points.rfind(' '))
      out += fmt::format("<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"1.8\" stroke-linejoin=\"round\"{} points=\"{}\"/>\n",
                         s.colour, dash_attribute(s.stroke), points);
    points.clear();
  };
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    if (!usable(s.x[i], chart.x.scale) || !usable(s.y[i], chart.y.scale)) {
      flush();
      continue;
    }
    points += fmt::format(" {:.2f},{:.2f}", xs(s.x[i]), ys(s.y[i]));
  }
  flush();
  std::pair<double, double> last_label{0, 0};  // the horizontal extent of the last label drawn above
  double last_label_y = 0;
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    if (!usable(s.x[i], chart.x.scale) || !usable(s.y[i], chart.y.scale)) continue;
    if (s.markers)
      out += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"3.2\" fill=\"{}\"/>\n", xs(s.x[i]), ys(s.y[i]), s.colour);
    if (s.point_labels.empty()) continue;
    // A label that would run into the previous one (drawn above its point) goes below its own.
    const double x = xs(s.x[i]) + 5, y = ys(s.y[i]);
    const double end = x + kLabelCharWidth * static_cast<double>(glyphs(s.point_labels[i]));
    const bool below = x < last_label.second && last_label.first < end && std::abs(y - last_label_y) < 12;
    out += fmt::format("<text x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"10\" fill=\"{}\">{}</text>\n", x,
                       below ? y + 14 : y - 5, kInk, xml_escape(s.point_labels[i]));
    last_label = below ? std::pair{0.0, 0.0} : std::pair{x, end};
    last_label_y = y;
  }
  return out;
}

std::string legend_svg(const Chart& chart, double x0, double x1, double y0, double y1) {
  std::vector<const Series*> entries;
  for (const auto& s : chart.series)
    if (!s.name.empty()) entries.push_back(&s);
  if (entries.empty() || chart.legend == Legend::none) return "";
  std::size_t longest = 0;
  for (const auto* s : entries) longest = std::max(longest, glyphs(s->name));
  const double w = 40 + 6.2 * static_cast<double>(longest), h = 8 + 16 * static_cast<double>(entries.size());
  const bool right = chart.legend == Legend::top_right || chart.legend == Legend::bottom_right;
  const bool top = chart.legend == Legend::top_right || chart.legend == Legend::top_left;
  const double lx = right ? x1 - w - 8 : x0 + 8, ly = top ? y1 + 8 : y0 - h - 8;
  std::string out = fmt::format(
      "<g class=\"legend\"><rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" fill=\"#fff\" "
      "fill-opacity=\"0.9\" stroke=\"#bbb\"/>\n",
      lx, ly, w, h);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const Series& s = *entries[i];
    const double y = ly + 12 + 16 * static_cast<double>(i);
    if (s.stroke != Stroke::none)
      out += fmt::format("<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"{}\" stroke-width=\"1.8\"{}/>\n",
                         lx + 6, y, lx + 30, y, s.colour, dash_attribute(s.stroke));
    if (s.markers || s.stroke == Stroke::none)
      out += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"3.2\" fill=\"{}\"/>\n", lx + 18, y, s.colour);
    out += fmt::format("<text x=\"{:.2f}\" y=\"{:.2f}\">{}</text>\n", lx + 35, y + 4, xml_escape(s.name));
  }
  return out + "</g>\n";
}

}  // namespace

std::vector<double> linear_ticks(double lo, double hi, int target) {
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return {lo};
  const double raw = (hi - lo) / std::max(target, 1);
  const double magnitude = std::pow(10, std::floor(std::log10(raw)));
  const double residual = raw / magnitude;
  const double step = magnitude * (residual <= 1 ? 1 : residual <= 2 ? 2 : residual <= 5 ? 5 : 10);
  const auto first = static_cast<long long>(std::floor(lo / step + 1e-9));
  const auto last = static_cast<long long>(std::ceil(hi / step - 1e-9));
  std::vector<double> ticks;
  for (long long k = first; k <= last; ++k) ticks.push_back(static_cast<double>(k) * step);
  return ticks;
}

std::vector<double> log_ticks(double lo, double hi) {
  if (!(lo > 0) || !(hi > lo)) return {lo};
  const int e0 = static_cast<int>(std::floor(std::log10(lo) + 1e-9));
  const int e1 = static_cast<int>(std::ceil(std::log10(hi) - 1e-9));
  const bool minor = e1 - e0 < 3;
  std::vector<double> ticks;
  for (int e = e0; e <= e1; ++e) {
    const double decade = std::pow(10, e);
    ticks.push_back(decade);
    if (minor && e < e1)
      for (int m = 2; m <= 9; ++m) ticks.push_back(m * decade);
  }
  return ticks;
}

std::string tick_text(double value, double step) {
  if (std::abs(value) < step * 1e-9) return "0";
  const double magnitude = std::abs(value);
  if (magnitude >= 1e5 || magnitude < 1e-3) return fmt::format("{:.3g}", value);
  const int decimals = std::clamp(static_cast<int>(std::ceil(-std::log10(step) - 1e-9)), 0, 8);
  std::string text = fmt::format("{:.{}f}", value, decimals);
  return text[0] == '-' ? fmt::format("\u2212{}", text.substr(1)) : text;
}

std::string xml_escape(std::string_view text) {
  std::string out;
  for (const char ch : text) {
    switch (ch) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += ch;
    }
  }
  return out;
}

std::string model_colour(std::string_view id) {
  static const std::pair<std::string_view, std::string_view> palette[] = {
      {"phong", "#000000"},           {"phong-normalized", "#4d4d4d"},   {"phong-lafortune", "#8c8c8c"},
      {"blinn-phong", "#56b4e9"},     {"blinn-phong-normalized", "#1f6fa8"}, {"blinn-phong-approx", "#8fc6e8"},
      {"schlick", "#0072b2"},         {"schlick-normalized", "#cc79a7"}, {"schlick-modified", "#8e4585"},
      {"gauss", "#009e73"},           {"log", "#d55e00"},                {"log-normalized", "#e69f00"},
      {"log-paper", "#8c510a"},       {"lambert", "#bab0ac"},            {"ward", "#59a14f"},
      {"ward-duer", "#8cd17d"},       {"ward-gmd", "#2e6b2e"},           {"cook-torrance-1982", "#e15759"},
      {"cook-torrance", "#b07aa1"},   {"ggx", "#4e79a7"}};
  for (const auto& [model, colour] : palette)
    if (model == id) return std::string(colour);
  const std::string hash = id_of(id);
  return fmt::format("#{}", std::string_view(hash).substr(hash.size() - 6));
}

std::string to_svg(const Chart& chart) {
  validate(chart);
  const double x0 = kLeft, x1 = chart.width - kRight, y0 = chart.height - kBottom, y1 = kTop;
  const auto [xlo, xhi] = data_range(chart, true);
  const auto [ylo, yhi] = data_range(chart, false);
  const AxisMap xs(chart.x, xlo, xhi, x0, x1), ys(chart.y, ylo, yhi, y0, y1);
  std::string clip_key = chart.title;
  for (const auto& s : chart.series) clip_key += "|" + s.name + std::to_string(s.x.size());
  const std::string clip = id_of(clip_key);
  std::string out = svg_open(chart.width, chart.height, chart.title);
  out += fmt::format("<defs><clipPath id=\"{}\"><rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\"/>"
                     "</clipPath></defs>\n",
                     clip, x0, y1, x1 - x0, y0 - y1);
  out += axes_svg(chart, xs, ys, x0, x1, y0, y1);
  out += fmt::format("<g clip-path=\"url(#{})\">\n", clip);
  for (const auto& s : chart.series) out += series_svg(chart, s, xs, ys);
  out += "</g>\n" + legend_svg(chart, x0, x1, y0, y1);
  return out + "</svg>\n";
}

render::Srgb8Image to_image(const Chart& chart) {
  using render::Canvas;
  validate(chart);
  const double x0 = kLeft, x1 = chart.width - kRight, y0 = chart.height - kBottom, y1 = kTop;
  const auto [xlo, xhi] = data_range(chart, true);
  const auto [ylo, yhi] = data_range(chart, false);
  const AxisMap xs(chart.x, xlo, xhi, x0, x1), ys(chart.y, ylo, yhi, y0, y1);
  Canvas canvas(chart.width, chart.height);
  const render::Srgb8 ink = render::parse_hex_colour("#222222"), grid = render::parse_hex_colour(kGrid),
                      minor = render::parse_hex_colour("#f2f2f2");
  for (const double t : xs.ticks()) {
    canvas.line(xs(t), y0, xs(t), y1, xs.major(t) ? grid : minor);
    canvas.line(xs(t), y0, xs(t), y0 + (xs.major(t) ? 5 : 3), ink);
    if (xs.major(t)) canvas.text(xs.plain_label(t), xs(t), y0 + 18, 11, Canvas::Anchor::middle, ink);
  }
  for (const double t : ys.ticks()) {
    canvas.line(x0, ys(t), x1, ys(t), ys.major(t) ? grid : minor);
    canvas.line(x0 - (ys.major(t) ? 5 : 3), ys(t), x0, ys(t), ink);
    if (ys.major(t)) canvas.text(ys.plain_label(t), x0 - 8, ys(t) + 4, 11, Canvas::Anchor::end, ink);
  }
  for (const auto& [ax, ay, bx, by] : {std::array{x0, y0, x1, y0}, {x1, y0, x1, y1}, {x1, y1, x0, y1}, {x0, y1, x0, y0}})
    canvas.line(ax, ay, bx, by, ink);
  canvas.text(chart.x.label, (x0 + x1) / 2, chart.height - 12, 13, Canvas::Anchor::middle, ink);
  canvas.text(chart.y.label, 20, (y0 + y1) / 2, 13, Canvas::Anchor::middle, ink, true);
  canvas.text(chart.title, (x0 + x1) / 2, 22, 14, Canvas::Anchor::middle, ink);
  const auto inside = [&](double x, double y) { return x >= x0 - 0.5 && x <= x1 + 0.5 && y >= y1 - 0.5 && y <= y0 + 0.5; };
  for (const auto& s : chart.series) {
    const render::Srgb8 colour = render::parse_hex_colour(s.colour);
    bool joined = false;  // the previous point is drawn and the line continues from (last_x, last_y)
    double last_x = 0, last_y = 0;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!usable(s.x[i], chart.x.scale) || !usable(s.y[i], chart.y.scale)) {
        joined = false;
        continue;
      }
      const double x = xs(s.x[i]), y = ys(s.y[i]);
      if (joined && s.stroke != Stroke::none && inside(x, y) && inside(last_x, last_y))
        canvas.line(last_x, last_y, x, y, colour, 1.8);
      if (s.markers && inside(x, y)) canvas.dot(x, y, 3.2, colour);
      if (!s.point_labels.empty() && inside(x, y))
        canvas.text(s.point_labels[i], x + 5, y - 5, 10, Canvas::Anchor::start, ink);
      joined = true;
      last_x = x;
      last_y = y;
    }
  }
  std::vector<const Series*> entries;
  for (const auto& s : chart.series)
    if (!s.name.empty()) entries.push_back(&s);
  if (!entries.empty() && chart.legend != Legend::none) {
    int longest = 0;
    for (const auto* s : entries) longest = std::max(longest, canvas.text_width(s->name, 11));
    const double w = 44 + longest, h = 8 + 16 * static_cast<double>(entries.size());
    const bool right = chart.legend == Legend::top_right || chart.legend == Legend::bottom_right;
    const bool top = chart.legend == Legend::top_right || chart.legend == Legend::top_left;
    const double lx = right ? x1 - w - 8 : x0 + 8, ly = top ? y1 + 8 : y0 - h - 8;
    for (double y = ly; y <= ly + h; y += 1) canvas.line(lx, y, lx + w, y, {255, 255, 255});
    for (const auto& [ax, ay, bx, by] : {std::array{lx, ly, lx + w, ly}, {lx + w, ly, lx + w, ly + h}, {lx + w, ly + h, lx, ly + h}, {lx, ly + h, lx, ly}})
      canvas.line(ax, ay, bx, by, render::parse_hex_colour("#bbbbbb"));
    for (std::size_t i = 0; i < entries.size(); ++i) {
      const Series& s = *entries[i];
      const double y = ly + 12 + 16 * static_cast<double>(i);
      const render::Srgb8 colour = render::parse_hex_colour(s.colour);
      if (s.stroke != Stroke::none) canvas.line(lx + 6, y, lx + 30, y, colour, 1.8);
      if (s.markers || s.stroke == Stroke::none) canvas.dot(lx + 18, y, 3.2, colour);
      canvas.text(s.name, lx + 35, y + 4, 11, Canvas::Anchor::start, ink);
    }
  }
  return canvas.image();
}

std::string to_svg(const PolarChart& chart) {
  double r_max = 0;
  for (const auto& s : chart.series) {
    if (s.angle_deg.size() != s.radius.size())
      throw InvalidArgument(fmt::format("polar chart '{}': series '{}' has {} angles and {} radii", chart.title,
                                        s.name, s.angle_deg.size(), s.radius.size()));
    for (const double r : s.radius)
      if (std::isfinite(r)) r_max = std::max(r_max, r);
  }
  if (!(r_max > 0)) throw InvalidArgument(fmt::format("polar chart '{}' has nothing to draw", chart.title));
  const std::vector<double> rings = linear_ticks(0, r_max, 4);
  const double outer = rings.back();
  const double cx = chart.size / 2.0, radius_px = chart.size * 0.40, cy = 44 + radius_px * 1.12;
  const auto named = std::count_if(chart.series.begin(), chart.series.end(), [](const PolarSeries& s) { return !s.name.empty(); });
  const double height = cy + 34 + 15 * static_cast<double>(named);
  auto at = [&](double angle_deg, double r) {
    const double a = angle_deg * std::numbers::pi / 180, scaled = r / outer * radius_px;
    return std::pair{cx + scaled * std::sin(a), cy - scaled * std::cos(a)};
  };
  std::string out = svg_open(chart.size, static_cast<int>(height), chart.title);
  out += fmt::format("<text x=\"{:.2f}\" y=\"20\" text-anchor=\"middle\" font-size=\"14\" font-weight=\"bold\">{}</text>\n",
                     cx, xml_escape(chart.title));
  for (const double ring : rings) {
    if (ring <= 0) continue;
    const double r = ring / outer * radius_px;
    out += fmt::format("<path d=\"M {:.2f} {:.2f} A {:.2f} {:.2f} 0 0 1 {:.2f} {:.2f}\" fill=\"none\" stroke=\"{}\"/>\n",
                       cx - r, cy, r, r, cx + r, cy, kGrid);
    out += fmt::format("<text x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"10\" fill=\"#666\">{}</text>\n", cx + 3, cy - r - 2,
                       tick_text(ring, rings[1] - rings[0]));
  }
  for (int a = -90; a <= 90; a += 30) {
    const auto [x, y] = at(a, outer);
    out += fmt::format("<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"{}\"/>\n", cx, cy, x, y, kGrid);
    const auto [lx, ly] = at(a, outer * 1.09);
    out += fmt::format("<text x=\"{:.2f}\" y=\"{:.2f}\" text-anchor=\"middle\">{}\u00b0</text>\n", lx, ly + 4,
                       a < 0 ? fmt::format("\u2212{}", -a) : std::to_string(a));
  }
  if (chart.incident_deg >= 0) {
    const auto [lx, ly] = at(-chart.incident_deg, outer * 1.0);
    out += fmt::format("<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"{}\" stroke-width=\"1.2\" "
                       "stroke-dasharray=\"4 3\"/>\n<text x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"10\" text-anchor=\"end\">"
                       "light</text>\n",
                       cx, cy, lx, ly, kInk, (cx + lx) / 2 - 4, (cy + ly) / 2);
  }
  for (const auto& s : chart.series) {
    std::string points;
    for (std::size_t i = 0; i < s.radius.size(); ++i) {
      if (!std::isfinite(s.radius[i]) || !std::isfinite(s.angle_deg[i])) continue;
      const auto [x, y] = at(s.angle_deg[i], std::max(s.radius[i], 0.0));
      points += fmt::format(" {:.2f},{:.2f}", x, y);
    }
    out += fmt::format("<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"1.8\"{} points=\"{}\"/>\n", s.colour,
                       dash_attribute(s.stroke), points);
  }
  out += fmt::format("<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"{}\"/>\n", cx - radius_px * 1.05,
                     cy, cx + radius_px * 1.05, cy, kInk);
  double ly = cy + 22;
  for (const auto& s : chart.series) {
    if (s.name.empty()) continue;
    out += fmt::format("<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"{}\" stroke-width=\"1.8\"{}/>"
                       "<text x=\"{:.2f}\" y=\"{:.2f}\">{}</text>\n",
                       cx - radius_px, ly, cx - radius_px + 24, ly, s.colour, dash_attribute(s.stroke),
                       cx - radius_px + 30, ly + 4, xml_escape(s.name));
    ly += 15;
  }
  out += fmt::format("<text x=\"{:.2f}\" y=\"{:.2f}\" text-anchor=\"end\" font-size=\"11\" fill=\"#444\">{}</text>\n",
                     cx + radius_px, cy + 22, xml_escape(chart.radius_label));
  return out + "</svg>\n";
}

}  // namespace specula::report
