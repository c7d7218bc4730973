// EXR round trips are bit-exact and invalid files are refused with the right error.
#include <gtest/gtest.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "core/error.h"
#include "core/exr_io.h"
#include "tests/test_files.h"

namespace rc {
namespace {

namespace fs = std::filesystem;

Framebuffer specialValues() {
  Framebuffer fb(7, 3);
  std::uint32_t* ids = fb.addUint("tri.id");
  float* values = fb.addFloat("bary.b0");
  const float specials[] = {0.0f, -0.0f, 1.0f, std::numeric_limits<float>::denorm_min(),
                            std::numeric_limits<float>::max(), -std::numeric_limits<float>::infinity(),
                            std::numeric_limits<float>::quiet_NaN(), 1e-30f, 3.14159274f};
  for (std::size_t i = 0; i < fb.pixelCount(); ++i) {
    ids[i] = i == 0 ? 0xFFFFFFFFu : std::uint32_t(i * 2654435761u);
    values[i] = specials[i % 9];
  }
  fb.attributes["rastercheck.scene"] = "special values";
  return fb;
}

std::int32_t expectError(const std::string& path) {
  try {
    readExr(path);
  } catch (const Error& e) {
    return int(e.code());
  }
  return -1;
}

TEST(ExrIo, RoundTripIsBitExactForUintAndFloatWithEveryCodec) {
  const testing::TempDir temp;  // removed at the end of the test
  const Framebuffer original = specialValues();
  const std::pair<ExrCompression, Imf::Compression> codecs[] = {
      {ExrCompression::kZip, Imf::ZIP_COMPRESSION},   {ExrCompression::kPiz, Imf::PIZ_COMPRESSION},
      {ExrCompression::kZips, Imf::ZIPS_COMPRESSION}, {ExrCompression::kRle, Imf::RLE_COMPRESSION},
      {ExrCompression::kNone, Imf::NO_COMPRESSION}};
  for (const auto& [codec, stored] : codecs) {
    SCOPED_TRACE(exrCompressionName(codec));
    const fs::path path = temp.path() / (std::string(exrCompressionName(codec)) + ".exr");
    writeExr(original, path.string(), codec);
    EXPECT_EQ(Imf::InputFile(path.c_str()).header().compression(), stored);
    const Framebuffer back = readExr(path.string());
    ASSERT_EQ(back.width(), 7);
    ASSERT_EQ(back.height(), 3);
    const Channel* ids = back.find("tri.id");
    const Channel* values = back.find("bary.b0");
    ASSERT_TRUE(ids && values);
    EXPECT_EQ(ids->type, ChannelType::kUint);
    EXPECT_EQ(values->type, ChannelType::kFloat);
    EXPECT_EQ(0, std::memcmp(ids->uints.data(), original.find("tri.id")->uints.data(), 21 * 4));
    EXPECT_EQ(0, std::memcmp(values->floats.data(), original.find("bary.b0")->floats.data(), 21 * 4));
    EXPECT_EQ(back.attributes.at("rastercheck.scene"), "special values");
  }
  // The default is ZIP.
  writeExr(original, (temp.path() / "default.exr").string());
  EXPECT_EQ(Imf::InputFile((temp.path() / "default.exr").c_str()).header().compression(), Imf::ZIP_COMPRESSION);
}

TEST(ExrIo, TruncatedFileIsBadInput) {
  const testing::TempDir temp;
  const fs::path& dir = temp.path();
  writeExr(specialValues(), (dir / "whole.exr").string());
  std::ifstream in(dir / "whole.exr", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), {});
  std::ofstream((dir / "cut.exr"), std::ios::binary).write(bytes.data(), std::streamsize(bytes.size() * 2 / 3));
  EXPECT_EQ(expectError((dir / "cut.exr").string()), int(ExitCode::kBadInput));
}

TEST(ExrIo, EmptyFileIsBadInputAndMissingFileIsIoError) {
  const testing::TempDir temp;
  const fs::path& dir = temp.path();
  std::ofstream(dir / "empty.exr").close();
  EXPECT_EQ(expectError((dir / "empty.exr").string()), int(ExitCode::kBadInput));
  EXPECT_EQ(expectError((dir / "absent.exr").string()), int(ExitCode::kIo));
}

TEST(ExrIo, NotAnExrIsBadInput) {
  const testing::TempDir temp;
  const fs::path& dir = temp.path();
  std::ofstream(dir / "text.exr") << "this is not an image";
  EXPECT_EQ(expectError((dir / "text.exr").string()), int(ExitCode::kBadInput));
}

TEST(ExrIo, WriteIntoMissingFolderIsIoErrorAndLeavesNothing) {
  const testing::TempDir temp;
  const fs::path dir = temp.path() / "missing";
  try {
    writeExr(specialValues(), (dir / "x.exr").string());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kIo);
  }
  EXPECT_FALSE(fs::exists(dir));
}

}  // namespace
}  // namespace rc
