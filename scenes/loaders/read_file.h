// Reading a whole input file with a size limit and clear errors (missing, not a file,
// unreadable, too large), shared by the loaders.
#pragma once

#include <cstdint>
#include <string>

namespace rc {

// The largest scene, mesh or glTF buffer file read (1 GiB).
inline constexpr std::uintmax_t kMaxInputFileBytes = std::uintmax_t(1) << 30;

// Throws ioError naming the path when it is missing, not a regular file or unreadable, and
// badInput when it exceeds kMaxInputFileBytes.
std::string readInputFile(const std::string& path);

}  // namespace rc
