// TextRenderer over FreeType: grey-scale glyphs blended onto the image.
#include "core/text.h"

#include <ft2build.h>
#include FT_FREETYPE_H

#include "core/error.h"

namespace rc {

struct TextRenderer::Impl {
  FT_Library library = nullptr;
  FT_Face face = nullptr;
};

TextRenderer::TextRenderer(int pixelHeight, const std::string& fontPath) : impl_(new Impl) {
  if (FT_Init_FreeType(&impl_->library) != 0 || FT_New_Face(impl_->library, fontPath.c_str(), 0, &impl_->face) != 0 ||
      FT_Set_Pixel_Sizes(impl_->face, 0, FT_UInt(pixelHeight)) != 0) {
    if (impl_->library) FT_Done_FreeType(impl_->library);
    delete impl_;
    throw ioError(fontPath, "cannot load the label font (Debian package fonts-dejavu-core)");
  }
}

TextRenderer::~TextRenderer() {
  FT_Done_Face(impl_->face);
  FT_Done_FreeType(impl_->library);
  delete impl_;
}

int TextRenderer::draw(Rgb8Image& image, int x, int baseline, const std::string& text, Rgb8 colour) const {
  const int start = x;
  for (unsigned char c : text) {
    if (FT_Load_Char(impl_->face, c, FT_LOAD_RENDER) != 0) continue;
    const FT_GlyphSlot g = impl_->face->glyph;
    for (unsigned row = 0; row < g->bitmap.rows; ++row) {
      for (unsigned col = 0; col < g->bitmap.width; ++col) {
        const int alpha = g->bitmap.buffer[row * unsigned(g->bitmap.pitch) + col];
        const int px = x + g->bitmap_left + int(col), py = baseline - g->bitmap_top + int(row);
        if (alpha == 0 || px < 0 || py < 0 || px >= image.width || py >= image.height) continue;
        std::uint8_t* p = &image.pixels[(std::size_t(py) * image.width + px) * 3];
        for (int k = 0; k < 3; ++k) p[k] = std::uint8_t((p[k] * (255 - alpha) + colour[k] * alpha) / 255);
      }
    }
    x += int(g->advance.x >> 6);
  }
  return x - start;
}

int TextRenderer::measure(const std::string& text) const {
  int width = 0;
  for (unsigned char c : text) {
    if (FT_Load_Char(impl_->face, c, FT_LOAD_DEFAULT) == 0) width += int(impl_->face->glyph->advance.x >> 6);
  }
  return width;
}

}  // namespace rc
