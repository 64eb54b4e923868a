#include "precompute/Kernels.hpp"
#include "precompute/Model.hpp"

#include <algorithm>
#include <cmath>
#if defined(__x86_64__)
#include <immintrin.h>
#endif

// Compiled three times (AVX-512, AVX2 and the baseline), chosen at load time by the CPU.
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
  // The common counts unrolled: 3 (RGB), 15 and 16 (15 or 47 wavelengths at once or in 3
  // batches), 5 and 8 (15 in batches of 5, 8 + 7); over a count known only at run time the
  // loop runs scalar, most of the multiple scattering's time with batches of 5.
  switch (nl) {
    case 1: gatherTexelsOf<1>(blend, nl, muS, x00, ws, wn, n, w, T, acc); break;
    case 3: gatherTexelsOf<3>(blend, nl, muS, x00, ws, wn, n, w, T, acc); break;
    case 4: gatherTexelsOf<4>(blend, nl, muS, x00, ws, wn, n, w, T, acc); break;
    case 5: gatherTexelsOf<5>(blend, nl, muS, x00, ws, wn, n, w, T, acc); break;
    case 8: gatherTexelsOf<8>(blend, nl, muS, x00, ws, wn, n, w, T, acc); break;
    case 15: gatherTexelsOf<15>(blend, nl, muS, x00, ws, wn, n, w, T, acc); break;
    case 16: gatherTexelsOf<16>(blend, nl, muS, x00, ws, wn, n, w, T, acc); break;
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

UMBRA_KERNEL void lobeValuesPlain(double A, double B, double g, const double* c, double* p, int n) {
  const double g2 = 1.0 + g * g, twoG = 2.0 * g;
  for (int j = 0; j < n; ++j) p[j] = lobeAt(A, B, g2, twoG, c[j]);
}
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
__attribute__((target("avx512f"))) static void lobeValuesAvx512(double A, double B, double g, const double* c, double* p,
                                                                int n) {
  const __m512d Av = _mm512_set1_pd(A), Bv = _mm512_set1_pd(B), g2 = _mm512_set1_pd(1.0 + g * g),
                twoG = _mm512_set1_pd(2.0 * g);
  int j = 0;
  for (; j + 8 <= n; j += 8) _mm512_storeu_pd(p + j, lobe8(Av, Bv, g2, twoG, _mm512_loadu_pd(c + j)));
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

UMBRA_KERNEL void cosineModesPlain(const double* f, const double* cosines, int n, int modes, double* out) {
  std::fill_n(out, modes, 0.0);
  for (int q = 0; q < n; ++q) {
    const double v = f[q];
    const double* c = cosines + static_cast<std::size_t>(q) * modes;
    for (int m = 0; m < modes; ++m) out[m] += v * c[m];
  }
}
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
namespace {
/// cosineModes for modes = 8 V, with AVX-512: the sums in registers, in two chains (one
/// chain through memory waits on every addition).
template <int V>
__attribute__((target("avx512f"))) void cosineModesAvx512(const double* f, const double* cosines, int n, double* out) {
  __m512d a[V], b[V];
  for (int v = 0; v < V; ++v) a[v] = _mm512_setzero_pd(), b[v] = _mm512_setzero_pd();
  int q = 0;
  for (; q + 2 <= n; q += 2) {
    const __m512d f0 = _mm512_set1_pd(f[q]), f1 = _mm512_set1_pd(f[q + 1]);
    const double* c0 = cosines + static_cast<std::size_t>(q) * 8 * V;
    for (int v = 0; v < V; ++v) {
      a[v] = _mm512_fmadd_pd(f0, _mm512_loadu_pd(c0 + 8 * v), a[v]);
      b[v] = _mm512_fmadd_pd(f1, _mm512_loadu_pd(c0 + 8 * V + 8 * v), b[v]);
    }
  }
  if (q < n) {
    const __m512d f0 = _mm512_set1_pd(f[q]);
    const double* c0 = cosines + static_cast<std::size_t>(q) * 8 * V;
    for (int v = 0; v < V; ++v) a[v] = _mm512_fmadd_pd(f0, _mm512_loadu_pd(c0 + 8 * v), a[v]);
  }
  for (int v = 0; v < V; ++v) _mm512_storeu_pd(out + 8 * v, _mm512_add_pd(a[v], b[v]));
}
}  // namespace
void cosineModes(const double* f, const double* cosines, int n, int modes, double* out) {
  static const bool avx512 = __builtin_cpu_supports("avx512f");
  if (avx512) switch (modes) {  // the density's numbers of azimuths: multiples of 8
      case 8: return cosineModesAvx512<1>(f, cosines, n, out);
      case 16: return cosineModesAvx512<2>(f, cosines, n, out);
      case 24: return cosineModesAvx512<3>(f, cosines, n, out);
      case 32: return cosineModesAvx512<4>(f, cosines, n, out);
      case 40: return cosineModesAvx512<5>(f, cosines, n, out);
      case 48: return cosineModesAvx512<6>(f, cosines, n, out);
      case 56: return cosineModesAvx512<7>(f, cosines, n, out);
      case 64: return cosineModesAvx512<8>(f, cosines, n, out);
      default: break;
    }
  cosineModesPlain(f, cosines, n, modes, out);
}
#else
void cosineModes(const double* f, const double* cosines, int n, int modes, double* out) {
  cosineModesPlain(f, cosines, n, modes, out);
}
#endif

AzimuthModes::AzimuthModes(int n) : nPh(n), Q(8 * n), qCos(Q), qModes(static_cast<std::size_t>(Q) * n), phiModes(static_cast<std::size_t>(n) * n) {
  for (int q = 0; q < Q; ++q) {
    const double d = (q + 0.5) * kPi / Q;
    qCos[q] = std::cos(d);
    for (int m = 0; m < nPh; ++m) qModes[static_cast<std::size_t>(q) * nPh + m] = 2.0 * kPi / Q * std::cos(m * d);
  }
  for (int i = 0; i < nPh; ++i)
    for (int m = 0; m < nPh; ++m)
      phiModes[static_cast<std::size_t>(i) * nPh + m] = (m == 0 ? 1.0 : 2.0) / nPh * std::cos(m * (i + 0.5) * kPi / nPh);
}

UMBRA_KERNEL void modeProducts(const double* alpha, const int* rows, int count, const double* gamma,
                               std::size_t gammaStride, int rings, int modes, double* out) {
  for (int u = 0; u < count; ++u) {
    double* o = out + static_cast<std::size_t>(u) * modes;
    const double* a = alpha + static_cast<std::size_t>(rows[u]) * rings * modes;
    const double* gu = gamma + u * gammaStride;
    std::fill_n(o, modes, 0.0);
    for (int lt = 0; lt < rings; ++lt) {
      const double* ar = a + static_cast<std::size_t>(lt) * modes;
      const double* gr = gu + static_cast<std::size_t>(lt) * modes;
      for (int m = 0; m < modes; ++m) o[m] += ar[m] * gr[m];
    }
  }
}

UMBRA_KERNEL void tablePositions(const double* c, int n, int* index, double* weight) {
  for (int j = 0; j < n; ++j) Model::tablePosition(c[j], index[j], weight[j]);
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
