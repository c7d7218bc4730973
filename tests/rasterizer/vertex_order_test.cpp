// jumpsThroughVertices (rasterizer/vertex_order.h): which triangle orders make set-up
// prefetch vertices.
#include "rasterizer/vertex_order.h"

#include <gtest/gtest.h>

#include <vector>

namespace rc {
namespace {

// A strip: triangle t uses vertices t, t + 1, t + 2.
std::vector<glm::uvec3> strip(std::uint32_t count, std::uint32_t first = 0) {
  std::vector<glm::uvec3> tris;
  for (std::uint32_t t = 0; t < count; ++t) tris.push_back({first + t, first + t + 1, first + t + 2});
  return tris;
}

TEST(VertexOrder, AStripOrAGridDoesNotJump) {
  const std::vector<glm::uvec3> tris = strip(8192);
  EXPECT_FALSE(jumpsThroughVertices(tris.data(), tris.size()));
  // Rows of a grid 1000 vertices wide, two triangles a quad: the row ends step by 1 vertex.
  std::vector<glm::uvec3> grid;
  for (std::uint32_t row = 0; row < 8; ++row) {
    for (std::uint32_t i = 0; i < 999; ++i) {
      const std::uint32_t v = row * 1000 + i;
      grid.push_back({v, v + 1, v + 1000});
      grid.push_back({v + 1, v + 1001, v + 1000});
    }
  }
  EXPECT_FALSE(jumpsThroughVertices(grid.data(), grid.size()));
}

TEST(VertexOrder, AScanOrderJumps) {
  // Consecutive triangles 1,557 vertices apart (the Stanford bunny's median), wrapping.
  std::vector<glm::uvec3> tris;
  for (std::uint32_t t = 0; t < 8192; ++t) {
    const std::uint32_t v = (t * 1557u) % 35000u;
    tris.push_back({v, v + 1, v + 2});
  }
  EXPECT_TRUE(jumpsThroughVertices(tris.data(), tris.size()));
}

TEST(VertexOrder, AJumpIsMoreThanKNearVerticesEitherWay) {
  // Every pair of consecutive triangles differs by exactly d in its first index.
  const auto steps = [](std::int64_t d) {
    std::vector<glm::uvec3> tris;
    std::int64_t v = 1 << 20;
    for (int t = 0; t < 64; ++t, v += d) tris.push_back({std::uint32_t(v), 0u, 0u});
    return tris;
  };
  const std::int64_t near = kNearVertices;
  for (std::int64_t d : {near, -near, std::int64_t(0)}) {
    const std::vector<glm::uvec3> tris = steps(d);
    EXPECT_FALSE(jumpsThroughVertices(tris.data(), tris.size())) << d;
  }
  for (std::int64_t d : {near + 1, -near - 1}) {
    const std::vector<glm::uvec3> tris = steps(d);
    EXPECT_TRUE(jumpsThroughVertices(tris.data(), tris.size())) << d;
  }
}

TEST(VertexOrder, AQuarterOfTheSampledPairsJumpingIsEnough) {
  // A strip whose sampled pairs jump in 3 (of 16), then 4: with count 1601, the samples are
  // the pairs (t, t + 1) at t = 100 s.
  for (int jumping : {3, 4}) {
    std::vector<glm::uvec3> tris = strip(1601);
    for (int s = 0; s < jumping; ++s) tris[std::size_t(100 * s + 1)].x += 1000;
    EXPECT_EQ(jumpsThroughVertices(tris.data(), tris.size()), jumping >= 4) << jumping;
  }
}

TEST(VertexOrder, FewerThanTwoTrianglesNeverJump) {
  const std::vector<glm::uvec3> one = {{5000u, 1u, 2u}};
  EXPECT_FALSE(jumpsThroughVertices(one.data(), one.size()));
  EXPECT_FALSE(jumpsThroughVertices(one.data(), 0));
}

}  // namespace
}  // namespace rc
