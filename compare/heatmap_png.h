// The heatmap as a picture for people: the false-colour error map above a legend that gives
// the log scale and the colours reserved for pixel classes.
#pragma once

#include "core/png_io.h"
#include "core/framebuffer.h"

namespace rc {

// From a heatmap made by compareImages (its R, G, B). The image is at least 760 pixels wide so
// the legend fits; a narrower map sits at the top left on grey.
Rgb8Image heatmapImage(const Framebuffer& heatmap);

}  // namespace rc
