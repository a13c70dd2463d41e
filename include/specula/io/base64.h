#pragma once
// Base64 (RFC 4648 §4, with padding): images inlined in HTML and JSON as data.
#include <string>
#include <string_view>

namespace specula::io {

std::string base64(std::string_view bytes);

}  // namespace specula::io
