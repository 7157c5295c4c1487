// Base64 (RFC 4648, section 4: the standard alphabet, padded with '='), for the PNGs the HTML
// reports embed as data: URLs.
#pragma once

#include <string>
#include <string_view>

namespace glrc::report {

// The base64 text of `bytes`, 4 characters for every 3 bytes begun, no line breaks. Cannot fail.
std::string base64_encode(std::string_view bytes);

}  // namespace glrc::report
