// Reading a whole input file with a size limit and clear errors (missing, not a file,
// unreadable, too large), shared by the loaders.
#pragma once

#include <cstdint>
#include <string>

#include "core/plane_allocator.h"

namespace rc {

// The largest scene, mesh or glTF buffer file read (1 GiB).
inline constexpr std::uintmax_t kMaxInputFileBytes = std::uintmax_t(1) << 30;

// Throws ioError naming the path when it is missing, not a regular file or unreadable, and
// badInput when it exceeds kMaxInputFileBytes.
std::string readInputFile(const std::string& path);

// The same, in memory of huge pages (core/plane_allocator.h), not zeroed first: for the
// largest text files (an OBJ of a million triangles is over 100 MB, whose 4 KB page faults
// cost more than reading it).
PlaneVector<char> readLargeInputFile(const std::string& path);

}  // namespace rc
