#include "scene_options.h"

#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "cli.h"
#include "specula/exceptions.h"
#include "specula/io/table.h"
#include "specula/io/values.h"

namespace specula::cli {
namespace {

std::vector<std::string_view> split_colons(std::string_view spec) {
  std::vector<std::string_view> parts;
  for (std::size_t start = 0; start <= spec.size();) {
    const std::size_t colon = std::min(spec.find(':', start), spec.size());
    parts.push_back(spec.substr(start, colon - start));
    start = colon + 1;
  }
  return parts;
}

std::vector<double> light_numbers(std::string_view spec, std::string_view part, std::size_t count,
                                  std::string_view what) {
  std::vector<double> numbers;
  for (std::size_t start = 0; start <= part.size();) {
    const std::size_t comma = std::min(part.find(',', start), part.size());
    numbers.push_back(io::parse_number(part.substr(start, comma - start), fmt::format("the {} of light '{}'", what, spec)));
    start = comma + 1;
  }
  if (numbers.size() != count)
    throw InvalidArgument(fmt::format("light '{}': the {} needs {} numbers, got {}", spec, what, count, numbers.size()));
  return numbers;
}

int side_of(std::string_view size, std::string_view text) {
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty())
    throw InvalidArgument(fmt::format("malformed --size '{}': expected WIDTHxHEIGHT, e.g. 512x512", size));
  return value;
}

}  // namespace

render::Light parse_light(std::string_view spec) {
  const auto parts = split_colons(spec);
  if ((parts[0] != "dir" && parts[0] != "point") || parts.size() < 2 || parts.size() > 4)
    throw InvalidArgument(fmt::format(
        "malformed light '{}': expected dir:x,y,z[:r,g,b[:intensity]] or point:x,y,z[:r,g,b[:intensity]]", spec));
  render::Light light;
  const bool directional = parts[0] == "dir";
  light.kind = directional ? render::LightKind::directional : render::LightKind::point;
  const auto xyz = light_numbers(spec, parts[1], 3, directional ? "direction" : "position");
  (directional ? light.direction : light.position) = {xyz[0], xyz[1], xyz[2]};
  if (parts.size() > 2) {
    const auto rgb = light_numbers(spec, parts[2], 3, "colour");
    light.colour = {rgb[0], rgb[1], rgb[2]};
  }
  if (parts.size() > 3) light.intensity = light_numbers(spec, parts[3], 1, "intensity")[0];
  render::check_light(light, fmt::format("light '{}'", spec));
  return light;
}

render::ToneMap parse_tone_map(std::string_view text) {
  if (const auto tone_map = enum_named<render::ToneMap, render::kToneMapCount>(text, ToString{})) return *tone_map;
  throw InvalidArgument(fmt::format("unknown tone map '{}': expected {}", text,
                                    names_listed<render::ToneMap, render::kToneMapCount>(ToString{})));
}

render::ExrPixel parse_exr_pixel(std::string_view text) {
  if (const auto pixel = enum_named<render::ExrPixel, render::kExrPixelCount>(text, ToString{})) return *pixel;
  throw InvalidArgument(fmt::format("unknown EXR pixel type '{}': expected {}", text,
                                    names_listed<render::ExrPixel, render::kExrPixelCount>(ToString{})));
}

render::Backend parse_backend(std::string_view text) {
  return choice_named<render::Backend, render::kBackendCount>("backend", text, Spelling::option);
}

render::RenderSettings settings_of(std::string_view size) {
  const std::size_t x = size.find('x');
  if (x == std::string_view::npos)
    throw InvalidArgument(fmt::format("malformed --size '{}': expected WIDTHxHEIGHT, e.g. 512x512", size));
  return {side_of(size, size.substr(0, x)), side_of(size, size.substr(x + 1))};
}

render::Rgb parse_colour(std::string_view option, std::string_view text) {
  const std::vector<double> c = option_values(option, text);
  if (c.size() != 3) throw InvalidArgument(fmt::format("{} '{}': expected r,g,b", option, text));
  return {c[0], c[1], c[2]};
}

std::string rgb_text(const render::Rgb& c) {
  return fmt::format("{},{},{}", io::format_number(c.r), io::format_number(c.g), io::format_number(c.b));
}

void SceneOptions::add_to(CLI::App& command, Picture picture) {
  const bool render = picture == Picture::render;
  if (render)
    command.add_option("--scene", mesh, "sphere (a unit sphere) or an OBJ file, framed from +z")->capture_default_str();
  size = render ? "512x512" : "384x384";
  command.add_option("--size", size, render ? "Image size WIDTHxHEIGHT, each in [1, 16384]" : "Size of each panel, WIDTHxHEIGHT")
      ->capture_default_str();
  command.add_option("--light", lights,
                     render ? "dir:x,y,z[:r,g,b[:intensity]] (x,y,z toward the light; E = colour·intensity) or\n"
                              "point:x,y,z[:r,g,b[:intensity]] (E = colour·intensity/d²); repeatable; default dir:-1,1,1"
                            : "dir:x,y,z[:r,g,b[:intensity]] or point:x,y,z[:r,g,b[:intensity]]; repeatable; default dir:-1,1,1");
  command.add_option("--diffuse", diffuse, "Diffuse albedo r,g,b (default 0.55,0.12,0.1)");
  command.add_option("--specular", specular, "Specular colour r,g,b: scales the model's f (default 0.4,0.4,0.4)");
  command.add_option("--ambient", ambient,
                     render ? "Ambient radiance r,g,b, reflected as ambient·diffuse (default 0.03,0.03,0.03)"
                            : "Ambient radiance r,g,b (default 0.03,0.03,0.03)");
  command.add_option("--exposure", exposure, render ? "PNG: scale the radiance by 2^STOPS" : "Scale the radiance by 2^STOPS before display")
      ->capture_default_str();
  command.add_option("--tonemap", tone_map, render ? "PNG: none (clamp) or aces (Narkowicz's fit)" : "none (clamp) or aces (Narkowicz's fit)")
      ->capture_default_str()
      ->check(one_of<render::ToneMap, render::kToneMapCount>());
}

render::SceneDescription SceneOptions::description() const {
  render::SceneDescription d;
  if (mesh != "sphere") d.mesh = render::load_obj(mesh);
  if (!lights.empty()) {
    d.lights.emplace();
    for (const auto& spec : lights) d.lights->push_back(parse_light(spec));
  }
  if (!diffuse.empty()) d.diffuse = parse_colour("--diffuse", diffuse);
  if (!specular.empty()) d.specular = parse_colour("--specular", specular);
  if (!ambient.empty()) d.ambient = parse_colour("--ambient", ambient);
  return d;
}

render::Display SceneOptions::display() const {
  if (!std::isfinite(exposure)) throw InvalidArgument(fmt::format("--exposure {} is not finite", exposure));
  return {exposure, parse_tone_map(tone_map)};
}

render::Metadata scene_metadata(const render::Scene& scene) {
  std::vector<std::string> lights;
  for (const auto& light : scene.lights) lights.push_back(render::to_string(light));
  return {{"lights", fmt::format("{}", fmt::join(lights, " "))},
          {"diffuse", rgb_text(scene.material.diffuse)},
          {"specular", rgb_text(scene.material.specular)},
          {"ambient", rgb_text(scene.material.ambient)}};
}

}  // namespace specula::cli
