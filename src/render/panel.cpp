#include "specula/render/panel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <memory>

#include "specula/exceptions.h"
#include "text.h"

namespace specula::render {
namespace {

constexpr int kTickLength = 6;
constexpr int kTickLabelGap = 4;  // between a tick mark and its number

void check_layout(const PanelLayout& layout) {
  const std::array<std::pair<const char*, int>, 4> lengths{{{"margin", layout.margin},
                                                            {"label height", layout.label_height},
                                                            {"colour bar width", layout.colour_bar_width},
                                                            {"tick label width", layout.tick_label_width}}};
  for (const auto& [name, value] : lengths)
    if (value < 0 || value > kMaxImageSide)
      throw InvalidArgument(fmt::format("panel layout: {} {} is outside [0, {}]", name, value, kMaxImageSide));
}

}  // namespace

std::filesystem::path default_font() {
  return SPECULA_DEFAULT_FONT;
}

PanelGeometry::PanelGeometry(int panel_count, int panel_width, int panel_height, bool heat_maps,
                             const PanelLayout& layout)
    : count_(panel_count), panel_width_(panel_width), panel_height_(panel_height), layout_(layout) {
  if (panel_count < 1) throw InvalidArgument("a comparison panel needs at least one image");
  if (panel_width < 1 || panel_height < 1 || panel_width > kMaxImageSide || panel_height > kMaxImageSide)
    throw InvalidArgument(fmt::format("panel size {}x{} is outside [1, {}]", panel_width, panel_height, kMaxImageSide));
  check_layout(layout);
  const long long m = layout.margin, rows = heat_maps ? 2 : 1;
  const long long column = layout.colour_bar_width + layout.tick_label_width + layout.label_height;
  const long long width = m + panel_count * (panel_width + m) + (heat_maps ? column + m : 0);
  const long long height = m + rows * (panel_height + layout.label_height + m);
  if (width > kMaxImageSide || height > kMaxImageSide)
    throw InvalidArgument(fmt::format("the comparison panel would be {}x{} pixels, more than {} on a side: "
                                      "use fewer models or a smaller size", width, height, kMaxImageSide));
  width_ = static_cast<int>(width);
  height_ = static_cast<int>(height);
}

Rect PanelGeometry::panel(int row, int column) const noexcept {
  const int m = layout_.margin, h = layout_.label_height;
  const int above = layout_.labels == LabelPlacement::above ? h : 0;
  return {m + column * (panel_width_ + m), m + row * (panel_height_ + h + m) + above, panel_width_, panel_height_};
}

Rect PanelGeometry::label(int row, int column) const noexcept {
  const Rect p = panel(row, column);
  const int h = layout_.label_height;
  return {p.x, layout_.labels == LabelPlacement::above ? p.y - h : p.y + p.height, p.width, h};
}

Rect PanelGeometry::colour_bar() const noexcept {
  const Rect heat_map = panel(1, 0);
  return {layout_.margin + count_ * (panel_width_ + layout_.margin), heat_map.y, layout_.colour_bar_width,
          panel_height_};
}

Rect PanelGeometry::tick_labels() const noexcept {
  const Rect bar = colour_bar();
  return {bar.x + bar.width, bar.y, layout_.tick_label_width, bar.height};
}

Rect PanelGeometry::colour_bar_title() const noexcept {
  const Rect ticks = tick_labels();
  return {ticks.x + ticks.width, ticks.y, layout_.label_height, ticks.height};
}

double luminance(const Rgb& linear) noexcept {
  return 0.2126 * linear.r + 0.7152 * linear.g + 0.0722 * linear.b;
}

LuminanceDifference luminance_difference(const Image& a, const Image& b) {
  if (a.width() != b.width() || a.height() != b.height())
    throw InvalidArgument(fmt::format("cannot compare a {}x{} image with a {}x{} one", a.width(), a.height(),
                                      b.width(), b.height()));
  LuminanceDifference d{a.width(), a.height(), {}, 0, 0};
  d.values.reserve(static_cast<std::size_t>(a.width()) * a.height());
  double sum = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      const double value = std::abs(luminance(a.at(x, y)) - luminance(b.at(x, y)));
      d.values.push_back(value);
      d.max = std::max(d.max, value);
      sum += value;
    }
  d.mean = sum / static_cast<double>(d.values.size());
  return d;
}

Rgb viridis(double t) noexcept {
  // Zucker's coefficients c0..c6 per channel (Shadertoy WlfXRN): c0 + t(c1 + t(c2 + … + t c6)).
  static constexpr std::array<Rgb, 7> c{{
      {0.2777273272234177, 0.005407344544966578, 0.3340998053353061},
      {0.1050930431085774, 1.404613529898575, 1.384590162594685},
      {-0.3308618287255563, 0.214847559468213, 0.09509516302823659},
      {-4.634230498983486, -5.799100973351585, -19.33244095627987},
      {6.228269936347081, 14.17993336680509, 56.69055260068105},
      {4.776384997670288, -13.74514537774601, -65.35303263337234},
      {-5.435455855934631, 4.645852612178535, 26.3124352495832},
  }};
  t = t > 0 ? std::min(t, 1.0) : 0.0;  // NaN too
  Rgb value = c[6];
  for (int i = 5; i >= 0; --i) value = value * t + c[static_cast<std::size_t>(i)];
  return {std::clamp(value.r, 0.0, 1.0), std::clamp(value.g, 0.0, 1.0), std::clamp(value.b, 0.0, 1.0)};
}

Srgb8 viridis_srgb8(double t) noexcept {
  const Rgb c = viridis(t);
  const auto code = [](double v) { return static_cast<std::uint8_t>(std::lround(255 * v)); };
  return {code(c.r), code(c.g), code(c.b)};
}

namespace {

double tick_step(double scale_max) {
  const double least = scale_max / 5;
  const double decade = std::pow(10.0, std::floor(std::log10(least)));
  for (const double multiple : {1.0, 2.0, 5.0, 10.0})
    if (multiple * decade >= least * (1 - 1e-12)) return multiple * decade;
  return 10 * decade;
}

void check_scale(double scale_max) {
  if (!std::isfinite(scale_max) || scale_max <= 0)
    throw InvalidArgument(fmt::format("the heat-map scale {} must be finite and > 0", scale_max));
}

}  // namespace

std::vector<double> colour_bar_ticks(double scale_max) {
  check_scale(scale_max);
  const double step = tick_step(scale_max);
  std::vector<double> ticks;
  for (int i = 0; i * step <= scale_max * (1 + 1e-12); ++i) ticks.push_back(i * step);
  return ticks;
}

namespace {

// ---- drawing -------------------------------------------------------------------------------

void fill(Srgb8Image& canvas, const Rect& r, Srgb8 colour) {
  for (int y = r.y; y < r.y + r.height; ++y)
    for (int x = r.x; x < r.x + r.width; ++x) canvas.set(x, y, colour);
}

// The layout's font at its text size, and smaller sizes, down to kSmallestShare of it, for text
// that would not fit its cell at full size.
class Typeface {
 public:
  static constexpr double kSmallestShare = 0.6;

  explicit Typeface(const PanelLayout& layout)
      : path_(layout.font.empty() ? default_font() : layout.font), size_(layout.text_size) {
    try {
      at(size_);
    } catch (const InvalidArgument& e) {
      if (!layout.font.empty()) throw;
      throw InvalidArgument(fmt::format("{} (install Debian's fonts-dejavu-core: scripts/install-deps)", e.what()));
    }
  }

  const Font& at(int size) {
    auto& font = fonts_[size];
    if (!font) font = std::make_unique<Font>(path_, size);
    return *font;
  }

  const Font& full_size() { return at(size_); }

  /// The largest size, from the text size down to the smallest, at which every one of `texts` is
  /// at most `length` wide; the smallest if there is none.
  const Font& fitting(const std::vector<std::string>& texts, int length) {
    const int smallest = std::max(1, static_cast<int>(std::ceil(kSmallestShare * size_)));
    for (int size = size_; size > smallest; --size)
      if (std::all_of(texts.begin(), texts.end(), [&](const auto& t) { return at(size).render(t).width <= length; }))
        return at(size);
    return at(smallest);
  }

 private:
  std::filesystem::path path_;
  int size_;
  std::map<int, std::unique_ptr<Font>> fonts_;
};

// Centred in `cell` when it fits along the line, else from its start; clipped to `cell`.
void draw_text(Srgb8Image& canvas, const Font& font, std::string_view text, const Rect& cell, Srgb8 ink) {
  const TextMask mask = font.render(text);
  const int spare = cell.width - mask.width;
  draw_mask(canvas, mask, cell.x + std::max(0, spare / 2), cell.y + (cell.height - mask.height) / 2, false, cell, ink);
}

// Reading upward, centred in `cell` when it fits, else from its bottom; clipped to `cell`.
void draw_text_upward(Srgb8Image& canvas, const Font& font, std::string_view text, const Rect& cell, Srgb8 ink) {
  const TextMask mask = font.render(text);
  const int spare = cell.height - mask.width;
  const int y = spare >= 0 ? cell.y + spare / 2 : cell.y + cell.height - mask.width;
  draw_mask(canvas, mask, cell.x + (cell.width - mask.height) / 2, y, true, cell, ink);
}

// One row's labels, all at the one size at which the widest fits its cell (or the smallest).
void draw_labels(Srgb8Image& canvas, Typeface& typeface, const std::vector<std::string>& labels,
                 const std::vector<Rect>& cells, Srgb8 ink) {
  const Font& font = typeface.fitting(labels, cells.front().width);
  for (std::size_t i = 0; i < labels.size(); ++i) draw_text(canvas, font, labels[i], cells[i], ink);
}

// `text` split at the ", " nearest its middle; the whole text if it has none.
std::vector<std::string> two_lines(const std::string& text) {
  std::size_t best = std::string::npos;
  for (std::size_t at = text.find(", "); at != std::string::npos; at = text.find(", ", at + 1))
    if (best == std::string::npos || std::abs(2.0 * at - text.size()) < std::abs(2.0 * best - text.size())) best = at;
  if (best == std::string::npos) return {text};
  return {text.substr(0, best + 1), text.substr(best + 2)};
}

// Reading upward in `cell`: on one line if it fits at some size, else on two lines side by side
// (split at a ", "), each in half the cell.
void draw_title(Srgb8Image& canvas, Typeface& typeface, const std::string& title, const Rect& cell, Srgb8 ink) {
  const Font& one_line = typeface.fitting({title}, cell.height);
  const std::vector<std::string> lines = two_lines(title);
  if (one_line.render(title).width <= cell.height || lines.size() == 1) {
    draw_text_upward(canvas, one_line, title, cell, ink);
    return;
  }
  const Font& font = typeface.fitting(lines, cell.height);
  const int half = cell.width / 2;
  draw_text_upward(canvas, font, lines[0], {cell.x, cell.y, half, cell.height}, ink);
  draw_text_upward(canvas, font, lines[1], {cell.x + half, cell.y, cell.width - half, cell.height}, ink);
}

void draw_display_image(Srgb8Image& canvas, const Image& image, const Display& display, const Rect& at) {
  const std::vector<std::uint8_t> codes = to_srgb8(image, display);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const std::size_t i = 3 * (static_cast<std::size_t>(y) * image.width() + x);
      canvas.set(at.x + x, at.y + y, {codes[i], codes[i + 1], codes[i + 2]});
    }
}

void draw_heat_map(Srgb8Image& canvas, const LuminanceDifference& d, double scale_max, const Rect& at) {
  for (int y = 0; y < d.height; ++y)
    for (int x = 0; x < d.width; ++x)
      canvas.set(at.x + x, at.y + y, viridis_srgb8(d.values[static_cast<std::size_t>(y) * d.width + x] / scale_max));
}

// The bar's row for value v: scale_max at the top row, 0 at the bottom one.
int bar_row(const Rect& bar, double v, double scale_max) {
  return bar.y + static_cast<int>(std::lround((1 - v / scale_max) * (bar.height - 1)));
}

std::string tick_text(double value, double step) {
  const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
  if (decimals <= 4 && step < 1e5) return fmt::format("{:.{}f}", value, decimals);
  return fmt::format("{:g}", value);
}

struct Canvas {
  Srgb8Image& image;
  Typeface& typeface;
  const PanelLayout& layout;
};

// viridis from 1 in the top row to 0 in the bottom one.
void draw_gradient(Srgb8Image& image, const Rect& bar) {
  for (int y = bar.y; y < bar.y + bar.height; ++y) {
    const double t = bar.height == 1 ? 1.0 : static_cast<double>(bar.y + bar.height - 1 - y) / (bar.height - 1);
    fill(image, {bar.x, y, bar.width, 1}, viridis_srgb8(t));
  }
}

// A mark right of the bar at the value's row.
void draw_tick_mark(const Canvas& c, const PanelGeometry& g, int row) {
  const Rect ticks = g.tick_labels();
  fill(c.image, {ticks.x, row, std::min(kTickLength, ticks.width), 1}, c.layout.ink);
}

// The number beside a tick mark, centred on its row. It may reach above or below the bar, but
// never left of the tick column.
void draw_tick_number(const Canvas& c, const PanelGeometry& g, int row, const TextMask& number) {
  const Rect ticks = g.tick_labels();
  const Rect clip{ticks.x, 0, ticks.width, c.image.height()};
  draw_mask(c.image, number, ticks.x + kTickLength + kTickLabelGap, row - number.height / 2, false, clip, c.layout.ink);
}

// Ticks from the bottom up; a number that would overlap the one below it is left out (a short bar).
void draw_colour_bar(const Canvas& c, const PanelGeometry& g, double scale_max, const std::string& title) {
  draw_gradient(c.image, g.colour_bar());
  const std::vector<double> values = colour_bar_ticks(scale_max);
  const double step = values.size() > 1 ? values[1] : scale_max;
  const Font& font = c.typeface.full_size();
  int last_number_row = c.image.height() + font.line_height();  // none yet
  for (const double v : values) {
    const int row = bar_row(g.colour_bar(), v, scale_max);
    draw_tick_mark(c, g, row);
    if (last_number_row - row < font.line_height()) continue;
    draw_tick_number(c, g, row, font.render(tick_text(v, step)));
    last_number_row = row;
  }
  draw_title(c.image, c.typeface, title, g.colour_bar_title(), c.layout.ink);
}

std::string difference_label(const LuminanceDifference& d) {
  return fmt::format("max {:.3g}, mean {:.3g}", d.max, d.mean);
}

double shared_scale(const std::vector<LuminanceDifference>& differences, const std::optional<double>& requested) {
  if (requested) {
    check_scale(*requested);
    return *requested;
  }
  double largest = 0;
  for (const auto& d : differences) largest = std::max(largest, d.max);
  return largest > 0 && std::isfinite(largest) ? largest : 1.0;
}

void check_sizes(const std::vector<LabelledImage>& panels, const std::optional<HeatMaps>& heat_maps) {
  if (panels.empty()) throw InvalidArgument("a comparison panel needs at least one image");
  const Image& first = panels.front().image;
  const auto check = [&](const Image& image, std::string_view what) {
    if (image.width() != first.width() || image.height() != first.height())
      throw InvalidArgument(fmt::format("{} is {}x{}, the first image {}x{}: a comparison panel needs one size",
                                        what, image.width(), image.height(), first.width(), first.height()));
  };
  for (const auto& p : panels) check(p.image, fmt::format("image '{}'", p.label));
  if (heat_maps) check(heat_maps->reference, "the reference image");
}

std::vector<Rect> label_cells(const PanelGeometry& g, int row, std::size_t count) {
  std::vector<Rect> cells;
  for (std::size_t i = 0; i < count; ++i) cells.push_back(g.label(row, static_cast<int>(i)));
  return cells;
}

void draw_image_row(const Canvas& c, const PanelGeometry& g, const std::vector<LabelledImage>& panels,
                    const Display& display) {
  std::vector<std::string> labels;
  for (std::size_t i = 0; i < panels.size(); ++i) {
    draw_display_image(c.image, panels[i].image, display, g.panel(0, static_cast<int>(i)));
    labels.push_back(panels[i].label);
  }
  draw_labels(c.image, c.typeface, labels, label_cells(g, 0, panels.size()), c.layout.ink);
}

void draw_heat_map_row(const Canvas& c, const PanelGeometry& g, const std::vector<LuminanceDifference>& differences,
                       double scale_max) {
  std::vector<std::string> labels;
  for (std::size_t i = 0; i < differences.size(); ++i) {
    draw_heat_map(c.image, differences[i], scale_max, g.panel(1, static_cast<int>(i)));
    labels.push_back(difference_label(differences[i]));
  }
  draw_labels(c.image, c.typeface, labels, label_cells(g, 1, differences.size()), c.layout.ink);
}

}  // namespace

ComparisonPanel compose_comparison(const std::vector<LabelledImage>& panels, const Display& display,
                                   const PanelLayout& layout, const std::optional<HeatMaps>& heat_maps) {
  check_sizes(panels, heat_maps);
  const PanelGeometry g(static_cast<int>(panels.size()), panels.front().image.width(),
                        panels.front().image.height(), heat_maps.has_value(), layout);
  Typeface typeface(layout);
  ComparisonPanel result{Srgb8Image(g.width(), g.height(), layout.background), {}, 0};
  const Canvas canvas{result.image, typeface, layout};
  draw_image_row(canvas, g, panels, display);
  if (!heat_maps) return result;
  for (const auto& p : panels) result.differences.push_back(luminance_difference(p.image, heat_maps->reference));
  result.scale_max = shared_scale(result.differences, heat_maps->scale_max);
  draw_heat_map_row(canvas, g, result.differences, result.scale_max);
  draw_colour_bar(canvas, g, result.scale_max, heat_maps->title);
  return result;
}

}  // namespace specula::render
