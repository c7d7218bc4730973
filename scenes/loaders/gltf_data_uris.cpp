// The structural scan for /buffers/N/uri and /images/N/uri, and a strict base64 decoder.
#include "scenes/loaders/gltf_data_uris.h"

#include <array>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string_view>

#include "core/base64.h"
#include "core/error.h"

namespace rc::gltf {
namespace {

constexpr std::string_view kNamePrefix = "*rastercheck-embedded-";
constexpr std::size_t kMaxDepth = 64;  // nesting the scan follows

// A uri string's contents (quotes excluded) found at /buffers/N/uri or /images/N/uri.
struct UriString {
  bool image = false;
  std::size_t index = 0;  // N
  std::size_t begin = 0, end = 0;
};

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// Where a frame sits: the top-level object, the "buffers" or "images" array in it, or an
// element of that array. Nothing deeper matters.
enum class Role : std::uint8_t { kOther, kTop, kList, kItem };

struct Frame {
  bool object = false;
  Role role = Role::kOther;
  bool image = false;                  // kList and kItem: under "images"
  std::size_t index = 0;               // kList: the element being read
  enum class Key : std::uint8_t { kOther, kBuffers, kImages, kUri } key = Key::kOther;  // objects: the current key
};

Frame::Key keyOf(std::string_view key) {
  if (key == "buffers") return Frame::Key::kBuffers;
  if (key == "images") return Frame::Key::kImages;
  if (key == "uri") return Frame::Key::kUri;
  return Frame::Key::kOther;
}

// s[i] is '"': the index of its closing quote, or npos.
std::size_t stringEnd(std::string_view s, std::size_t i) {
  std::size_t from = i + 1;
  for (;;) {
    const void* q = from < s.size() ? std::memchr(s.data() + from, '"', s.size() - from) : nullptr;
    if (!q) return std::string_view::npos;
    const std::size_t k = std::size_t(static_cast<const char*>(q) - s.data());
    std::size_t b = k;
    while (b > i + 1 && s[b - 1] == '\\') --b;  // backslashes since the last quote: linear overall
    if ((k - b) % 2 == 0) return k;
    from = k + 1;
  }
}

// The frame an object or array opens inside `parent` (null: at the top level).
Frame frameUnder(const Frame* parent, bool object) {
  Frame f;
  f.object = object;
  if (!parent) {
    f.role = object ? Role::kTop : Role::kOther;
  } else if (parent->role == Role::kTop && !object &&
             (parent->key == Frame::Key::kBuffers || parent->key == Frame::Key::kImages)) {
    f.role = Role::kList;
    f.image = parent->key == Frame::Key::kImages;
  } else if (parent->role == Role::kList && object) {
    f.role = Role::kItem;
    f.image = parent->image;
    f.index = parent->index;
  }
  return f;
}

// Follows the JSON's brackets, strings and separators (numbers and literals are taken as any
// run of other characters, for the parser to judge) and returns the uri strings written
// without escapes, or nothing where the structure is broken.
std::optional<std::vector<UriString>> findUris(std::string_view s) {
  const std::size_t n = s.size();
  std::size_t i = 0;
  const auto skipSpace = [&] {
    while (i < n && isSpace(s[i])) ++i;
  };

  std::vector<UriString> found;
  std::vector<Frame> stack;
  enum class Want { kValue, kKeyOrClose, kKey, kValueOrClose, kCommaOrClose } want = Want::kValue;
  for (;;) {
    skipSpace();
    if (i == n) return std::nullopt;  // ended inside a value
    const char c = s[i];
    switch (want) {
      case Want::kValue:
      case Want::kValueOrClose: {
        if (want == Want::kValueOrClose && c == ']') break;  // an empty array: closed below
        Frame* parent = stack.empty() ? nullptr : &stack.back();
        if (c == '{' || c == '[') {
          const Frame f = frameUnder(parent, c == '{');
          // Deeper than any glTF needs: left to the parsers (whose own stacks grow with it),
          // so that this scan's never does.
          if (stack.size() == kMaxDepth) return std::nullopt;
          stack.push_back(f);
          ++i;
          want = f.object ? Want::kKeyOrClose : Want::kValueOrClose;
          continue;
        }
        if (!parent) return std::nullopt;  // the top level must be an object or an array
        if (c == '"') {
          const std::size_t end = stringEnd(s, i);
          if (end == std::string_view::npos) return std::nullopt;
          if (parent->role == Role::kItem && parent->key == Frame::Key::kUri &&
              std::memchr(s.data() + i + 1, '\\', end - i - 1) == nullptr) {
            found.push_back({parent->image, parent->index, i + 1, end});
          }
          i = end + 1;
        } else {
          const std::size_t start = i;
          while (i < n && !isSpace(s[i]) && std::strchr(",:]}[{\"", s[i]) == nullptr) ++i;
          if (i == start) return std::nullopt;
        }
        want = Want::kCommaOrClose;
        continue;
      }
      case Want::kKeyOrClose:
      case Want::kKey: {
        if (want == Want::kKeyOrClose && c == '}') break;  // an empty object: closed below
        if (c != '"') return std::nullopt;
        const std::size_t end = stringEnd(s, i);
        if (end == std::string_view::npos) return std::nullopt;
        stack.back().key = keyOf(s.substr(i + 1, end - i - 1));
        i = end + 1;
        skipSpace();
        if (i == n || s[i] != ':') return std::nullopt;
        ++i;
        want = Want::kValue;
        continue;
      }
      case Want::kCommaOrClose:
        if (c == ',') {
          ++i;
          if (stack.back().object) {
            want = Want::kKey;
          } else {
            ++stack.back().index;
            want = Want::kValue;
          }
          continue;
        }
        break;
    }
    // A closing bracket, which must match the innermost frame.
    if (c != (stack.back().object ? '}' : ']')) return std::nullopt;
    ++i;
    stack.pop_back();
    if (stack.empty()) {
      skipSpace();
      if (i != n) return std::nullopt;
      return found;
    }
    want = Want::kCommaOrClose;
  }
}

constexpr std::array<std::int8_t, 256> kDigitValues = [] {
  std::array<std::int8_t, 256> t{};
  for (auto& v : t) v = -1;
  for (int i = 0; i < 64; ++i) t[std::uint8_t(kBase64Digits[i])] = std::int8_t(i);
  return t;
}();

std::string shown(char c) {
  if (c >= 0x20 && c < 0x7F) return std::string("'") + c + "'";
  static const char* hex = "0123456789abcdef";
  return std::string("byte 0x") + hex[std::uint8_t(c) >> 4] + hex[std::uint8_t(c) & 15];
}

bool endsWithBase64(std::string_view header) {
  constexpr std::string_view tag = ";base64";
  if (header.size() < tag.size()) return false;
  for (std::size_t k = 0; k < tag.size(); ++k) {
    const char c = header[header.size() - tag.size() + k];
    if ((c >= 'A' && c <= 'Z' ? char(c - 'A' + 'a') : c) != tag[k]) return false;
  }
  return true;
}

// The bytes of base64 `data`, which starts at character `offset` of its URI (for messages).
std::vector<unsigned char> decodeBase64(std::string_view data, std::size_t offset, const std::string& where) {
  std::size_t length = data.size();
  std::size_t padding = 0;
  while (length > 0 && padding < 2 && data[length - 1] == '=') {
    --length;
    ++padding;
  }
  const auto refuse = [&](std::size_t k, const std::string& why) -> void {
    throw badInput(where, "its base64 data is not valid: " + why + " at character " + std::to_string(offset + k + 1) +
                              " of the URI");
  };
  for (std::size_t k = 0; k < length; k += 4) {  // find the first bad character before decoding
    const std::size_t m = std::min<std::size_t>(4, length - k);
    int bad = 0;
    for (std::size_t j = 0; j < m; ++j) bad |= kDigitValues[std::uint8_t(data[k + j])];
    if (bad < 0) {
      for (std::size_t j = 0; j < m; ++j) {
        if (kDigitValues[std::uint8_t(data[k + j])] < 0) refuse(k + j, shown(data[k + j]) + " is not a base64 digit");
      }
    }
  }
  if (length % 4 == 1) refuse(length - 1, "a lone digit ends it");
  if (padding > 0 && (length + padding) % 4 != 0) refuse(length, "its '=' padding does not fill the last group of four");
  std::vector<unsigned char> out(length / 4 * 3 + (length % 4 == 0 ? 0 : length % 4 - 1));
  const auto digit = [&](std::size_t k) { return std::uint32_t(kDigitValues[std::uint8_t(data[k])]); };
  std::size_t o = 0, k = 0;
  for (; k + 4 <= length; k += 4, o += 3) {
    const std::uint32_t v = digit(k) << 18 | digit(k + 1) << 12 | digit(k + 2) << 6 | digit(k + 3);
    out[o] = (unsigned char)(v >> 16);
    out[o + 1] = (unsigned char)(v >> 8);
    out[o + 2] = (unsigned char)v;
  }
  if (length - k >= 2) {
    const std::uint32_t v = digit(k) << 18 | digit(k + 1) << 12 | (length - k == 3 ? digit(k + 2) << 6 : 0);
    out[o] = (unsigned char)(v >> 16);
    if (length - k == 3) out[o + 1] = (unsigned char)(v >> 8);
  }
  return out;
}

}  // namespace

EmbeddedData takeDataUris(std::string_view json, const std::string& path) {
  EmbeddedData result;
  // A file that already holds the names' prefix keeps its text: no name could then be told from
  // a string of the file's own (which checkUris refuses anyway, for its '*').
  if (json.find(kNamePrefix) != std::string::npos) return result;
  const std::optional<std::vector<UriString>> uris = findUris(json);
  if (!uris) return result;

  std::string out;
  std::size_t copied = 0;
  for (const UriString& u : *uris) {
    const std::string_view uri(json.data() + u.begin, u.end - u.begin);
    if (uri.rfind("data:", 0) != 0) continue;
    const std::size_t comma = uri.find(',');
    const bool base64 = comma != std::string_view::npos && endsWithBase64(uri.substr(0, comma));
    std::string replacement;
    if (u.image) {
      if (!base64) continue;  // not data tinygltf decodes: it warns and goes on, as for a missing image
      replacement = std::string(uri.substr(0, comma + 1)) + "AA==";
    } else {
      const std::string where = path + ": /buffers/" + std::to_string(u.index) + "/uri";
      if (!base64) {
        throw badInput(where, "is a data: URI without base64 data; a buffer's must be data:[<media type>];base64,<data>");
      }
      replacement = std::string(kNamePrefix) + std::to_string(result.buffers.size());
      result.buffers[replacement] = decodeBase64(uri.substr(comma + 1), comma + 1, where);
    }
    if (out.empty()) out.reserve(json.size());  // address space only: the pages never written stay unmapped
    out.append(json, copied, u.begin - copied);
    out += replacement;
    copied = u.end;
  }
  if (copied == 0) return result;
  out.append(json, copied, std::string::npos);
  result.json = std::move(out);
  return result;
}

}  // namespace rc::gltf
