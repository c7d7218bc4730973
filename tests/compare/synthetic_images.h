// The small synthetic images the compare tests build, whose differences are known exactly.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "compare/compare.h"
#include "core/channels.h"
#include "core/framebuffer.h"

namespace rc::testing {

inline constexpr int kW = 10, kH = 10;

// Every pixel covered by triangle 1 with b = (0.25, 0.25, 0.5), depth 4, uv = (x, y).
inline Framebuffer image() {
  Framebuffer fb(kW, kH);
  fb.addUint(channels::kTriangleId, 1);
  fb.addFloat(channels::kBary[0], 0.25f);
  fb.addFloat(channels::kBary[1], 0.25f);
  fb.addFloat(channels::kBary[2], 0.5f);
  fb.addFloat(channels::kDepth, 4.0f);
  float* u = fb.addFloat(channels::attributeChannel("uv", 0));
  float* v = fb.addFloat(channels::attributeChannel("uv", 1));
  for (int i = 0; i < kW * kH; ++i) {
    u[i] = float(i % kW);
    v[i] = float(i / kW);
  }
  return fb;
}

inline float& at(Framebuffer& fb, const std::string& channel, int x, int y) {
  return fb.find(channel)->floats[std::size_t(y) * kW + x];
}
inline std::uint32_t& idAt(Framebuffer& fb, int x, int y) {
  return fb.find(channels::kTriangleId)->uints[std::size_t(y) * kW + x];
}

inline const FamilyReport& family(const CompareReport& r, const std::string& name) {
  for (const FamilyReport& f : r.families) {
    if (f.name == name) return f;
  }
  throw std::runtime_error("no family " + name);
}

}  // namespace rc::testing
