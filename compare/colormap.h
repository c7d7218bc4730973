// A perceptual colour map (magma, sampled at nine stops from matplotlib's table and
// interpolated linearly) and the colours reserved for pixel classes, which magma never uses.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace rc {

using Rgb = std::array<float, 3>;

inline Rgb magma(double t) {
  static const float kStops[9][3] = {
      {0.0015f, 0.0005f, 0.0139f}, {0.0788f, 0.0542f, 0.2117f}, {0.2321f, 0.0599f, 0.4377f},
      {0.3904f, 0.1004f, 0.5019f}, {0.5503f, 0.1612f, 0.5057f}, {0.7164f, 0.2150f, 0.4753f},
      {0.8688f, 0.2877f, 0.4093f}, {0.9737f, 0.5184f, 0.3678f}, {0.9871f, 0.9914f, 0.7495f}};
  if (!(t >= 0.0)) t = 0.0;  // NaN maps to the bottom; callers colour NaN separately
  t = std::min(t, 1.0) * 8.0;
  const int i = std::min(int(t), 7);
  const float f = float(t - i);
  return {kStops[i][0] + f * (kStops[i + 1][0] - kStops[i][0]),
          kStops[i][1] + f * (kStops[i + 1][1] - kStops[i][1]),
          kStops[i][2] + f * (kStops[i + 1][2] - kStops[i][2])};
}

// Log scale of a heatmap quantity: values at or below 10^logMin are the darkest, 10^logMax
// and above the brightest.
struct HeatScale {
  double logMin, logMax;
  const char* title;  // legend title
  const char* key;    // as recorded in the heatmap's header (rastercheck.heatmapQuantity)
};

inline HeatScale heatScaleByKey(const std::string& key) {
  if (key == "ulps") return {-1.0, 6.0, "barycentric error in float ulps just below 1 (2^-24), same triangle", "ulps"};
  if (key == "bound") return {-4.0, 2.0, "barycentric error / bound (above 1 fails), same triangle", "bound"};
  return {-8.0, -1.0, "barycentric error |b_test - b_ref|, same triangle", "error"};
}

inline Rgb heatColour(double value, const HeatScale& scale) {
  if (!(value > 0.0)) return magma(0.0);
  return magma((std::log10(value) - scale.logMin) / (scale.logMax - scale.logMin));
}

// The stops above are sRGB-encoded (display) values; EXR holds linear light.
inline Rgb linearFromSrgb(const Rgb& c) {
  Rgb out;
  for (int k = 0; k < 3; ++k) {
    out[k] = c[k] <= 0.04045f ? c[k] / 12.92f : float(std::pow((c[k] + 0.055) / 1.055, 2.4));
  }
  return out;
}

inline constexpr Rgb kColourBackground{0.15f, 0.15f, 0.15f};     // both empty: grey
inline constexpr Rgb kColourDifferentTriangle{0.0f, 1.0f, 0.0f};  // green
inline constexpr Rgb kColourOneSideOnly{0.0f, 0.9f, 1.0f};        // cyan
inline constexpr Rgb kColourNonFinite{1.0f, 0.0f, 1.0f};          // NaN or Inf: magenta
inline constexpr Rgb kColourUnexplained{1.0f, 0.0f, 0.0f};        // unexplained disagreement

}  // namespace rc
