// Base64 (RFC 4648, with padding), for data: URIs: glTF buffers written by `rastercheck export`
// and the ones the tests build.
#pragma once

#include <cstdint>
#include <string>

namespace rc {

// The 64 digits, in value order (scenes/loaders/gltf_data_uris.cpp decodes with them).
inline constexpr const char* kBase64Digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

inline std::string base64(const std::string& in) {
  const char* digits = kBase64Digits;
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < in.size(); i += 3) {
    std::uint32_t n = std::uint32_t(std::uint8_t(in[i])) << 16;
    if (i + 1 < in.size()) n |= std::uint32_t(std::uint8_t(in[i + 1])) << 8;
    if (i + 2 < in.size()) n |= std::uint32_t(std::uint8_t(in[i + 2]));
    out += digits[(n >> 18) & 63];
    out += digits[(n >> 12) & 63];
    out += i + 1 < in.size() ? digits[(n >> 6) & 63] : '=';
    out += i + 2 < in.size() ? digits[n & 63] : '=';
  }
  return out;
}

}  // namespace rc
