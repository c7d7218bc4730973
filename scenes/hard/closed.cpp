// "closed:seed=N": a random closed mesh, a subdivided icosahedron with jittered vertex radii,
// randomly rotated, in front of the camera.
//
// Stresses: watertightness of a closed surface, where silhouette edges are shared by a front-
// and a back-facing triangle lying on the same side of the edge on screen.
// Must hold: at every pixel centre, as many front-facing as back-facing triangles cover it
// (a ray enters and leaves a closed surface equally often), so there are no holes and no
// double covers; the visible owner is the nearest front face.
#include <algorithm>
#include <cstdint>
#include <map>
#include <random>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "scenes/hard/builder.h"
#include "scenes/hard/hard_scenes.h"

namespace rc::hard {

Mesh jitteredSphere(std::uint64_t seed, int subdivisions, double jitter) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<glm::dvec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                               {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<glm::uvec3> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                               {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                               {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                               {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<unsigned, unsigned>, unsigned> midpoints;
    const auto mid = [&](unsigned a, unsigned b) {
      const auto key = std::minmax(a, b);
      auto [it, added] = midpoints.emplace(key, unsigned(v.size()));
      if (added) v.push_back(glm::normalize(v[a] + v[b]));
      return it->second;
    };
    std::vector<glm::uvec3> next;
    for (const glm::uvec3& tri : f) {
      const unsigned a = mid(tri.x, tri.y), b = mid(tri.y, tri.z), c = mid(tri.z, tri.x);
      for (const glm::uvec3 face : {glm::uvec3(tri.x, a, c), glm::uvec3(tri.y, b, a), glm::uvec3(tri.z, c, b), glm::uvec3(a, b, c)}) next.push_back(face);
    }
    f = std::move(next);
  }
  const glm::dvec3 axis = glm::normalize(glm::dvec3(uniform(rng), uniform(rng), uniform(rng) + 2.0));
  const glm::dmat4 rotation = glm::rotate(glm::dmat4(1.0), M_PI * uniform(rng), axis);
  Mesh mesh;
  for (const glm::dvec3& p : v) {
    const double radius = 1.0 + jitter * uniform(rng);
    mesh.positions.emplace_back(glm::vec3(rotation * glm::dvec4(glm::normalize(p) * radius, 1.0)));
  }
  mesh.triangles.assign(f.begin(), f.end());
  return mesh;
}

Scene makeClosed(SceneArgs& args) {
  const auto seed = std::uint64_t(args.getInt("seed", 1, 0, 1LL << 40));
  const int level = int(args.getInt("level", 3, 0, 6));
  Builder b("closed", lookAt({0.0, 0.0, 3.2}, {0.0, 0.0, 0.0}, 45.0, 0.1, 192, 192));
  b.mesh() = jitteredSphere(seed, level, 0.15);
  // Each vertex moves along its own ray from the centre, so each triangle keeps to the cone its
  // unjittered self spans and faces away from the centre (det[r0 u0, r1 u1, r2 u2] =
  // r0 r1 r2 det[u0, u1, u2] > 0): a closed solid for every seed and level.
  b.mesh().closedSolid = true;
  return b.finish();
}

}  // namespace rc::hard
