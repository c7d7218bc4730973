// The RGB preview written into every render so any EXR viewer shows something meaningful.
// It is computed from the render's own channels, so both renderers get it from one function.
#pragma once

#include "core/framebuffer.h"

namespace rc {

// Adds channels R, G, B: a checkerboard of attr.uv (8 squares per unit, the pattern that makes
// affine interpolation visible) shaded by attr.normal when present; without uv, the normal as
// a colour; without either, the barycentrics. Background pixels are black.
void addPreview(Framebuffer& fb);

}  // namespace rc
