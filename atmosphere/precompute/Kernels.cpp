#include "precompute/Kernels.hpp"
#include "precompute/Model.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#if defined(__x86_64__)
#include <immintrin.h>
#endif

// Compiled twice (AVX2 and the baseline), chosen at load time by the CPU.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define UMBRA_KERNEL __attribute__((target_clones("avx2", "default")))
#else
#define UMBRA_KERNEL
#endif

namespace umbra::atmosphere::stages {

/// The sun's (mu_s, nu) at a view-ray sample for n texels of a row, as cells (sNuCorner):
/// mu_s = xr sx + yr muS0, nu = tx sx + ty muS0 (sx, muS0: the sun in the ray's frame).
UMBRA_KERNEL void sNuTexels(const ScatterGeometry& geometry, double xr, double yr, double tx, double ty,
                            const double* sx, const double* muS0, int n, int* x00, double* ws, double* wn) {
  const ScatterGeometry g = geometry;  // a local copy: the outputs cannot alias it
  for (int x = 0; x < n; ++x)
    sNuCorner(g, g.muSTexel(xr * sx[x] + yr * muS0[x]), g.nuTexel(tx * sx[x] + ty * muS0[x]), x00[x], ws[x], wn[x]);
}

/// out[0..width * channels) = the (r, mu) interpolation of a 4D table: the cell's four
/// rows of (mu_s, nu) texels blended with their weights, in one pass.
UMBRA_KERNEL void blendRows(const FloatTable3D& T, const RMuCell& a, double* out) {
  const std::size_t n = static_cast<std::size_t>(T.width) * T.channels;
  const float* r00 = T.at(0, a.iy, a.iz);
  const float* r01 = T.at(0, a.iy + 1, a.iz);
  const float* r10 = T.at(0, a.iy, std::min(a.iz + 1, T.depth - 1));
  const float* r11 = T.at(0, a.iy + 1, std::min(a.iz + 1, T.depth - 1));
  const double w00 = (1.0 - a.wz) * (1.0 - a.wy), w01 = (1.0 - a.wz) * a.wy, w10 = a.wz * (1.0 - a.wy),
               w11 = a.wz * a.wy;
  for (std::size_t i = 0; i < n; ++i) out[i] = w00 * r00[i] + w01 * r01[i] + w10 * r10[i] + w11 * r11[i];
}

/// The sun at a view-ray sample (radius r, frame xr, yr) for n texels of a row (the sun
/// sx, muS0 in the ray's frame): its visibility (sunVisibility) and the column coordinate
/// in [0, columns - 1] of its transmittance in a table of that many columns.
UMBRA_KERNEL void sunTexels(const ShellRadii& shell, double alpha, double r, double xr, double yr, const double* sx,
                            const double* muS0, int n, int columns, double* vis, double* fx) {
  const double b = shell.bottomRadiusM, t = shell.topRadiusM;
  const double rc = std::clamp(r, b, t), H = std::sqrt((t - b) * (t + b)), rho = safeSqrt((rc - b) * (rc + b));
  for (int x = 0; x < n; ++x) {
    const double muS = clampCosine(xr * sx[x] + yr * muS0[x]);
    vis[x] = sunVisibility(b, alpha, r, muS);
    fx[x] = transmittanceXMu(t, rc, rho, H, muS) * (columns - 1);
  }
}

/// p_j = A (1 + B c_j^2) / (1 + g^2 - 2 g c_j)^{3/2} for j < n: the density's inner loop.
/// With AVX-512, (.)^{-3/2} is y^3 with y the reciprocal square root from vrsqrt14pd (14
/// bits) refined by two Newton steps (56 bits: the same double to a few ulps), which avoids
/// the divider; elsewhere a plain loop (vectorised: this file is compiled without math errno).
UMBRA_KERNEL void lobeValuesPlain(double A, double B, double g, const double* c, double* p, int n) {
  const double g2 = 1.0 + g * g, twoG = 2.0 * g;
  for (int j = 0; j < n; ++j) {
    const double d = g2 - twoG * c[j];
    p[j] = A * (1.0 + B * c[j] * c[j]) / (d * std::sqrt(d));
  }
}
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
__attribute__((target("avx512f"))) static void lobeValuesAvx512(double A, double B, double g, const double* c, double* p,
                                                         int n) {
  const __m512d Av = _mm512_set1_pd(A), Bv = _mm512_set1_pd(B), g2 = _mm512_set1_pd(1.0 + g * g),
                twoG = _mm512_set1_pd(2.0 * g), one = _mm512_set1_pd(1.0), half = _mm512_set1_pd(0.5),
                threeHalves = _mm512_set1_pd(1.5);
  int j = 0;
  for (; j + 8 <= n; j += 8) {
    const __m512d cc = _mm512_loadu_pd(c + j);
    const __m512d d = _mm512_fnmadd_pd(twoG, cc, g2);
    const __m512d hd = _mm512_mul_pd(half, d);
    __m512d y = _mm512_maskz_rsqrt14_pd(0xFF, d);
    y = _mm512_mul_pd(y, _mm512_fnmadd_pd(hd, _mm512_mul_pd(y, y), threeHalves));
    y = _mm512_mul_pd(y, _mm512_fnmadd_pd(hd, _mm512_mul_pd(y, y), threeHalves));
    const __m512d num = _mm512_mul_pd(Av, _mm512_fmadd_pd(Bv, _mm512_mul_pd(cc, cc), one));
    _mm512_storeu_pd(p + j, _mm512_mul_pd(num, _mm512_mul_pd(y, _mm512_mul_pd(y, y))));
  }
  lobeValuesPlain(A, B, g, c + j, p + j, n - j);
}
void lobeValues(double A, double B, double g, const double* c, double* p, int n) {
  static const bool avx512 = __builtin_cpu_supports("avx512f");
  if (avx512) lobeValuesAvx512(A, B, g, c, p, n);
  else lobeValuesPlain(A, B, g, c, p, n);
}
#else
void lobeValues(double A, double B, double g, const double* c, double* p, int n) { lobeValuesPlain(A, B, g, c, p, n); }
#endif

UMBRA_KERNEL void tablePositions(const double* c, int n, int* index, double* weight) {
  for (int j = 0; j < n; ++j) Model::tablePosition(c[j], index[j], weight[j]);
}

namespace {
typedef double Lanes __attribute__((vector_size(4 * sizeof(double))));

/// tableSums for C groups of four wavelengths from l0 (C fixed: the sums stay in registers,
/// and the table's rows are read once for all of them).
template <int C>
__attribute__((always_inline)) inline void tableSumsOf(const double* T, int stride, int l0, const int* index, const double* weight, int n,
                        const double* wdo, const double* L, double* norm, double* sum) {
  Lanes nAcc[C], sAcc[C], a0, a1, b0, b1, light;
  for (int c = 0; c < C; ++c) nAcc[c] = Lanes{0.0, 0.0, 0.0, 0.0}, sAcc[c] = nAcc[c];
  for (int j = 0; j < n; ++j) {
    const double* a = T + static_cast<std::size_t>(index[j]) * stride + l0;
    const double* b = T + static_cast<std::size_t>(index[n + j]) * stride + l0;
    const double* l = L + static_cast<std::size_t>(j) * stride + l0;
    const double wa = weight[j], wb = weight[n + j], w = wdo[j];
    for (int c = 0; c < C; ++c) {
      std::memcpy(&a0, a + 4 * c, sizeof a0), std::memcpy(&a1, a + stride + 4 * c, sizeof a1);
      std::memcpy(&b0, b + 4 * c, sizeof b0), std::memcpy(&b1, b + stride + 4 * c, sizeof b1);
      std::memcpy(&light, l + 4 * c, sizeof light);
      const Lanes p = (a0 + wa * (a1 - a0)) + (b0 + wb * (b1 - b0));
      nAcc[c] += p * w;
      sAcc[c] += p * light;
    }
  }
  for (int c = 0; c < C; ++c)
    for (int k = 0; k < 4; ++k) norm[l0 + 4 * c + k] = 0.5 * nAcc[c][k], sum[l0 + 4 * c + k] = 0.5 * sAcc[c][k];
}
}  // namespace

UMBRA_KERNEL void tableSums(const double* T, int stride, const int* index, const double* weight, int n,
                            const double* wdo, const double* L, double* norm, double* sum) {
  for (int l0 = 0; l0 < stride; l0 += 16) {
    switch (std::min(16, stride - l0) / 4) {
      case 4: tableSumsOf<4>(T, stride, l0, index, weight, n, wdo, L, norm, sum); break;
      case 3: tableSumsOf<3>(T, stride, l0, index, weight, n, wdo, L, norm, sum); break;
      case 2: tableSumsOf<2>(T, stride, l0, index, weight, n, wdo, L, norm, sum); break;
      default: tableSumsOf<1>(T, stride, l0, index, weight, n, wdo, L, norm, sum); break;
    }
  }
}

/// sum_j a_j b_j.
UMBRA_KERNEL double dot(const double* a, const double* b, int n) {
  double s = 0.0;
#pragma omp simd reduction(+ : s)
  for (int j = 0; j < n; ++j) s += a[j] * b[j];
  return s;
}

}  // namespace umbra::atmosphere::stages

namespace umbra::atmosphere::detail {
void lobeValuesBaseline(double A, double B, double g, const double* c, double* p, int n) {
  stages::lobeValuesPlain(A, B, g, c, p, n);
}
void lobeValuesDispatched(double A, double B, double g, const double* c, double* p, int n) {
  stages::lobeValues(A, B, g, c, p, n);
}
}  // namespace umbra::atmosphere::detail
