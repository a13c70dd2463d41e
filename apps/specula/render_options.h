#pragma once
// What the picture commands (`render`, `compare`) share: the image size and material colours as
// the command line spells them, and the settings as metadata text.
#include <string>
#include <string_view>

#include "specula/render/render.h"

namespace specula::cli {

/// "WIDTHxHEIGHT"; InvalidArgument naming --size when malformed (the renderer checks the range).
render::RenderSettings settings_of(std::string_view size);

/// "r,g,b" given to `option`, or `fallback` when `text` is empty.
render::Rgb colour_of(std::string_view option, const std::string& text, const render::Rgb& fallback);

/// "r,g,b" in shortest round-trip form.
std::string rgb_text(const render::Rgb& c);

}  // namespace specula::cli
