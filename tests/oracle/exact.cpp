// The exact oracle: rational clipping, projection, snapping and the top-left rule.
#include "tests/oracle/exact.h"

#include <algorithm>
#include <cmath>

namespace rc::oracle {
namespace {

Q exact(double v) { return Q(v); }  // every finite double is a dyadic rational

std::int64_t floorDiv(std::int64_t a, std::int64_t b) {  // b > 0
  const std::int64_t q = a / b;
  return (a % b != 0 && a < 0) ? q - 1 : q;
}
std::int64_t ceilDiv(std::int64_t a, std::int64_t b) { return -floorDiv(-a, b); }

// floor of a rational.
mpz_class floorQ(const Q& q) {
  mpz_class r;
  mpz_fdiv_q(r.get_mpz_t(), q.get_num_mpz_t(), q.get_den_mpz_t());
  return r;
}

// Round to nearest, ties to even; flags values within 2^-20 of a tie.
std::int64_t roundEven(const Q& q, int& ambiguous) {
  const mpz_class f = floorQ(q);
  const Q frac = q - Q(f);
  const Q half(1, 2);
  if (abs(frac - half) < Q(1, 1 << 20)) ++ambiguous;
  mpz_class r = f;
  if (frac > half || (frac == half && mpz_odd_p(f.get_mpz_t()))) r += 1;
  return r.get_si();
}

struct Vertex {
  Q x, y, w;
  std::array<Q, 3> bary;
};

// Signed distance to clip plane i (>= 0 inside), the rasterizer's documented volume.
Q planeDistance(const Vertex& v, int plane, const Q& zNear, const Q& zFar, bool finiteFar, const Q& guard) {
  switch (plane) {
    case 0: return v.w - zNear;
    case 1: return finiteFar ? zFar - v.w : Q(1);
    case 2: return guard * v.w - v.x;
    case 3: return guard * v.w + v.x;
    case 4: return guard * v.w - v.y;
    default: return guard * v.w + v.y;
  }
}

// The top-left rule on integer (snapped) coordinates, y down: a centre on an edge is in when
// the interior lies to its right (left edge) or below a horizontal edge (top edge).
bool covers(const std::int64_t X[3], const std::int64_t Y[3], std::int64_t px, std::int64_t py) {
  for (int i = 0; i < 3; ++i) {
    const int a = (i + 1) % 3, b = (i + 2) % 3;
    // Interior normal of edge a->b for a positively oriented triangle.
    const std::int64_t nx = -(Y[b] - Y[a]), ny = X[b] - X[a];
    const std::int64_t e = nx * (px - X[a]) + ny * (py - Y[a]);
    if (e < 0) return false;
    if (e == 0 && !(nx > 0 || (nx == 0 && ny > 0))) return false;
  }
  return true;
}

}  // namespace

std::vector<std::uint32_t> unsnappedCoverage(const std::array<glm::dvec2, 3>& raster, int width, int height,
                                             bool cullBackFaces) {
  Q X[3], Y[3];
  for (int i = 0; i < 3; ++i) X[i] = exact(raster[i].x), Y[i] = exact(raster[i].y);
  const Q area = (X[1] - X[0]) * (Y[2] - Y[0]) - (Y[1] - Y[0]) * (X[2] - X[0]);
  std::vector<std::uint32_t> pixels;
  if (area == 0 || (cullBackFaces && area > 0)) return pixels;
  const int s = sgn(area);
  const auto [minX, maxX] = std::minmax({raster[0].x, raster[1].x, raster[2].x});
  const auto [minY, maxY] = std::minmax({raster[0].y, raster[1].y, raster[2].y});
  const int x0 = std::max(0, int(std::floor(minX)) - 1), x1 = std::min(width - 1, int(std::ceil(maxX)) + 1);
  const int y0 = std::max(0, int(std::floor(minY)) - 1), y1 = std::min(height - 1, int(std::ceil(maxY)) + 1);
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const Q cx(2 * x + 1, 2), cy(2 * y + 1, 2);
      bool inside = true;
      for (int i = 0; i < 3 && inside; ++i) {
        const int a = (i + 1) % 3, b = (i + 2) % 3;
        // Interior normal of edge a->b, the triangle made positively oriented.
        const Q nx = -(Y[b] - Y[a]) * s, ny = (X[b] - X[a]) * s;
        const Q e = nx * (cx - X[a]) + ny * (cy - Y[a]);
        if (e < 0 || (e == 0 && !(nx > 0 || (nx == 0 && ny > 0)))) inside = false;
      }
      if (inside) pixels.push_back(std::uint32_t(y) * std::uint32_t(width) + std::uint32_t(x));
    }
  }
  return pixels;
}

glm::dvec2 rasterPosition(const Camera& camera, const glm::vec3& p) {
  const glm::dvec4 c = camera.clipFromWorld() * glm::dvec4(glm::dvec3(p), 1.0);
  return {camera.rasterXFromNdc(c.x / c.w), camera.rasterYFromNdc(c.y / c.w)};
}

Oracle::Oracle(const Scene& scene, int subpixelBits) : scene_(scene), bits_(subpixelBits) {
  const glm::dmat4 m = scene.camera.clipFromWorld();
  clip_.reserve(scene.mesh.vertexCount());
  for (const glm::vec3& p : scene.mesh.positions) {
    const Q px(double(p.x)), py(double(p.y)), pz(double(p.z));
    Clip c;
    c.x = exact(m[0][0]) * px + exact(m[1][0]) * py + exact(m[2][0]) * pz + exact(m[3][0]);
    c.y = exact(m[0][1]) * px + exact(m[1][1]) * py + exact(m[2][1]) * pz + exact(m[3][1]);
    c.w = exact(m[0][3]) * px + exact(m[1][3]) * py + exact(m[2][3]) * pz + exact(m[3][3]);
    clip_.push_back(c);
  }
  // The guard band as the rasterizer defines it (a double): 2 * 2^(28 - bits) / max(W, H).
  const int side = std::max(scene.camera.width(), scene.camera.height());
  guard_ = exact(2.0 * std::ldexp(1.0, 28 - subpixelBits) / side);
  zNear_ = exact(scene.camera.zNear());
  finiteFar_ = std::isfinite(scene.camera.zFar());
  if (finiteFar_) zFar_ = exact(scene.camera.zFar());
}

CoverageResult Oracle::coverage(std::size_t t) const {
  CoverageResult result;
  const glm::uvec3 tri = scene_.mesh.triangles[t];
  std::vector<Vertex> poly;
  for (int i = 0; i < 3; ++i) {
    const Clip& c = clip_[tri[i]];
    std::array<Q, 3> b{Q(0), Q(0), Q(0)};
    b[i] = 1;
    poly.push_back({c.x, c.y, c.w, b});
  }
  // Clip only against planes some vertex is outside of, in plane order (Sutherland-Hodgman).
  unsigned outside = 0;
  for (const Vertex& v : poly) {
    for (int plane = 0; plane < 6; ++plane) {
      if (planeDistance(v, plane, zNear_, zFar_, finiteFar_, guard_) < 0) outside |= 1u << plane;
    }
  }
  unsigned all = 0x3F;
  for (const Vertex& v : poly) {
    unsigned code = 0;
    for (int plane = 0; plane < 6; ++plane) {
      if (planeDistance(v, plane, zNear_, zFar_, finiteFar_, guard_) < 0) code |= 1u << plane;
    }
    all &= code;
  }
  if (all) return result;
  for (int plane = 0; plane < 6 && !poly.empty(); ++plane) {
    if (!(outside & (1u << plane))) continue;
    std::vector<Vertex> next;
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Vertex& cur = poly[i];
      const Vertex& nxt = poly[(i + 1) % poly.size()];
      const Q dc = planeDistance(cur, plane, zNear_, zFar_, finiteFar_, guard_);
      const Q dn = planeDistance(nxt, plane, zNear_, zFar_, finiteFar_, guard_);
      if (dc >= 0) next.push_back(cur);
      if ((dc >= 0) != (dn >= 0)) {
        const Q s = dc / (dc - dn);
        Vertex v{cur.x + s * (nxt.x - cur.x), cur.y + s * (nxt.y - cur.y), cur.w + s * (nxt.w - cur.w), {}};
        for (int k = 0; k < 3; ++k) v.bary[k] = cur.bary[k] + s * (nxt.bary[k] - cur.bary[k]);
        next.push_back(v);
      }
    }
    poly = std::move(next);
  }
  if (poly.size() < 3) return result;
  // Project and snap: raster x = (x / w + 1) W / 2, y = (1 - y / w) H / 2, times 2^bits.
  const int width = scene_.camera.width(), height = scene_.camera.height();
  const Q scale(mpz_class(1) << bits_);
  std::vector<std::int64_t> X, Y;
  for (const Vertex& v : poly) {
    X.push_back(roundEven((v.x / v.w + 1) * Q(width, 2) * scale, result.ambiguousSnaps));
    Y.push_back(roundEven((Q(1) - v.y / v.w) * Q(height, 2) * scale, result.ambiguousSnaps));
  }
  // Fan around vertex 0; the union of the sub-triangles' centres.
  std::vector<std::uint32_t> pixels;
  for (std::size_t k = 1; k + 1 < poly.size(); ++k) {
    std::int64_t x[3] = {X[0], X[k], X[k + 1]}, y[3] = {Y[0], Y[k], Y[k + 1]};
    const std::int64_t area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
    if (area == 0) continue;
    if (area < 0) std::swap(x[1], x[2]), std::swap(y[1], y[2]);
    const std::int64_t one = std::int64_t(1) << bits_, half = one / 2;
    const std::int64_t lo[2] = {std::min({x[0], x[1], x[2]}), std::min({y[0], y[1], y[2]})};
    const std::int64_t hi[2] = {std::max({x[0], x[1], x[2]}), std::max({y[0], y[1], y[2]})};
    // Pixel centres (2p + 1) half inside the box, clamped to the image.
    const std::int64_t x0 = std::max<std::int64_t>(0, ceilDiv(lo[0] - half, one));
    const std::int64_t y0 = std::max<std::int64_t>(0, ceilDiv(lo[1] - half, one));
    const std::int64_t x1 = std::min<std::int64_t>(width - 1, floorDiv(hi[0] - half, one));
    const std::int64_t y1 = std::min<std::int64_t>(height - 1, floorDiv(hi[1] - half, one));
    for (std::int64_t py = y0; py <= y1; ++py) {
      for (std::int64_t px = x0; px <= x1; ++px) {
        if (covers(x, y, (2 * px + 1) * half, (2 * py + 1) * half)) pixels.push_back(std::uint32_t(py * width + px));
      }
    }
  }
  std::sort(pixels.begin(), pixels.end());
  const auto end = std::unique(pixels.begin(), pixels.end());
  result.doubleCovered = int(pixels.end() - end);
  pixels.erase(end, pixels.end());
  result.pixels = std::move(pixels);
  return result;
}

std::array<std::int64_t, 2> Oracle::snapped(std::size_t v, int& ambiguous) const {
  const Clip& c = clip_[v];
  const Q scale(mpz_class(1) << bits_);
  return {roundEven((c.x / c.w + 1) * Q(scene_.camera.width(), 2) * scale, ambiguous),
          roundEven((Q(1) - c.y / c.w) * Q(scene_.camera.height(), 2) * scale, ambiguous)};
}

std::array<Q, 2> Oracle::raster(std::size_t v) const {
  const Clip& c = clip_[v];
  return {(c.x / c.w + 1) * Q(scene_.camera.width(), 2), (Q(1) - c.y / c.w) * Q(scene_.camera.height(), 2)};
}

std::array<double, 3> Oracle::projected(std::size_t t, int x, int y, bool& defined) const {
  const glm::uvec3 tri = scene_.mesh.triangles[t];
  // Pixel centre in NDC, exactly: the inverse of the raster mapping.
  const Q nx = Q(2 * x + 1, scene_.camera.width()) - 1;
  const Q ny = Q(1) - Q(2 * y + 1, scene_.camera.height());
  // b_i proportional to det[c_j; c_k; (nx, ny, 1)] over homogeneous (x, y, w) rows.
  Q d[3];
  for (int i = 0; i < 3; ++i) {
    const Clip& a = clip_[tri[(i + 1) % 3]];
    const Clip& b = clip_[tri[(i + 2) % 3]];
    d[i] = a.x * (b.y - ny * b.w) - a.y * (b.x - nx * b.w) + a.w * (b.x * ny - b.y * nx);
  }
  const Q sum = d[0] + d[1] + d[2];
  defined = sgn(sum) != 0;
  if (!defined) return {0, 0, 0};
  return {Q(d[0] / sum).get_d(), Q(d[1] / sum).get_d(), Q(d[2] / sum).get_d()};
}

std::array<double, 3> Oracle::alongRay(std::size_t t, int x, int y, bool& defined) const {
  const glm::uvec3 tri = scene_.mesh.triangles[t];
  const CameraRay ray = scene_.camera.rayThroughPixel(x, y);
  const Q o[3] = {exact(ray.origin.x), exact(ray.origin.y), exact(ray.origin.z)};
  const Q dir[3] = {exact(ray.direction.x), exact(ray.direction.y), exact(ray.direction.z)};
  std::array<std::array<Q, 3>, 3> v;
  for (int i = 0; i < 3; ++i) {
    const glm::vec3& p = scene_.mesh.positions[tri[i]];
    for (int k = 0; k < 3; ++k) v[i][k] = Q(double(p[k])) - o[k];
  }
  Q vol[3];
  for (int i = 0; i < 3; ++i) {
    const auto& a = v[(i + 1) % 3];
    const auto& b = v[(i + 2) % 3];
    // d . (a x b)
    vol[i] = dir[0] * (a[1] * b[2] - a[2] * b[1]) + dir[1] * (a[2] * b[0] - a[0] * b[2]) +
             dir[2] * (a[0] * b[1] - a[1] * b[0]);
  }
  const Q sum = vol[0] + vol[1] + vol[2];
  defined = sgn(sum) != 0;
  if (!defined) return {0, 0, 0};
  return {Q(vol[0] / sum).get_d(), Q(vol[1] / sum).get_d(), Q(vol[2] / sum).get_d()};
}

}  // namespace rc::oracle
