// RGB preview from a render's channels.
#include "core/preview.h"

#include <cmath>

#include "core/channels.h"

namespace rc {
namespace {

const float* plane(const Framebuffer& fb, const std::string& name) {
  const Channel* c = fb.find(name);
  return c && c->type == ChannelType::kFloat ? c->floats.data() : nullptr;
}

}  // namespace

void addPreview(Framebuffer& fb) {
  using namespace channels;
  const Channel* idChannel = fb.find(kTriangleId);
  const float* u = plane(fb, attributeChannel("uv", 0));
  const float* v = plane(fb, attributeChannel("uv", 1));
  const float* n[3] = {plane(fb, attributeChannel("normal", 0)),
                       plane(fb, attributeChannel("normal", 1)),
                       plane(fb, attributeChannel("normal", 2))};
  const bool hasNormal = n[0] && n[1] && n[2];
  const float* b[3] = {plane(fb, kBary[0]), plane(fb, kBary[1]), plane(fb, kBary[2])};
  float* rgb[3] = {fb.addFloat(kPreview[0]), fb.addFloat(kPreview[1]), fb.addFloat(kPreview[2])};
  for (std::size_t i = 0; i < fb.pixelCount(); ++i) {
    if (!idChannel || idChannel->uints[i] == kNoTriangle) continue;
    float colour[3] = {b[0] ? b[0][i] : 0.f, b[1] ? b[1][i] : 0.f, b[2] ? b[2][i] : 0.f};
    if (hasNormal) {
      for (int k = 0; k < 3; ++k) colour[k] = 0.5f + 0.5f * n[k][i];
    }
    if (u && v) {
      // Parity of floor(8u) + floor(8v), in double so no float-to-int conversion can overflow.
      const double cu = std::fmod(std::floor(double(u[i]) * 8.0), 2.0);
      const double cv = std::fmod(std::floor(double(v[i]) * 8.0), 2.0);
      const float shade = (std::fabs(cu + cv) == 1.0) ? 0.25f : 1.0f;
      for (int k = 0; k < 3; ++k) colour[k] = (hasNormal ? colour[k] : 0.9f) * shade;
    }
    for (int k = 0; k < 3; ++k) rgb[k][i] = colour[k];
  }
}

}  // namespace rc
