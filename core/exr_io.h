// Reading and writing Framebuffers as multi-channel OpenEXR files. This pair of functions
// (and exr_io.cpp) is the only place in the project that includes OpenEXR.
#pragma once

#include <string>

#include "core/framebuffer.h"

namespace rc {

// The largest image either function accepts, per side (also set as OpenEXR's own limit, so a
// huge declared data window in a tiny file is refused before anything is allocated).
inline constexpr int kMaxImageSide = 16384;
// The most pixel data one image may hold in memory (all channels): 4 GiB.
inline constexpr unsigned long long kMaxImageBytes = 1ull << 32;
// No lossless EXR codec compresses better than about 1032:1 (deflate's limit); a file smaller
// than its declared raw data divided by this is truncated or lies about its size.
inline constexpr unsigned long long kMaxCompressionRatio = 2048;

// OpenEXR's lossless codecs. kZip (deflate over blocks of 16 scanlines) is the default, at
// deflate's fastest level: on the outputs of the default scenes, the Stanford bunny and the
// blob at 1M triangles it wrote 17% faster than OpenEXR's default level for 2% more bytes
// (docs/channels.md). kPiz (wavelet) writes full frames of tiny triangles faster and smaller,
// sparse or smooth images slower and larger; kNone is ten times faster to write and three
// times larger.
enum class ExrCompression { kNone, kRle, kZips, kZip, kPiz };
const char* exrCompressionName(ExrCompression compression);  // "none", "rle", "zips", "zip", "piz"

// Writes every channel losslessly and every attribute as a string attribute, through a
// temporary file renamed into place. Throws ioError on failure; nothing partial is left.
void writeExr(const Framebuffer& fb, const std::string& path, ExrCompression compression = ExrCompression::kZip);

// Reads a scanline or tiled single-part EXR whose channels are all FLOAT or UINT.
// Throws ioError when the file cannot be opened, badInput naming the file and the channel or
// attribute when it is not a complete, valid EXR in that form.
Framebuffer readExr(const std::string& path);

// Sets the number of threads OpenEXR uses for (de)compression; 0 = all cores.
void setExrThreads(int threads);

}  // namespace rc
