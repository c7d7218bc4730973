// glTF data: URIs taken out of the JSON before any JSON parser reads it.
//
// A .gltf file with embedded buffers holds them as base64 in JSON strings: 37 MB of one string
// for a million triangles. nlohmann's lexer appends such a string character by character, and
// tinygltf copies it several times before decoding it, so parsing the text as it is took about
// 2.3 s of the 2.6 s that loading such a file took. The strings are found here by a scan that
// only follows the JSON's structure, and each is decoded once, straight into the bytes tinygltf
// is then handed; the JSON the parsers read is small.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace rc::gltf {

struct EmbeddedData {
  // The JSON with every base64 data: URI of /buffers/N/uri replaced by a name of `buffers`, and
  // the data of every base64 data: URI of /images/N/uri by one byte (images are never read).
  // Empty when nothing was taken out.
  std::string json;
  // Name -> the bytes its data: URI held. A name begins with '*', which checkUris refuses in
  // any URI of the file itself, so it can never name a file.
  std::map<std::string, std::vector<unsigned char>> buffers;
  bool changed() const { return !json.empty(); }
};

// Takes the data: URIs out of `json` (a .gltf file or a GLB's JSON chunk). A buffer's data:
// URI must be base64 (`data:[<media type>];base64,<data>`, padding optional): otherwise it is
// refused, badInput("path: /buffers/N/uri", ...) naming the first character that is wrong.
// Strings the scan cannot take as they are written (with JSON escapes, or under a key spelled
// with escapes), and any text that is not well-formed JSON as far as the scan can tell, are
// left as they are, for the parsers to read or refuse.
EmbeddedData takeDataUris(std::string_view json, const std::string& path);

}  // namespace rc::gltf
