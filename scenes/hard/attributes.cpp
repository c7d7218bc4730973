// "attributes": one mesh (a 6 x 4 grid of quads, tilted in depth) carrying four attributes of
// awkward magnitude: "huge" (values near 10^30), "tiny" (near 10^-30), "mixed" (+-10^30 next to
// values near 1, so interpolation cancels) and "constant" (3.7 at every vertex, 4 components).
//
// Stresses: attribute interpolation sum(b_i a_i) in float: overflow, underflow, cancellation.
// Must hold: no Inf or NaN; every attribute within gamma_3 sum|b_i a_i| + sum|db_i||a_i| of the
// exact value (docs/numerics.md); the constant attribute equal to 3.7 within 8 float ulps.
#include <cmath>
#include <utility>

#include "scenes/hard/builder.h"
#include "scenes/hard/hard_scenes.h"

namespace rc::hard {

Scene makeAttributes(SceneArgs&) {
  Builder b("attributes", frontCamera(160, 120));
  const DepthPlane plane{80.0, 60.0, 3.0, 1.5e-3, -1e-3};
  const int nx = 6, ny = 4;
  unsigned grid[ny + 1][nx + 1];
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      const double x = 6.3 + 24.7 * i, y = 5.1 + 27.3 * j;
      grid[j][i] = b.at(x, y, plane.at(x, y));
    }
  }
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      b.triangle(grid[j][i], grid[j][i + 1], grid[j + 1][i + 1]);
      b.triangle(grid[j][i], grid[j + 1][i + 1], grid[j + 1][i]);
    }
  }
  Mesh& mesh = b.mesh();
  for (const auto& [name, components] : {std::pair{"huge", 1}, {"tiny", 2}, {"mixed", 1}, {"constant", 4}}) {
    mesh.addAttribute(name, components);  // all added first: the vector may move its elements
  }
  Attribute& huge = mesh.attributes[0];
  Attribute& tiny = mesh.attributes[1];
  Attribute& mixed = mesh.attributes[2];
  Attribute& constant = mesh.attributes[3];
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
    const double s = 1.0 + 0.37 * double(v % 7);
    huge.values[v] = float(s * 1e30);
    tiny.values[2 * v] = float(s * 1e-30);
    tiny.values[2 * v + 1] = float(-s * 3e-31);
    mixed.values[v] = v % 3 == 0 ? 1e30f : v % 3 == 1 ? -1e30f : float(s);
    for (int c = 0; c < 4; ++c) constant.values[4 * v + c] = 3.7f;
  }
  return b.finish();
}

}  // namespace rc::hard
