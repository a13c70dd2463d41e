#pragma once
// Private to src/exports: the files of include/specula/lobes/portable/, compiled in by
// cmake/embed_assets.cmake, which the C++ export embeds as text (so that its sampler and
// specula's are one source).
#include <span>
#include <string_view>

namespace specula::exports {

struct PortableFile {
  std::string_view path;  ///< below include/specula/lobes/portable/: "radial.h"
  std::string_view text;
};

/// Every file of include/specula/lobes/portable/ (generated source).
std::span<const PortableFile> portable_files();

/// The text of the portable file at `path`. Throws std::logic_error if there is none.
std::string_view portable_file(std::string_view path);

}  // namespace specula::exports
