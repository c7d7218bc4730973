// OpenEXR input and output for Framebuffers. Every OpenEXR exception is turned into an
// rc::Error naming the file; nothing of OpenEXR leaks past this file.
#include "core/exr_io.h"
#include "core/parallel.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <ImfTestFile.h>
#include <ImfThreading.h>

#include <algorithm>
#include <cstring>
#include <iterator>
#include <map>
#include <new>
#include <filesystem>
#include <fstream>

#include "core/atomic_file.h"
#include "core/error.h"

namespace rc {
namespace {

void setLimits() {
  // OpenEXR accepts any declared size by default; a 30-byte file could ask for terabytes.
  Imf::Header::setMaxImageSize(kMaxImageSide, kMaxImageSide);
  Imf::Header::setMaxTileSize(kMaxImageSide, kMaxImageSide);
}

Imf::PixelType pixelType(ChannelType type) {
  return type == ChannelType::kUint ? Imf::UINT : Imf::FLOAT;
}

char* planeBase(const Channel& c) {
  return c.type == ChannelType::kUint
             ? reinterpret_cast<char*>(const_cast<std::uint32_t*>(c.uints.data()))
             : reinterpret_cast<char*>(const_cast<float*>(c.floats.data()));
}

void checkHeaderSizes(const std::string& path);

// Rejects what cannot be an OpenEXR file before OpenEXR sees it, with a clear reason.
void checkOpenable(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw ioError(path, "cannot read: no such file");
  if (!std::filesystem::is_regular_file(path, ec)) throw ioError(path, "cannot read: not a file");
  std::ifstream probe(path, std::ios::binary);
  if (!probe) throw ioError(path, "cannot read: permission denied");
  if (std::filesystem::file_size(path, ec) == 0) throw badInput(path, "empty file, not an EXR");
  bool tiled = false, deep = false, multipart = false;
  if (!Imf::isOpenExrFile(path.c_str(), tiled, deep, multipart)) {
    throw badInput(path, "not an OpenEXR file (bad magic number or version)");
  }
  if (deep) throw badInput(path, "deep EXR files are not supported");
  if (multipart) throw badInput(path, "multi-part EXR files are not supported");
  checkHeaderSizes(path);
}

// OpenEXR 3.1 allocates whatever size a header attribute declares (an attribute of unknown type
// becomes an OpaqueAttribute of that many bytes): a 689-byte file found by fuzzing asked for
// 1.6 GB. And OpenEXR reads known types by their contents, not by the declared size (a channel
// list until its empty name, a box2i as 16 bytes, a preview as 8 + width x height x 4 bytes),
// so a size that disagrees with the contents makes it read the rest of the header from a
// different place than any size check looked. The single-part header is therefore walked here
// first, as OpenEXR will read it: every size must fit in the file and agree with its contents.
std::uint64_t expectedSize(const std::string& type) {
  static const std::map<std::string, std::uint64_t> kFixed = {
      {"box2i", 16},         {"box2f", 16},   {"compression", 1}, {"lineOrder", 1}, {"envmap", 1},
      {"deepImageState", 1}, {"float", 4},    {"double", 8},      {"int", 4},       {"v2i", 8},
      {"v2f", 8},            {"v2d", 16},     {"v3i", 12},        {"v3f", 12},      {"v3d", 24},
      {"m33f", 36},          {"m33d", 72},    {"m44f", 64},       {"m44d", 128},    {"chromaticities", 32},
      {"keycode", 28},       {"timecode", 8}, {"tiledesc", 9},    {"rational", 8}};
  const auto it = kFixed.find(type);
  return it == kFixed.end() ? 0 : it->second;
}

void checkHeaderSizes(const std::string& path) {
  // Headers are small: the walk reads the first 64 KiB and more (doubling) only while the
  // header goes on, to at most 16 MiB; a header that does not end there is refused. Sizes are
  // checked against the whole file.
  constexpr std::size_t kMaxHeader = std::size_t(16) << 20;
  std::error_code ec;
  const std::uint64_t n = std::filesystem::file_size(path, ec);
  const std::size_t cap = std::size_t(std::min<std::uint64_t>(n, kMaxHeader));
  std::ifstream file(path, std::ios::binary);
  std::string bytes;
  // Loads at least the first `upTo` bytes (as far as the cap allows); false when it cannot.
  const auto load = [&](std::uint64_t upTo) {
    if (upTo <= bytes.size()) return true;
    if (bytes.size() >= cap) return false;
    const std::size_t want = std::min(cap, std::max<std::size_t>({std::size_t(upTo), 2 * bytes.size(), std::size_t(64) << 10}));
    const std::size_t have = bytes.size();
    bytes.resize(want);
    file.read(bytes.data() + have, std::streamsize(want - have));
    return upTo <= bytes.size();
  };
  std::uint64_t p = 8;  // magic and version
  const auto where = [&](std::uint64_t at) { return path + ": byte " + std::to_string(at); };
  const auto readString = [&](const char* what) {
    std::size_t end = bytes.find('\0', std::size_t(p));
    while (end == std::string::npos && load(bytes.size() + 1)) end = bytes.find('\0', std::size_t(p));
    if (end == std::string::npos) {
      throw badInput(where(p), cap < n ? "header does not end within 16 MiB" : "truncated header");
    }
    if (end - p > 255) throw badInput(where(p), std::string(what) + " longer than 255 bytes");
    std::string text = bytes.substr(std::size_t(p), end - std::size_t(p));
    p = end + 1;
    return text;
  };
  const auto readInt = [&]() {
    if (!load(p + 4)) throw badInput(where(p), "truncated header");
    std::int32_t v;
    std::memcpy(&v, bytes.data() + p, 4);
    p += 4;
    return v;
  };
  for (int count = 0;; ++count) {
    if (count > 100000) throw badInput(path, "more than 100000 header attributes");
    const std::uint64_t start = p;
    const std::string name = readString("attribute name");
    if (name.empty()) return;  // end of header
    const std::string type = readString("attribute type");
    const std::int32_t size = readInt();
    const std::string at = path + ": header attribute '" + name + "' at byte " + std::to_string(start);
    if (size < 0 || p + std::uint64_t(size) > n) {
      throw badInput(at, "declares " + std::to_string(size) + " bytes, more than the file holds");
    }
    const std::uint64_t valueStart = p;
    if (const std::uint64_t fixed = expectedSize(type); fixed != 0 && std::uint64_t(size) != fixed) {
      throw badInput(at, "a " + type + " holds " + std::to_string(fixed) + " bytes, not " + std::to_string(size));
    }
    if (type == "chlist") {  // name\0, then pixel type, pLinear + 3 reserved, x and y sampling
      while (true) {
        if (readString("channel name").empty()) break;
        p += 16;
        if (p > valueStart + std::uint64_t(size) || p > cap) break;
      }
      if (p != valueStart + std::uint64_t(size)) throw badInput(at, "channel list does not match its declared size");
    } else if (type == "preview") {
      const std::uint64_t w = std::uint32_t(readInt()), h = std::uint32_t(readInt());
      if (8 + w * h * 4 != std::uint64_t(size)) throw badInput(at, "preview image does not match its declared size");
    }
    p = valueStart + std::uint64_t(size);
  }
}

// "(x0,y0)-(x1,y1)".
std::string boxText(const Imath::Box2i& box) {
  return "(" + std::to_string(box.min.x) + "," + std::to_string(box.min.y) + ")-(" + std::to_string(box.max.x) + "," +
         std::to_string(box.max.y) + ")";
}

}  // namespace

void setExrThreads(int threads) {
  threads = resolveThreadCount(threads);  // 0 = all cores, as everywhere else
  Imf::setGlobalThreadCount(threads > 1 ? threads : 0);
}

const char* exrCompressionName(ExrCompression compression) {
  switch (compression) {
    case ExrCompression::kNone: return "none";
    case ExrCompression::kRle: return "rle";
    case ExrCompression::kZips: return "zips";
    case ExrCompression::kZip: return "zip";
    case ExrCompression::kPiz: return "piz";
  }
  return "?";
}

void writeExr(const Framebuffer& fb, const std::string& path, ExrCompression compression) {
  setLimits();
  AtomicOutput out(path);
  try {
    Imf::Header header(fb.width(), fb.height());
    // Every one of these is lossless for FLOAT and UINT.
    switch (compression) {
      case ExrCompression::kNone: header.compression() = Imf::NO_COMPRESSION; break;
      case ExrCompression::kRle: header.compression() = Imf::RLE_COMPRESSION; break;
      case ExrCompression::kZips: header.compression() = Imf::ZIPS_COMPRESSION; break;
      case ExrCompression::kZip: header.compression() = Imf::ZIP_COMPRESSION; break;
      case ExrCompression::kPiz: header.compression() = Imf::PIZ_COMPRESSION; break;
    }
    header.zipCompressionLevel() = 1;  // read by zip and zips only; not stored in the file
    Imf::FrameBuffer slices;
    const std::size_t xStride = 4, yStride = 4 * std::size_t(fb.width());
    for (const Channel& c : fb.channels()) {
      header.channels().insert(c.name, Imf::Channel(pixelType(c.type)));
      slices.insert(c.name, Imf::Slice(pixelType(c.type), planeBase(c), xStride, yStride));
    }
    for (const auto& [key, value] : fb.attributes) {
      header.insert(key, Imf::StringAttribute(value));
    }
    Imf::OutputFile file(out.tempPath().c_str(), header);
    file.setFrameBuffer(slices);
    file.writePixels(fb.height());
  } catch (const std::bad_alloc&) {
    throw outOfMemory(path, "writing " + std::to_string(fb.width()) + "x" + std::to_string(fb.height()) + " pixels in " +
                                std::to_string(fb.channels().size()) + " channels");
  } catch (const std::exception& e) {
    throw ioError(path, std::string("cannot write EXR: ") + e.what());
  }
  out.commit();
}

namespace {

// The frame an EXR's header declares, checked before anything is allocated: a whole frame
// (data window = display window from (0,0)) of at most kMaxImageSide a side, whose pixel data
// fits the memory budget and is plausible for the file's size (a 30-byte file must not make us
// allocate gigabytes). Returns its width and height; `pixels` says them with the channels and
// bytes, for running out of memory.
Imath::V2i checkFrame(const std::string& path, const Imf::Header& header, std::string& pixels) {
  const Imath::Box2i window = header.dataWindow();
  const long long width = static_cast<long long>(window.max.x) - window.min.x + 1;
  const long long height = static_cast<long long>(window.max.y) - window.min.y + 1;
  if (width <= 0 || height <= 0 || width > kMaxImageSide || height > kMaxImageSide) {
    throw badInput(path + ": dataWindow", "absurd size " + std::to_string(width) + "x" +
                                              std::to_string(height));
  }
  int channelCount = 0;
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it) ++channelCount;
  const unsigned long long raw = static_cast<unsigned long long>(width) * height * 4ull * channelCount;
  if (raw > kMaxImageBytes) {
    throw badInput(path + ": dataWindow", std::to_string(width) + "x" + std::to_string(height) + " with " +
                                              std::to_string(channelCount) + " channels exceeds the 4 GiB image limit");
  }
  pixels = std::to_string(width) + "x" + std::to_string(height) + " pixels in " + std::to_string(channelCount) +
           " channels (" + std::to_string(raw) + " bytes)";
  std::error_code sizeError;
  const unsigned long long fileSize = std::filesystem::file_size(path, sizeError);
  if (!sizeError && fileSize * kMaxCompressionRatio < raw) {
    throw badInput(path + ": dataWindow", "declares " + std::to_string(raw) + " bytes of pixels in a file of " +
                                              std::to_string(fileSize) + " bytes: truncated or corrupt");
  }
  // Pixel (x, y) of a frame is the camera's pixel (x, y) only where the data window is the
  // whole display window and starts at (0, 0): a shifted or cropped data window would
  // otherwise be compared as if it were aligned with the other image.
  const Imath::Box2i display = header.displayWindow();
  if (window != display) {
    throw badInput(path + ": dataWindow", boxText(window) + " is not the displayWindow " + boxText(display) +
                                              "; compare reads whole frames (docs/compare.md)");
  }
  if (display.min != Imath::V2i(0, 0)) {
    throw badInput(path + ": displayWindow", boxText(display) +
                                                 " does not start at (0,0); compare reads frames whose pixel (0,0) "
                                                 "is the camera's (docs/compare.md)");
  }
  return {int(width), int(height)};
}

// A plane of `fb` for each channel the header declares, FLOAT or UINT at full resolution, and
// the slices that read into them.
Imf::FrameBuffer addChannels(const std::string& path, const Imf::Header& header, Framebuffer& fb) {
  Imf::FrameBuffer slices;
  const std::size_t xStride = 4, yStride = 4 * std::size_t(fb.width());
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
    const std::string name = it.name();
    const Imf::Channel& ch = it.channel();
    if (ch.xSampling != 1 || ch.ySampling != 1) {
      throw badInput(path + ": channel " + name, "subsampled channels are not supported");
    }
    char* base = nullptr;
    if (ch.type == Imf::UINT) {
      base = reinterpret_cast<char*>(fb.addUint(name));
    } else if (ch.type == Imf::FLOAT) {
      base = reinterpret_cast<char*>(fb.addFloat(name));
    } else {
      throw badInput(path + ": channel " + name,
                     "is HALF; rastercheck compares FLOAT data (HALF cannot hold ground truth)");
    }
    slices.insert(name, Imf::Slice(ch.type, base, xStride, yStride));
  }
  return slices;
}

}  // namespace

Framebuffer readExr(const std::string& path) {
  setLimits();
  checkOpenable(path);
  std::string pixels = "its header";  // what was being read, for running out of memory
  try {
    Imf::InputFile file(path.c_str());
    const Imath::V2i size = checkFrame(path, file.header(), pixels);
    Framebuffer fb(size.x, size.y);
    const Imf::FrameBuffer slices = addChannels(path, file.header(), fb);
    for (auto it = file.header().begin(); it != file.header().end(); ++it) {
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute())) {
        fb.attributes[it.name()] = s->value();
      }
    }
    file.setFrameBuffer(slices);
    const Imath::Box2i window = file.header().dataWindow();
    file.readPixels(window.min.y, window.max.y);
    if (!file.isComplete()) throw badInput(path, "truncated: some pixel data is missing");
    return fb;
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw outOfMemory(path, "reading " + pixels);
  } catch (const std::exception& e) {
    throw badInput(path, std::string("invalid EXR: ") + e.what());
  }
}

}  // namespace rc
