#pragma once
// What the picture commands (`render`, `compare`) share: the scene and display options, each
// declared here once with its help text, and the command-line syntax they are written in, read
// here into the render library's typed values (render::SceneDescription, render::Display, …).
// The render library knows no CLI syntax; the server reads its own fields (JSON numbers) into
// the same render::SceneDescription (src/serve/endpoints.cpp).
#include <CLI/CLI.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "specula/render/image_io.h"
#include "specula/render/render.h"
#include "specula/render/scene.h"

namespace specula::cli {

// --- The syntax ---

/// "dir:x,y,z[:r,g,b[:intensity]]" or "point:x,y,z[:r,g,b[:intensity]]" (colour 1,1,1 and
/// intensity 1 by default), as render::to_string writes it; throws InvalidArgument naming the
/// malformed part and the spec.
render::Light parse_light(std::string_view spec);

/// "none" or "aces"; throws InvalidArgument otherwise.
render::ToneMap parse_tone_map(std::string_view text);

/// "half" or "float"; throws InvalidArgument otherwise.
render::ExrPixel parse_exr_pixel(std::string_view text);

/// "cpu" or "gl"; throws InvalidField "backend" otherwise.
render::Backend parse_backend(std::string_view text);

/// "WIDTHxHEIGHT"; InvalidArgument naming --size when malformed (the renderer checks the range).
render::RenderSettings settings_of(std::string_view size);

/// "r,g,b" given to `option`; InvalidArgument naming the option unless three numbers.
render::Rgb parse_colour(std::string_view option, std::string_view text);

/// "r,g,b" in shortest round-trip form.
std::string rgb_text(const render::Rgb& c);

// --- The options ---

/// Which command the options are for: their defaults and help texts differ a little.
enum class Picture { render, compare };

/// --scene (render only), --size, --light, --diffuse, --specular, --ambient, --exposure and
/// --tonemap, as given.
struct SceneOptions {
  std::string mesh = "sphere";  ///< --scene: "sphere" or an OBJ file
  std::string size;
  std::vector<std::string> lights;
  std::string diffuse, specular, ambient;
  double exposure = 0;
  std::string tone_map = "none";

  /// Registers the options on `command` in this order (--size's default: 512x512 for render,
  /// 384x384 for compare).
  void add_to(CLI::App& command, Picture picture);

  /// The scene as given, in the order its parts are read (and their errors found): the mesh
  /// (load_obj), the lights, then the colours; what is not given is left empty (default_scene's).
  render::SceneDescription description() const;
  /// "WIDTHxHEIGHT" of --size.
  render::RenderSettings settings() const { return settings_of(size); }
  /// --exposure (InvalidArgument unless finite) and --tonemap.
  render::Display display() const;
};

/// The scene's lights and material colours as image metadata: "lights", "diffuse", "specular",
/// "ambient".
render::Metadata scene_metadata(const render::Scene& scene);

}  // namespace specula::cli
