// The transform (transform.h): a scalar loop for the x86-64 baseline and an AVX2 one, with the
// same bits.
#include "rasterizer/transform.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>

namespace rc {

// Non-temporal stores: transform.h says why.
void transformScalar(const glm::vec3* positions, std::size_t begin, std::size_t end, const glm::dmat4& m,
                     const ClipVolume<double>& volume, const Camera& camera, glm::dvec4* clip, glm::dvec2* raster,
                     std::uint8_t* outcode, VertexFacts& factsOut) {
  VertexFacts facts = factsOut;  // in registers: the outcode stores may alias factsOut
  for (std::size_t i = begin; i < end; ++i) {
    const glm::dvec3 p(positions[i]);
    const glm::dvec4 c = m * glm::dvec4(p, 1.0);
    double* to = reinterpret_cast<double*>(clip + i);
    _mm_stream_pd(to, _mm_set_pd(c.y, c.x));
    _mm_stream_pd(to + 2, _mm_set_pd(c.w, c.z));
    outcode[i] = std::uint8_t(volume.outcode(c));
    facts.outcodes |= outcode[i];
    glm::dvec2 r(0.0);
    if (outcode[i] == 0) r = rasterOf(camera, c);  // what emit() would compute
    _mm_stream_pd(reinterpret_cast<double*>(raster + i), _mm_set_pd(r.y, r.x));
    facts.largest = std::max({facts.largest, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    facts.nearestW = std::min(facts.nearestW, c.w);
  }
  factsOut = facts;
}

// The same operations as transformScalar's, lane by lane (transform.h).
__attribute__((target("avx2"))) void transformAvx2(const glm::vec3* positions, std::size_t begin, std::size_t end,
                                                   const glm::dmat4& m, const ClipVolume<double>& volume,
                                                   const Camera& camera, glm::dvec4* clip, glm::dvec2* raster,
                                                   std::uint8_t* outcode, VertexFacts& facts) {
  const double width = camera.width(), height = camera.height();
  const __m256d m0 = _mm256_loadu_pd(&m[0][0]), m1 = _mm256_loadu_pd(&m[1][0]);
  const __m256d m2 = _mm256_loadu_pd(&m[2][0]), m3 = _mm256_loadu_pd(&m[3][0]);
  const __m256d guard = _mm256_set1_pd(volume.guard);
  const __m256d negateXY = _mm256_set_pd(0.0, -0.0, 0.0, -0.0);  // lanes -x, +x, -y, +y
  const __m128d negateY = _mm_set_pd(-0.0, 0.0), one = _mm_set1_pd(1.0), half = _mm_set1_pd(0.5);
  const __m128d size = _mm_set_pd(height, width);
  const bool farPlane = !std::isinf(volume.zFar);
  double largest = facts.largest, nearestW = facts.nearestW;
  unsigned outcodes = facts.outcodes;
  for (std::size_t i = begin; i < end; ++i) {
    const double px = positions[i].x, py = positions[i].y, pz = positions[i].z;
    const __m256d c = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(m0, _mm256_set1_pd(px)), _mm256_mul_pd(m1, _mm256_set1_pd(py))),
                                    _mm256_add_pd(_mm256_mul_pd(m2, _mm256_set1_pd(pz)), m3));
    double* to = reinterpret_cast<double*>(clip + i);  // 16-byte aligned: two streams, as the scalar loop
    _mm_stream_pd(to, _mm256_castpd256_pd128(c));
    _mm_stream_pd(to + 2, _mm256_extractf128_pd(c, 1));
    const __m256d w4 = _mm256_permute4x64_pd(c, 0xFF);
    const double w = _mm256_cvtsd_f64(w4);
    // ClipVolume::outcode: planes 2 to 5 are guard w -+ x and guard w -+ y, outside unless >= 0.
    const __m256d d = _mm256_add_pd(_mm256_mul_pd(guard, w4), _mm256_xor_pd(_mm256_permute4x64_pd(c, 0x50), negateXY));
    unsigned code = unsigned(_mm256_movemask_pd(_mm256_cmp_pd(d, _mm256_setzero_pd(), _CMP_NGE_UQ))) << 2;
    if (!(w - volume.zNear >= 0.0)) code |= 1u;
    if (farPlane && !(volume.zFar - w >= 0.0)) code |= 2u;
    outcode[i] = std::uint8_t(code);
    outcodes |= code;
    __m128d r = _mm_setzero_pd();
    if (code == 0) {
      const __m128d ndc = _mm_div_pd(_mm256_castpd256_pd128(c), _mm256_castpd256_pd128(w4));
      r = _mm_mul_pd(_mm_mul_pd(_mm_add_pd(_mm_xor_pd(ndc, negateY), one), half), size);
    }
    _mm_stream_pd(reinterpret_cast<double*>(raster + i), r);
    largest = std::max({largest, std::fabs(px), std::fabs(py), std::fabs(pz)});
    nearestW = std::min(nearestW, w);
  }
  facts.largest = largest;
  facts.nearestW = nearestW;
  facts.outcodes = outcodes;
}

}  // namespace rc
