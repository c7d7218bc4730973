// PNG output with libpng; errors surface through setjmp as rc::Error after cleanup.
#include "core/png_io.h"

#include <png.h>

#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>

#include "core/atomic_file.h"
#include "core/error.h"

namespace rc {

Rgb8Image::Rgb8Image(int w, int h, Rgb8 fill) : width(w), height(h), pixels(std::size_t(w) * h * 3) {
  for (std::size_t i = 0; i < pixels.size(); i += 3) {
    pixels[i] = fill[0];
    pixels[i + 1] = fill[1];
    pixels[i + 2] = fill[2];
  }
}

void Rgb8Image::set(int x, int y, Rgb8 c) {
  if (x < 0 || y < 0 || x >= width || y >= height) return;
  std::uint8_t* p = &pixels[(std::size_t(y) * width + x) * 3];
  p[0] = c[0];
  p[1] = c[1];
  p[2] = c[2];
}

void Rgb8Image::paste(const Rgb8Image& other, int x0, int y0) {
  for (int y = 0; y < other.height; ++y) {
    for (int x = 0; x < other.width; ++x) {
      const std::uint8_t* p = &other.pixels[(std::size_t(y) * other.width + x) * 3];
      set(x0 + x, y0 + y, {p[0], p[1], p[2]});
    }
  }
}

namespace {

std::uint8_t encodeSrgb(float linear) {
  if (!(linear > 0.0f)) return 0;  // also NaN
  if (linear >= 1.0f) return 255;
  const double v = linear <= 0.0031308f ? 12.92 * linear : 1.055 * std::pow(double(linear), 1.0 / 2.4) - 0.055;
  return std::uint8_t(std::lround(v * 255.0));
}

// libpng's errors, kept for the message instead of printed ("libpng error: Write Error"): its
// message, and errno as the failing fwrite left it (ENOSPC on a full disk).
struct PngFailure {
  int savedErrno = 0;
  char message[128] = {};
};

[[noreturn]] void onPngError(png_structp png, png_const_charp message) {
  auto* failure = static_cast<PngFailure*>(png_get_error_ptr(png));
  failure->savedErrno = errno;
  std::snprintf(failure->message, sizeof failure->message, "%s", message);
  png_longjmp(png, 1);
}

void onPngWarning(png_structp, png_const_charp) {}

}  // namespace

Rgb8Image displayImage(const Framebuffer& fb) {
  const Channel* c[3] = {fb.find("R"), fb.find("G"), fb.find("B")};
  for (const Channel* channel : c) {
    if (!channel || channel->type != ChannelType::kFloat) throw internalError("displayImage: no R, G, B channels");
  }
  Rgb8Image image(fb.width(), fb.height(), {0, 0, 0});
  for (std::size_t i = 0; i < fb.pixelCount(); ++i) {
    for (int k = 0; k < 3; ++k) image.pixels[3 * i + k] = encodeSrgb(c[k]->floats[i]);
  }
  return image;
}

void writePng(const Rgb8Image& image, const std::string& path) {
  AtomicOutput out(path);
  FILE* file = std::fopen(out.tempPath().c_str(), "wb");
  if (!file) throw ioError(path, std::string("cannot write PNG: ") + std::strerror(errno));
  PngFailure failure;
  errno = 0;  // so that an errno kept on failure is the write's
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &failure, onPngError, onPngWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  volatile bool ok = png && info;  // volatile: survives libpng's longjmp
  if (ok && setjmp(png_jmpbuf(png)) == 0) {
    png_init_io(png, file);
    png_set_IHDR(png, info, png_uint_32(image.width), png_uint_32(image.height), 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    // zlib level 3 and the Sub filter alone, in place of level 6 with libpng's choice of filter
    // per row: on the 1920x1080 pictures of the blob at 1M triangles a preview wrote in 48
    // instead of 152 ms (27% more bytes) and a heatmap in 51 instead of 229 ms (34% fewer).
    png_set_compression_level(png, 3);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
    png_write_info(png, info);
    for (int y = 0; y < image.height; ++y) {
      png_write_row(png, &image.pixels[std::size_t(y) * image.width * 3]);
    }
    png_write_end(png, nullptr);
  } else {
    ok = false;
  }
  png_destroy_write_struct(&png, &info);
  const bool closed = std::fclose(file) == 0;
  if (!closed && !failure.savedErrno) failure.savedErrno = errno;
  if (!ok || !closed) {
    const std::string cause = failure.savedErrno ? std::strerror(failure.savedErrno)
                              : failure.message[0] ? failure.message
                                                   : "libpng could not start";
    throw ioError(path, "cannot write PNG: " + cause);
  }
  out.commit();
}

}  // namespace rc
