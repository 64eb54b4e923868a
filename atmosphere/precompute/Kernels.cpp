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
#define UMBRA_KERNEL __attribute__((target_clones("avx512f", "avx2", "default")))
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

namespace {
template <int NL>
__attribute__((always_inline)) inline void gatherTexelsOf(const double* blend, int nl, int muS, const int* x00,
                                                          const double* ws, const double* wn, int n, double w,
                                                          const double* T, double* acc) {
  const int L = NL > 0 ? NL : nl;
  const std::size_t up = static_cast<std::size_t>(muS) * L;
  for (int x = 0; x < n; ++x) {
    const double* p00 = blend + static_cast<std::size_t>(x00[x]) * L;
    const double* p01 = p00 + L;
    const double* p10 = p00 + up;
    const double* p11 = p10 + L;
    const double s = ws[x], t = wn[x];
    const double w00 = w * (1 - t) * (1 - s), w01 = w * (1 - t) * s, w10 = w * t * (1 - s), w11 = w * t * s;
    double* a = acc + static_cast<std::size_t>(x) * L;
    for (int l = 0; l < L; ++l) a[l] += T[l] * (w00 * p00[l] + w01 * p01[l] + w10 * p10[l] + w11 * p11[l]);
  }
}
}  // namespace

UMBRA_KERNEL void gatherTexels(const double* blend, int nl, int muS, const int* x00, const double* ws,
                               const double* wn, int n, double w, const double* T, double* acc) {
  switch (nl) {  // the common counts unrolled
    case 1: gatherTexelsOf<1>(blend, nl, muS, x00, ws, wn, n, w, T, acc); break;
    case 3: gatherTexelsOf<3>(blend, nl, muS, x00, ws, wn, n, w, T, acc); break;
    case 4: gatherTexelsOf<4>(blend, nl, muS, x00, ws, wn, n, w, T, acc); break;
    default: gatherTexelsOf<0>(blend, nl, muS, x00, ws, wn, n, w, T, acc); break;
  }
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

// The density's closed-form lobes, p(c) = A (1 + B c^2) / (1 + g^2 - 2 g c)^{3/2}. With
// AVX-512, (.)^{-3/2} is y^3 with y the reciprocal square root from vrsqrt14pd (14 bits)
// refined by two Newton steps (56 bits: the same double to a few ulps), which avoids the
// divider; elsewhere a plain loop (vectorised: this file is compiled without math errno).
namespace {
/// A (1 + B c^2) / d^{3/2}, d = g2 - twoG c (g2 = 1 + g^2, twoG = 2 g).
inline double lobeAt(double A, double B, double g2, double twoG, double c) {
  const double d = g2 - twoG * c;
  return A * (1.0 + B * c * c) / (d * std::sqrt(d));
}
}  // namespace

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
namespace {
/// lobeAt for eight cosines, with vrsqrt14pd and two Newton steps.
__attribute__((target("avx512f"), always_inline)) inline __m512d lobe8(__m512d Av, __m512d Bv, __m512d g2,
                                                                       __m512d twoG, __m512d c) {
  const __m512d one = _mm512_set1_pd(1.0), half = _mm512_set1_pd(0.5), threeHalves = _mm512_set1_pd(1.5);
  const __m512d d = _mm512_fnmadd_pd(twoG, c, g2);
  const __m512d hd = _mm512_mul_pd(half, d);
  __m512d y = _mm512_maskz_rsqrt14_pd(0xFF, d);
  y = _mm512_mul_pd(y, _mm512_fnmadd_pd(hd, _mm512_mul_pd(y, y), threeHalves));
  y = _mm512_mul_pd(y, _mm512_fnmadd_pd(hd, _mm512_mul_pd(y, y), threeHalves));
  const __m512d num = _mm512_mul_pd(Av, _mm512_fmadd_pd(Bv, _mm512_mul_pd(c, c), one));
  return _mm512_mul_pd(num, _mm512_mul_pd(y, _mm512_mul_pd(y, y)));
}
}  // namespace
#endif

namespace {
/// sum_j a_j b_j in four chains (inline: the kernels below call it per wavelength).
inline double dotInline(const double* a, const double* b, int n) {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  int j = 0;
  for (; j + 4 <= n; j += 4) s0 += a[j] * b[j], s1 += a[j + 1] * b[j + 1], s2 += a[j + 2] * b[j + 2], s3 += a[j + 3] * b[j + 3];
  for (; j < n; ++j) s0 += a[j] * b[j];
  return (s0 + s1) + (s2 + s3);
}
}  // namespace

UMBRA_KERNEL void lobePairSumsPlain(double A, double B, double g, const double* wx, const double* wy,
                                    const double* wz, double vx, double vy, double vz, int n, const double* wdo,
                                    const double* L, const int* rows, int users, double* pair, double* out) {
  const double g2 = 1.0 + g * g, twoG = 2.0 * g;
  for (int j = 0; j < n; ++j) {
    const double base = wx[j] * vx + wz[j] * vz, side = wy[j] * vy;
    pair[j] = 0.5 * (lobeAt(A, B, g2, twoG, base + side) + lobeAt(A, B, g2, twoG, base - side));
  }
  out[0] = dotInline(pair, wdo, n);
  for (int u = 0; u < users; ++u) out[1 + u] = dotInline(pair, L + static_cast<std::size_t>(rows[u]) * n, n);
}
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
namespace {
/// sum_j a_j b_j, eight lanes at a time.
__attribute__((target("avx512f"))) double dot8(const double* a, const double* b, int n) {
  __m512d s0 = _mm512_setzero_pd(), s1 = _mm512_setzero_pd();
  int j = 0;
  for (; j + 16 <= n; j += 16) {
    s0 = _mm512_fmadd_pd(_mm512_loadu_pd(a + j), _mm512_loadu_pd(b + j), s0);
    s1 = _mm512_fmadd_pd(_mm512_loadu_pd(a + j + 8), _mm512_loadu_pd(b + j + 8), s1);
  }
  for (; j + 8 <= n; j += 8) s0 = _mm512_fmadd_pd(_mm512_loadu_pd(a + j), _mm512_loadu_pd(b + j), s0);
  alignas(64) double lanes[8];
  _mm512_store_pd(lanes, _mm512_add_pd(s0, s1));
  double s = ((lanes[0] + lanes[1]) + (lanes[2] + lanes[3])) + ((lanes[4] + lanes[5]) + (lanes[6] + lanes[7]));
  for (; j < n; ++j) s += a[j] * b[j];
  return s;
}
}  // namespace
__attribute__((target("avx512f"))) static void lobePairSumsAvx512(double A, double B, double g, const double* wx,
                                                                  const double* wy, const double* wz, double vx,
                                                                  double vy, double vz, int n, const double* wdo,
                                                                  const double* L, const int* rows, int users,
                                                                  double* pair, double* out) {
  const __m512d Av = _mm512_set1_pd(A), Bv = _mm512_set1_pd(B), g2 = _mm512_set1_pd(1.0 + g * g),
                twoG = _mm512_set1_pd(2.0 * g), vxv = _mm512_set1_pd(vx), vyv = _mm512_set1_pd(vy),
                vzv = _mm512_set1_pd(vz), half = _mm512_set1_pd(0.5);
  int j = 0;
  for (; j + 8 <= n; j += 8) {
    const __m512d base = _mm512_fmadd_pd(_mm512_loadu_pd(wx + j), vxv, _mm512_mul_pd(_mm512_loadu_pd(wz + j), vzv));
    const __m512d side = _mm512_mul_pd(_mm512_loadu_pd(wy + j), vyv);
    const __m512d p1 = lobe8(Av, Bv, g2, twoG, _mm512_add_pd(base, side));
    const __m512d p2 = lobe8(Av, Bv, g2, twoG, _mm512_sub_pd(base, side));
    _mm512_storeu_pd(pair + j, _mm512_mul_pd(half, _mm512_add_pd(p1, p2)));
  }
  if (j < n)  // the last n % 8 directions' pairs (its sums are overwritten below)
    lobePairSumsPlain(A, B, g, wx + j, wy + j, wz + j, vx, vy, vz, n - j, wdo + j, L, rows, 0, pair + j, out);
  out[0] = dot8(pair, wdo, n);
  for (int u = 0; u < users; ++u) out[1 + u] = dot8(pair, L + static_cast<std::size_t>(rows[u]) * n, n);
}
void lobePairSums(double A, double B, double g, const double* wx, const double* wy, const double* wz, double vx,
                  double vy, double vz, int n, const double* wdo, const double* L, const int* rows, int users,
                  double* pair, double* out) {
  static const bool avx512 = __builtin_cpu_supports("avx512f");
  if (avx512) lobePairSumsAvx512(A, B, g, wx, wy, wz, vx, vy, vz, n, wdo, L, rows, users, pair, out);
  else lobePairSumsPlain(A, B, g, wx, wy, wz, vx, vy, vz, n, wdo, L, rows, users, pair, out);
}
#else
void lobePairSums(double A, double B, double g, const double* wx, const double* wy, const double* wz, double vx,
                  double vy, double vz, int n, const double* wdo, const double* L, const int* rows, int users,
                  double* pair, double* out) {
  lobePairSumsPlain(A, B, g, wx, wy, wz, vx, vy, vz, n, wdo, L, rows, users, pair, out);
}
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


}  // namespace umbra::atmosphere::stages

namespace umbra::atmosphere::detail {
void lobePairSumsBaseline(double A, double B, double g, const double* wx, const double* wy, const double* wz,
                          double vx, double vy, double vz, int n, const double* wdo, const double* L, const int* rows,
                          int users, double* pair, double* out) {
  stages::lobePairSumsPlain(A, B, g, wx, wy, wz, vx, vy, vz, n, wdo, L, rows, users, pair, out);
}
void lobePairSumsDispatched(double A, double B, double g, const double* wx, const double* wy, const double* wz,
                            double vx, double vy, double vz, int n, const double* wdo, const double* L,
                            const int* rows, int users, double* pair, double* out) {
  stages::lobePairSums(A, B, g, wx, wy, wz, vx, vy, vz, n, wdo, L, rows, users, pair, out);
}
}  // namespace umbra::atmosphere::detail
