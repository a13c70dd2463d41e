#include "render_options.h"

#include <charconv>
#include <fmt/format.h>
#include <vector>

#include "cli.h"
#include "specula/exceptions.h"

namespace specula::cli {
namespace {

int side_of(std::string_view size, std::string_view text) {
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty())
    throw InvalidArgument(fmt::format("malformed --size '{}': expected WIDTHxHEIGHT, e.g. 512x512", size));
  return value;
}

}  // namespace

render::RenderSettings settings_of(std::string_view size) {
  const std::size_t x = size.find('x');
  if (x == std::string_view::npos)
    throw InvalidArgument(fmt::format("malformed --size '{}': expected WIDTHxHEIGHT, e.g. 512x512", size));
  return {side_of(size, size.substr(0, x)), side_of(size, size.substr(x + 1))};
}

render::Rgb colour_of(std::string_view option, const std::string& text, const render::Rgb& fallback) {
  if (text.empty()) return fallback;
  const std::vector<double> c = option_values(option, text);
  if (c.size() != 3) throw InvalidArgument(fmt::format("{} '{}': expected r,g,b", option, text));
  return {c[0], c[1], c[2]};
}

std::string rgb_text(const render::Rgb& c) {
  return fmt::format("{},{},{}", io::format_number(c.r), io::format_number(c.g), io::format_number(c.b));
}

}  // namespace specula::cli
