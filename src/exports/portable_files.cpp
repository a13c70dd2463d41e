#include "portable_files.h"

#include <fmt/format.h>

#include <stdexcept>

namespace specula::exports {

std::string_view portable_file(std::string_view path) {
  for (const PortableFile& file : portable_files())
    if (file.path == path) return file.text;
  throw std::logic_error(fmt::format("no embedded portable file '{}'", path));
}

}  // namespace specula::exports
