// UV-sphere tessellation and vertex normals.
#include "scenes/builtin/uv_sphere.h"

#include <cmath>

namespace rc::builtin {

Mesh makeUvSphereMesh(int stacks, int slices,
                      const std::function<glm::vec3(double, double)>& position) {
  Mesh mesh;
  // Reserved at their final sizes: grown by doubling, a million-triangle mesh's arrays were
  // copied and faulted in about twice over (16,049 page faults loading blob:tris=1000000).
  const std::size_t vertices = std::size_t(stacks + 1) * std::size_t(slices + 1);
  mesh.positions.reserve(vertices);
  mesh.triangles.reserve(2 * std::size_t(stacks - 1) * std::size_t(slices));
  HugeVector<float> uvs;
  uvs.reserve(2 * vertices);
  for (int i = 0; i <= stacks; ++i) {
    const double theta = M_PI * i / stacks;
    for (int j = 0; j <= slices; ++j) {
      // The seam's second column (j = slices) takes the first one's angle, 0 rather than a
      // rounded 2 pi, and each pole row takes one angle for all its columns (sin(pi) rounds to
      // 1.2e-16, not 0): repeated positions are the same bit for bit, so the surface closes
      // exactly (Mesh::closedSolid).
      const bool pole = i == 0 || i == stacks;
      const double phi = pole ? 0.0 : 2.0 * M_PI * (j % slices) / slices;
      mesh.positions.push_back(position(theta, phi));
      uvs.push_back(float(double(j) / slices));
      uvs.push_back(float(double(i) / stacks));
    }
  }
  const auto index = [&](int i, int j) { return unsigned(i * (slices + 1) + j); };
  for (int i = 0; i < stacks; ++i) {
    for (int j = 0; j < slices; ++j) {
      const unsigned a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1),
                     d = index(i, j + 1);
      if (i != 0) mesh.triangles.push_back({a, b, d});           // the top row's is degenerate
      if (i != stacks - 1) mesh.triangles.push_back({d, b, c});  // the bottom row's too
    }
  }
  mesh.attributes.push_back({"uv", 2, std::move(uvs)});
  return mesh;
}

void addVertexNormals(Mesh& mesh) {
  std::vector<glm::dvec3> sum(mesh.positions.size(), glm::dvec3(0.0));
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::dvec3 p0(mesh.positions[t.x]), p1(mesh.positions[t.y]), p2(mesh.positions[t.z]);
    const glm::dvec3 n = glm::cross(p1 - p0, p2 - p0);  // length = twice the area
    sum[t.x] += n;
    sum[t.y] += n;
    sum[t.z] += n;
  }
  Attribute& normal = mesh.addAttribute("normal", 3);
  for (std::size_t i = 0; i < sum.size(); ++i) {
    const double length = glm::length(sum[i]);
    const glm::dvec3 n = length > 0.0 ? sum[i] / length : glm::dvec3(0.0, 0.0, 1.0);
    for (int k = 0; k < 3; ++k) normal.values[3 * i + k] = float(n[k]);
  }
}

}  // namespace rc::builtin
