#include "assets.h"

#include <algorithm>

namespace specula::serve {

const Asset* find_asset(std::string_view path) {
  if (path == "/") path = "/index.html";
  const auto all = embedded_assets();
  const auto it = std::find_if(all.begin(), all.end(), [&](const Asset& a) { return a.path == path; });
  return it == all.end() ? nullptr : &*it;
}

}  // namespace specula::serve
