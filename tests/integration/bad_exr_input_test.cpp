// Broken EXR files given to compare, and images holding NaN or infinity: each refused with its
// documented exit code and a message naming the file and the place, or, for the values, failed
// and counted (the other hostile and broken inputs in bad_input_test.cpp).
#include <gtest/gtest.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>

#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/exr_io.h"
#include "core/framebuffer.h"
#include "tests/integration/bad_input.h"

namespace {

using namespace rc::testing::bad_input;

// Offset of the first byte after an EXR header (where the chunk table starts), by walking its
// attribute list: name\0 type\0 size value, ended by an empty name.
std::size_t endOfHeader(const std::string& bytes) {
  std::size_t p = 8;
  while (bytes[p] != '\0') {
    p = bytes.find('\0', p) + 1;  // name
    p = bytes.find('\0', p) + 1;  // type
    std::int32_t size;
    std::memcpy(&size, bytes.data() + p, 4);
    p += 4 + std::size_t(size);
  }
  return p + 1;
}

// A 4x4 EXR with HALF values; `sampling` > 1 stores bary.b0 at every sampling-th pixel each way.
void writeHalfExr(const std::string& path, int sampling = 1) {
  Imf::Header header(4, 4);
  for (const char* name : {"tri.id", "bary.b0", "bary.b1", "bary.b2", "depth.z"}) {
    const int s = std::string(name) == "bary.b0" ? sampling : 1;
    header.channels().insert(name, Imf::Channel(std::string(name) == "tri.id" ? Imf::UINT : Imf::HALF, s, s));
  }
  Imf::OutputFile file(path.c_str(), header);
  std::vector<std::uint32_t> ids(16, 0);
  std::vector<std::uint16_t> halves(16, 0x3C00);  // 1.0
  Imf::FrameBuffer slices;
  slices.insert("tri.id", Imf::Slice(Imf::UINT, reinterpret_cast<char*>(ids.data()), 4, 16));
  for (const char* name : {"bary.b0", "bary.b1", "bary.b2", "depth.z"}) {
    const int s = std::string(name) == "bary.b0" ? sampling : 1;
    slices.insert(name, Imf::Slice(Imf::HALF, reinterpret_cast<char*>(halves.data()), 2, 8, s, s));
  }
  file.setFrameBuffer(slices);
  file.writePixels(4);
}

// FROM's channels written again under the windows given (OpenEXR's absolute pixel
// coordinates): the data window holds FROM's pixels from its top-left corner on.
void writeWindowedExr(const std::string& from, const std::string& to, const Imath::Box2i& display,
                      const Imath::Box2i& data) {
  const rc::Framebuffer fb = rc::readExr(from);
  Imf::Header header(display, data);
  Imf::FrameBuffer slices;
  const std::ptrdiff_t xStride = 4, yStride = 4 * std::ptrdiff_t(fb.width());
  const std::ptrdiff_t origin = data.min.x * xStride + data.min.y * yStride;
  for (const rc::Channel& c : fb.channels()) {
    const bool uint = c.type == rc::ChannelType::kUint;
    const Imf::PixelType type = uint ? Imf::UINT : Imf::FLOAT;
    const char* plane = uint ? reinterpret_cast<const char*>(c.uints.data()) : reinterpret_cast<const char*>(c.floats.data());
    header.channels().insert(c.name, Imf::Channel(type));
    slices.insert(c.name, Imf::Slice(type, const_cast<char*>(plane) - origin, xStride, yStride));
  }
  Imf::OutputFile file(to.c_str(), header);
  file.setFrameBuffer(slices);
  file.writePixels(data.max.y - data.min.y + 1);
}

TEST(BadInput, ExrFilesGivenToCompare) {
  TempDir dir;
  const std::string good = dir.file("good.exr"), other = dir.file("other.exr");
  ASSERT_EQ(rastercheck("render cube --size 32x24 -o " + good).exitCode, 0);
  ASSERT_EQ(rastercheck("render cube --size 32x24 --backend reference -o " + other).exitCode, 0);
  const std::string bytes = readAll(good);
  const std::size_t table = endOfHeader(bytes);

  std::string corruptTable = bytes;
  for (std::size_t i = table; i < table + 8 * 2; ++i) corruptTable[i] = '\xFF';
  for (std::size_t i = table + 8 * 2; i < bytes.size(); i += 97) corruptTable[i] = char(corruptTable[i] ^ 0x5A);
  std::string window = bytes;
  const std::size_t dw = window.find("dataWindow") + std::strlen("dataWindow") + 1 + std::strlen("box2i") + 1 + 4;
  const std::int32_t absurd[4] = {0, 0, 1 << 30, 1 << 30};
  std::memcpy(window.data() + dw, absurd, 16);
  // Regression (found by fuzzing): a small file declaring a large but legal window made
  // readExr allocate all planes before OpenEXR noticed the data was missing.
  std::string implausible = bytes;
  const std::int32_t large[4] = {0, 0, 3999, 3999};  // 4000x4000, ~700 MB of planes in a ~30 KB file
  std::memcpy(implausible.data() + dw, large, 16);
  std::string budget = bytes;
  const std::int32_t huge[4] = {0, 0, 16383, 16383};  // 16384^2 x 12 channels x 4 bytes > 4 GiB
  std::memcpy(budget.data() + dw, huge, 16);
  // Regression (found by fuzzing on a fresh machine): an attribute whose size field claims
  // 1.6 GB made OpenEXR allocate it while reading the header.
  std::string attribute = bytes;
  const std::size_t sizeField = attribute.find("pixelAspectRatio") + std::strlen("pixelAspectRatio") + 1 + std::strlen("float") + 1;
  const std::int32_t claimed = 0x61686300;
  std::memcpy(attribute.data() + sizeField, &claimed, 4);
  // Regression (the same fuzz run): sizes that fit the file but disagree with the contents, so
  // OpenEXR (which reads by contents) and a size-based check would walk different headers.
  std::string chlist = bytes;
  const std::size_t chlistSize = chlist.find("chlist") + std::strlen("chlist") + 1;
  std::int32_t declared;
  std::memcpy(&declared, chlist.data() + chlistSize, 4);
  declared -= 18;
  std::memcpy(chlist.data() + chlistSize, &declared, 4);
  std::string fixedSize = bytes;
  const std::size_t boxSize = fixedSize.find("box2i") + std::strlen("box2i") + 1;
  const std::int32_t seventeen = 17;
  std::memcpy(fixedSize.data() + boxSize, &seventeen, 4);
  // A preview attribute of 1x2 pixels (16 bytes with its size fields) that declares 12 bytes,
  // added at the header's end; the offsets after it no longer matter, since it is refused first.
  std::string preview = bytes;
  const std::int32_t previewFields[3] = {12, 1, 2};
  std::string thumb = std::string("thumb\0preview\0", 14) + std::string(reinterpret_cast<const char*>(previewFields), 12) +
                      std::string(8, '\x7F');
  preview.insert(table - 1, thumb);
  std::string inverted = bytes;
  const std::int32_t backwards[4] = {10, 10, 0, 0};
  std::memcpy(inverted.data() + dw, backwards, 16);
  writeHalfExr(dir.file("half.exr"));
  writeHalfExr(dir.file("subsampled.exr"), 2);
  // Through the cube's camera, so that only its channels differ from the cube's.
  ASSERT_EQ(rastercheck("render sphere --size 32x24 --eye 2.6,2.2,3.4 -o " + dir.file("sphere.exr")).exitCode, 0);
  ASSERT_EQ(rastercheck("render cube --size 24x32 -o " + dir.file("portrait.exr")).exitCode, 0);
  // Another renderer's frame, cropped or shifted: read as if aligned, each passed against the
  // reference it is not aligned with.
  const Imath::Box2i frame({0, 0}, {31, 23});
  writeWindowedExr(good, dir.file("shifted.exr"), frame, Imath::Box2i({5, 0}, {36, 23}));
  writeWindowedExr(good, dir.file("cropped.exr"), frame, Imath::Box2i({0, 0}, {15, 23}));
  writeWindowedExr(good, dir.file("overscan.exr"), Imath::Box2i({-4, -2}, {27, 21}), Imath::Box2i({-4, -2}, {27, 21}));

  const struct { std::string file; int code; std::string fragment; } cases[] = {
      {dir.write("zero.exr", ""), 3, "zero.exr"},
      {dir.write("truncated.exr", bytes.substr(0, table + 20)), 3, "truncated.exr"},
      {dir.write("header-only.exr", bytes.substr(0, table - 30)), 3, "header-only.exr"},
      {dir.write("table.exr", corruptTable), 3, "table.exr"},
      {dir.write("window.exr", window), 3, "window.exr"},  // OpenEXR or our limit, naming the window
      {dir.write("inverted.exr", inverted), 3, "inverted.exr"},
      {dir.write("attribute.exr", attribute), 3, "attribute.exr: header attribute 'pixelAspectRatio' at byte"},
      {dir.write("chlist.exr", chlist), 3, "chlist.exr: header attribute 'channels'"},
      {dir.write("fixed.exr", fixedSize), 3, "fixed.exr: header attribute 'dataWindow'"},
      {dir.write("preview.exr", preview), 3, "preview.exr: header attribute 'thumb' at byte " + std::to_string(table - 1) +
                                                 ": preview image does not match its declared size"},
      {dir.write("implausible.exr", implausible), 3, "implausible.exr: dataWindow: declares"},
      {dir.write("budget.exr", budget), 3, "budget.exr"},  // OpenEXR (chunk table) or our 4 GiB limit
      {dir.file("half.exr"), 3, "half.exr: channel bary.b0"},
      {dir.file("subsampled.exr"), 3, "subsampled.exr: channel bary.b0: subsampled channels are not supported"},
      {dir.file("sphere.exr"), 3, "attr.normal"},
      {dir.file("portrait.exr"), 3, "differs"},
      {dir.file("shifted.exr"), 3,
       "shifted.exr: dataWindow: (5,0)-(36,23) is not the displayWindow (0,0)-(31,23); compare reads whole frames"},
      {dir.file("cropped.exr"), 3,
       "cropped.exr: dataWindow: (0,0)-(15,23) is not the displayWindow (0,0)-(31,23); compare reads whole frames"},
      {dir.file("overscan.exr"), 3,
       "overscan.exr: displayWindow: (-4,-2)-(27,21) does not start at (0,0); compare reads frames whose pixel (0,0) is "
       "the camera's"},
      {dir.file("absent.exr"), 4, "absent.exr"},
      {dir.write("text.exr", "P6\n1 1\n255\n   "), 3, "text.exr"},
  };
  for (const auto& c : cases) {
    const fs::path out = dir.path() / "out";
    fs::create_directories(out);
    const Outcome r = rastercheck("compare " + c.file + " " + other + " --json " + (out / "r.json").string() +
                                  " --heatmap " + (out / "h.exr").string() + " --heatmap-png " + (out / "h.png").string());
    EXPECT_EQ(r.exitCode, c.code) << c.file << "\n" << r.output;
    EXPECT_NE(r.output.find(c.fragment), std::string::npos) << c.fragment << "\n" << r.output;
    EXPECT_TRUE(emptyOrAbsent(out)) << c.file << " left output behind";
  }
}

// A 4x4 render-layout EXR, every pixel on triangle 0, with `special` at pixel 5 of bary.b1.
void writeFloatExr(const std::string& path, float special) {
  Imf::Header header(4, 4);
  const char* floats[] = {"bary.b0", "bary.b1", "bary.b2", "depth.z"};
  header.channels().insert("tri.id", Imf::Channel(Imf::UINT));
  for (const char* name : floats) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
  std::vector<std::uint32_t> ids(16, 0);
  std::vector<std::vector<float>> planes(4, std::vector<float>(16, 0.25f));
  planes[1][5] = special;
  Imf::FrameBuffer slices;
  slices.insert("tri.id", Imf::Slice(Imf::UINT, reinterpret_cast<char*>(ids.data()), 4, 16));
  for (int i = 0; i < 4; ++i) slices.insert(floats[i], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(planes[i].data()), 4, 16));
  Imf::OutputFile file(path.c_str(), header);
  file.setFrameBuffer(slices);
  file.writePixels(4);
}

TEST(BadInput, NanOrInfInEitherImageFailsTheGateAndIsCounted) {
  TempDir dir;
  writeFloatExr(dir.file("clean.exr"), 0.25f);
  writeFloatExr(dir.file("nan.exr"), std::numeric_limits<float>::quiet_NaN());
  writeFloatExr(dir.file("inf.exr"), std::numeric_limits<float>::infinity());
  EXPECT_EQ(rastercheck("compare " + dir.file("clean.exr") + " " + dir.file("clean.exr")).exitCode, 0);
  const struct { const char* test; const char* ref; const char* counted; } cases[] = {
      {"nan.exr", "clean.exr", "\"nan\": 1"}, {"clean.exr", "nan.exr", "\"nan\": 1"},
      {"inf.exr", "clean.exr", "\"inf\": 1"}, {"clean.exr", "inf.exr", "\"inf\": 1"}, {"nan.exr", "nan.exr", "\"nan\": 1"}};
  for (const auto& c : cases) {
    // Even with thresholds that let any finite error through.
    const Outcome r = rastercheck("compare " + dir.file(c.test) + " " + dir.file(c.ref) + " --max-bary 1e30 --max-depth 1e30" +
                                  " --max-disagreement 1 --max-coverage 1 --json " + dir.file("r.json"));
    EXPECT_EQ(r.exitCode, 1) << c.test << " vs " << c.ref << "\n" << r.output;
    EXPECT_NE(readAll(dir.file("r.json")).find(c.counted), std::string::npos) << c.test << " vs " << c.ref;
  }
}

}  // namespace
