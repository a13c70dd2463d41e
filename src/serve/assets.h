#pragma once
// The page's files (web/), compiled into the binary by cmake/embed_assets.cmake. Lookups are by
// exact path in this fixed list: no request can reach any other file.
#include <span>
#include <string_view>

namespace specula::serve {

struct Asset {
  std::string_view path;          ///< URL path, "/index.html"
  std::string_view content_type;
  std::string_view bytes;
};

/// Every embedded file (generated source).
std::span<const Asset> embedded_assets();

/// The asset at a URL path ("/" is "/index.html"), or nullptr.
const Asset* find_asset(std::string_view path);

}  // namespace specula::serve
