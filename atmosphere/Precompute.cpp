#include "Precompute.hpp"
#include "ParallelErrors.hpp"
#include "Quadrature.hpp"

#include "Refraction.hpp"
#include "SightLines.hpp"  // refractiveMedium
#include "TextureCoords.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <sstream>
#ifdef _OPENMP
#include <omp.h>
#endif
#if defined(__x86_64__)
#include <immintrin.h>
#endif

// Kernels compiled twice (AVX2 and the baseline), chosen at load time by the CPU.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define UMBRA_KERNEL __attribute__((target_clones("avx2", "default")))
#else
#define UMBRA_KERNEL
#endif

namespace umbra::atmosphere {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Bruneton's GetTextureCoordFromUnitRange, inline for the lookups' hot path.
inline double texCoord(double x, int n) { return (0.5 + x * (n - 1.0)) / n; }

inline double smoothstep(double e0, double e1, double x) {
  const double t = std::min(std::max((x - e0) / (e1 - e0), 0.0), 1.0);
  const double step = x < e0 ? 0.0 : 1.0;
  return e1 > e0 ? t * t * (3.0 - 2.0 * t) : step;
}

[[noreturn]] void throwNonFiniteLookup() {
  throw std::domain_error("a table lookup at a non-finite coordinate: the atmosphere's numbers (radii, scale "
                          "heights, densities) put its light out of the tables' reach");
}

/// Linear texel coordinate in [0, n - 1] from a texture coordinate (centres at (i + 0.5) / n).
inline void texelLerp(double u, int n, int lo, int hi, int& i, double& w) {
  if (std::isnan(u)) throwNonFiniteLookup();  // a NaN passes std::clamp and becomes an index
  double f = std::clamp(u * n - 0.5, static_cast<double>(lo), static_cast<double>(hi));
  if (hi <= lo) {
    i = lo, w = 0.0;
    return;
  }
  i = std::min(static_cast<int>(std::floor(f)), hi - 1);
  w = f - i;
}

}  // namespace

// ---- options -------------------------------------------------------------------------------

std::string PrecomputeOptions::validate() const {
  std::ostringstream e;
  if (transmittanceWidth < 2 || transmittanceHeight < 2) e << "transmittance size must be >= 2x2; ";
  if (scatteringR < 2 || scatteringMuS < 2 || scatteringNu < 2) e << "scattering R, MU_S, NU must be >= 2; ";
  if (scatteringMu < 4 || scatteringMu % 2 != 0) e << "scatteringMu must be even and >= 4; ";
  if (irradianceWidth < 2 || irradianceHeight < 2) e << "irradiance size must be >= 2x2; ";
  if (orders < 1) e << "orders must be >= 1; ";
  if (transmittanceSamples < 2 || transmittanceSamples % 2 != 0) e << "transmittanceSamples must be even and >= 2; ";
  if (singleScatteringSamples < 1 || multipleScatteringSamples < 1) e << "scattering samples must be >= 1; ";
  if (opticalDepthSubsamples < 2 || opticalDepthSubsamples % 2 != 0) e << "opticalDepthSubsamples must be even and >= 2; ";
  if (sphereSamples != 0 && sphereSamples < 2) e << "sphereSamples must be 0 (from the phase functions) or >= 2; ";
  if (irradianceSamples < 2 || irradianceSamples % 2 != 0) e << "irradianceSamples must be even and >= 2; ";
  if (!(muSMin >= -1.0 && muSMin < 1.0)) e << "muSMin must be in [-1, 1); ";
  if (!(sunAngularRadiusRad >= 0.0 && sunAngularRadiusRad < 0.5)) e << "sunAngularRadiusRad must be in [0, 0.5); ";
  if (!(refractionStepM > 0.0)) e << "refractionStepM must be > 0; ";
  if (wavelengthBatch < 0) e << "wavelengthBatch must be >= 0; ";
  return e.str();
}

std::size_t AtmosphereTables::bytes() const {
  std::size_t n = transmittance.values.size() + multipleScattering.values.size() +
                  directIrradiance.values.size() + irradiance.values.size();
  for (const Table3D& t : singleScattering) n += t.values.size();
  return n * sizeof(double);
}

// ---- the 4D parametrisation ---------------------------------------------------------------

namespace {

struct ScatterGeometry {
  double b, t, H, muSMin, A;
  int R, MU, MUS, NU;

  ScatterGeometry(const ShellRadii& s, const ScatteringTableSize& z, double muSMinIn)
      : b(s.bottomRadiusM), t(s.topRadiusM), H(std::sqrt((t - b) * (t + b))), muSMin(muSMinIn),
        R(z.r), MU(z.mu), MUS(z.muS), NU(z.nu) {
    const double D = distanceToTopBoundaryM(t, b, muSMin);
    A = (D - (t - b)) / (H - (t - b));
  }

  double uR(double r) const {
    const double rho = safeSqrt((r - b) * (r + b));
    return texCoord(std::clamp(rho / H, 0.0, 1.0), R);
  }
  double uMu(double r, double mu, bool ground) const {
    r = std::clamp(r, b, t);
    const double rho = safeSqrt((r - b) * (r + b));
    if (ground) {
      const double d = distanceToBottomBoundaryM(b, r, mu);
      const double dMin = r - b, dMax = rho;
      const double x = dMax <= dMin ? 0.0 : std::clamp((d - dMin) / (dMax - dMin), 0.0, 1.0);
      return 0.5 - 0.5 * texCoord(x, MU / 2);
    }
    const double d = distanceToTopBoundaryM(t, r, mu);
    const double dMin = t - r, dMax = rho + H;
    const double x = std::clamp((d - dMin) / (dMax - dMin), 0.0, 1.0);
    return 0.5 + 0.5 * texCoord(x, MU / 2);
  }
  double uMuS(double muS) const {
    // distance from the ground to the top along mu_s (inline: the hot path of the lookups;
    // branch-free so that loops over it vectorise)
    muS = clampCosine(muS);
    const double root = std::sqrt(b * b * muS * muS + H * H);
    const double q = muS > 0.0 ? b * muS + root : root - b * muS;
    const double qInverse = H * H / q;
    const double d = muS > 0.0 ? qInverse : q;
    const double a = (d - (t - b)) / (H - (t - b));
    return texCoord(std::max(1.0 - a / A, 0.0) / (1.0 + a), MUS);
  }
  static double uNu(double nu) { return 0.5 * (clampCosine(nu) + 1.0); }
  /// Continuous texel coordinates: mu_s in [0, MU_S - 1], nu in [0, NU - 1].
  double muSTexel(double muS) const { return std::min(std::max(uMuS(muS) * MUS - 0.5, 0.0), MUS - 1.0); }
  double nuTexel(double nu) const { return std::min(std::max(uNu(nu) * (NU - 1), 0.0), NU - 1.0); }

  double rFromU(double u) const {
    const double rho = H * std::clamp(unitRangeFromTextureCoord(u, R), 0.0, 1.0);
    return std::min(t, std::sqrt(rho * rho + b * b));
  }
  double muFromU(double r, double u, bool& ground) const {
    const double rho = safeSqrt((r - b) * (r + b));
    if (u < 0.5) {
      ground = true;
      const double dMin = r - b, dMax = rho;
      const double d = dMin + (dMax - dMin) * std::clamp(unitRangeFromTextureCoord(1.0 - 2.0 * u, MU / 2), 0.0, 1.0);
      return d == 0.0 ? -1.0 : clampCosine(-(rho * rho + d * d) / (2.0 * r * d));
    }
    ground = false;
    const double dMin = t - r, dMax = rho + H;
    const double d = dMin + (dMax - dMin) * std::clamp(unitRangeFromTextureCoord(2.0 * u - 1.0, MU / 2), 0.0, 1.0);
    return d == 0.0 ? 1.0 : clampCosine((H * H - rho * rho - d * d) / (2.0 * r * d));
  }
  double muSFromU(double u) const {
    const double x = std::clamp(unitRangeFromTextureCoord(u, MUS), 0.0, 1.0);
    const double dMin = t - b, dMax = H;
    const double a = (A - x * A) / (1.0 + x * A);
    const double d = dMin + std::min(a, A) * (dMax - dMin);
    return d == 0.0 ? 1.0 : clampCosine((H * H - d * d) / (2.0 * b * d));
  }

  ScatteringPoint texel(int x, int y, int z) const {
    ScatteringPoint p;
    const int k = x / MUS, i = x % MUS;
    p.r = rFromU((z + 0.5) / R);
    p.mu = muFromU(p.r, (y + 0.5) / MU, p.rayIntersectsGround);
    p.muS = muSFromU((i + 0.5) / MUS);
    const double nu = clampCosine(2.0 * k / (NU - 1) - 1.0);
    const double s = std::sqrt(std::max(0.0, (1.0 - p.mu * p.mu) * (1.0 - p.muS * p.muS)));
    p.nu = std::clamp(nu, p.mu * p.muS - s, p.mu * p.muS + s);
    return p;
  }
};

ScatterGeometry geometryOf(const AtmosphereTables& t) {
  const PrecomputeOptions& o = t.options;
  return ScatterGeometry(t.shell(), {o.scatteringR, o.scatteringMu, o.scatteringMuS, o.scatteringNu}, o.muSMin);
}

/// The (r, mu) part of a 4D lookup: two mu rows in two r layers.
struct RMuCell {
  int iz = 0, iy = 0;
  double wz = 0.0, wy = 0.0;
};
/// The (mu_s, nu) part: column indices x = nu * MU_S + mu_s.
struct SNuCell {
  int x00, x01, x10, x11;  // [nu][mu_s]
  double w00, w01, w10, w11;
};

inline RMuCell rMuCell(const ScatterGeometry& g, double r, double mu, bool ground) {
  RMuCell c;
  texelLerp(g.uR(r), g.R, 0, g.R - 1, c.iz, c.wz);
  const int half = g.MU / 2;
  if (ground) texelLerp(g.uMu(r, mu, true), g.MU, 0, half - 1, c.iy, c.wy);
  else texelLerp(g.uMu(r, mu, false), g.MU, half, g.MU - 1, c.iy, c.wy);
  return c;
}

/// The lower corner (x = nu * MU_S + mu_s) and the weights of the cell at continuous texel
/// coordinates (ScatterGeometry::muSTexel, nuTexel).
inline void sNuCorner(const ScatterGeometry& g, double fs, double fn, int& x00, double& ws, double& wn) {
  const int is = std::min(static_cast<int>(fs), g.MUS - 2);  // fs >= 0: truncation is floor
  const double nearest = std::round(fn);
  fn = std::abs(fn - nearest) < 1e-12 ? nearest : fn;  // on a slice: one slice to read
  const int in = std::min(static_cast<int>(fn), g.NU - 2);
  x00 = in * g.MUS + is, ws = fs - is, wn = fn - in;
}

inline SNuCell sNuCell(const ScatterGeometry& g, double muS, double nu) {
  double ws, wn;
  SNuCell c;
  sNuCorner(g, g.muSTexel(muS), g.nuTexel(nu), c.x00, ws, wn);
  c.x01 = c.x00 + 1, c.x10 = c.x00 + g.MUS, c.x11 = c.x10 + 1;
  c.w00 = (1 - wn) * (1 - ws), c.w01 = (1 - wn) * ws, c.w10 = wn * (1 - ws), c.w11 = wn * ws;
  return c;
}

/// The sun's (mu_s, nu) at a view-ray sample for n texels of a row, as cells (sNuCorner):
/// mu_s = xr sx + yr muS0, nu = tx sx + ty muS0 (sx, muS0: the sun in the ray's frame).
UMBRA_KERNEL void sNuTexels(const ScatterGeometry& geometry, double xr, double yr, double tx, double ty,
                            const double* sx, const double* muS0, int n, int* x00, double* ws, double* wn) {
  const ScatterGeometry g = geometry;  // a local copy: the outputs cannot alias it
  for (int x = 0; x < n; ++x)
    sNuCorner(g, g.muSTexel(xr * sx[x] + yr * muS0[x]), g.nuTexel(tx * sx[x] + ty * muS0[x]), x00[x], ws[x], wn[x]);
}

/// out[0..n) += scale * table(r, mu, mu_s, nu) for the channels l0 .. l0 + n (n < 0: all).
inline void accumulate4(const Table3D& T, const RMuCell& a, const SNuCell& s, double scale, double* out, int l0 = 0,
                        int n = -1) {
  const int nc = T.channels, nr = n < 0 ? nc : n;
  for (int dz = 0; dz < 2; ++dz) {
    const double wz = (dz ? a.wz : 1.0 - a.wz) * scale;
    if (wz == 0.0) continue;
    for (int dy = 0; dy < 2; ++dy) {
      const double wzy = wz * (dy ? a.wy : 1.0 - a.wy);
      if (wzy == 0.0) continue;
      const double* row = T.at(0, a.iy + dy, a.iz + dz) + l0;
      const double* p00 = row + static_cast<std::size_t>(s.x00) * nc;
      const double* p01 = row + static_cast<std::size_t>(s.x01) * nc;
      const double* p10 = row + static_cast<std::size_t>(s.x10) * nc;
      const double* p11 = row + static_cast<std::size_t>(s.x11) * nc;
      const double w00 = wzy * s.w00, w01 = wzy * s.w01, w10 = wzy * s.w10, w11 = wzy * s.w11;
      if (s.w10 == 0.0 && s.w11 == 0.0) {
        for (int l = 0; l < nr; ++l) out[l] += w00 * p00[l] + w01 * p01[l];
      } else {
        for (int l = 0; l < nr; ++l) out[l] += w00 * p00[l] + w01 * p01[l] + w10 * p10[l] + w11 * p11[l];
      }
    }
  }
}

/// out[0..width * channels) = the (r, mu) interpolation of a 4D table: the cell's four
/// rows of (mu_s, nu) texels blended with their weights, in one pass.
UMBRA_KERNEL void blendRows(const Table3D& T, const RMuCell& a, double* out) {
  const std::size_t n = static_cast<std::size_t>(T.width) * T.channels;
  const double* r00 = T.at(0, a.iy, a.iz);
  const double* r01 = T.at(0, a.iy + 1, a.iz);
  const double* r10 = T.at(0, a.iy, std::min(a.iz + 1, T.depth - 1));
  const double* r11 = T.at(0, a.iy + 1, std::min(a.iz + 1, T.depth - 1));
  const double w00 = (1.0 - a.wz) * (1.0 - a.wy), w01 = (1.0 - a.wz) * a.wy, w10 = a.wz * (1.0 - a.wy),
               w11 = a.wz * a.wy;
  for (std::size_t i = 0; i < n; ++i) out[i] = w00 * r00[i] + w01 * r01[i] + w10 * r10[i] + w11 * r11[i];
}

/// Bilinear lookup in a 2D table of unit-range coordinates (texel centres on the ends).
inline void bilinearUnit(const Table2D& T, double xu, double yu, double* out) {
  const double fx = std::clamp(xu, 0.0, 1.0) * (T.width - 1), fy = std::clamp(yu, 0.0, 1.0) * (T.height - 1);
  const int ix = std::min(static_cast<int>(fx), T.width - 2), iy = std::min(static_cast<int>(fy), T.height - 2);
  const double wx = fx - ix, wy = fy - iy;
  const double* p00 = T.at(ix, iy);
  const double* p01 = T.at(ix + 1, iy);
  const double* p10 = T.at(ix, iy + 1);
  const double* p11 = T.at(ix + 1, iy + 1);
  const double w00 = (1 - wx) * (1 - wy), w01 = wx * (1 - wy), w10 = (1 - wx) * wy, w11 = wx * wy;
  for (int l = 0; l < T.channels; ++l) out[l] = w00 * p00[l] + w01 * p01[l] + w10 * p10[l] + w11 * p11[l];
}

inline void lookupTransmittance(const Table2D& T, const ShellRadii& shell, double r, double mu, double* out) {
  const TransmittanceCoords c = transmittanceCoordsFromRMu(shell, r, mu);
  bilinearUnit(T, c.xMu, c.xR, out);
}

inline void lookupIrradiance(const Table2D& T, const ShellRadii& shell, double r, double muS, double* out) {
  bilinearUnit(T, 0.5 * (muS + 1.0), (r - shell.bottomRadiusM) / (shell.topRadiusM - shell.bottomRadiusM), out);
}

/// E_0 at (r, muS) from the transmittance table: T to the top times the cosine of the Sun's
/// visible disc (sunDiscCosine), per unit solar irradiance. Computed where needed rather
/// than read from the direct-irradiance table, whose mu_s cells cannot follow the disc's
/// setting (x19 at mu_s = 0 with 64 cells).
inline void directIrradianceAt(const Table2D& T, const ShellRadii& shell, double alphaRad, double r, double muS,
                               double* out) {
  lookupTransmittance(T, shell, r, clampCosine(muS), out);
  const double cosine = sunDiscCosine(muS, alphaRad);
  for (int l = 0; l < T.channels; ++l) out[l] *= cosine;
}

/// The sun's transmittance with Bruneton's smoothstep over the solar disc at the horizon.
inline double sunVisibility(double b, double alpha, double r, double muS) {
  const double sinH = b / r;
  const double cosH = -std::sqrt(std::max(0.0, 1.0 - sinH * sinH));
  return smoothstep(-sinH * alpha, sinH * alpha, muS - cosH);
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
/// the divider; elsewhere a plain loop (vectorised: Precompute.cpp has no math errno).
UMBRA_KERNEL void lobeValuesPlain(double A, double B, double g, const double* c, double* p, int n) {
  const double g2 = 1.0 + g * g, twoG = 2.0 * g;
  for (int j = 0; j < n; ++j) {
    const double d = g2 - twoG * c[j];
    p[j] = A * (1.0 + B * c[j] * c[j]) / (d * std::sqrt(d));
  }
}
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
__attribute__((target("avx512f"))) void lobeValuesAvx512(double A, double B, double g, const double* c, double* p,
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

/// sum_j a_j b_j.
UMBRA_KERNEL double dot(const double* a, const double* b, int n) {
  double s = 0.0;
#pragma omp simd reduction(+ : s)
  for (int j = 0; j < n; ++j) s += a[j] * b[j];
  return s;
}

// ---- paths ---------------------------------------------------------------------------------

struct Knot {
  double s, x, y, tx, ty;
};

/// A ray in its plane (start at (0, r), first heading towards +x): straight (two knots) or
/// traced (a knot per RK4 step), cubic Hermite in position between the knots.
struct Path {
  std::vector<Knot> knots;
  double length = 0.0;

  /// Position and unit tangent at arc length s; `seg` is a cursor for increasing s.
  void eval(double s, std::size_t& seg, double& x, double& y, double& tx, double& ty) const {
    if (knots.size() < 2) {
      const Knot& k = knots.front();
      x = k.x, y = k.y, tx = k.tx, ty = k.ty;
      return;
    }
    while (seg + 2 < knots.size() && s > knots[seg + 1].s) ++seg;
    while (seg > 0 && s < knots[seg].s) --seg;
    const Knot& a = knots[seg];
    const Knot& c = knots[seg + 1];
    const double L = c.s - a.s;
    const double u = L > 0.0 ? std::clamp((s - a.s) / L, 0.0, 1.0) : 0.0;
    const double u2 = u * u, u3 = u2 * u;
    const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
    x = h00 * a.x + h10 * L * a.tx + h01 * c.x + h11 * L * c.tx;
    y = h00 * a.y + h10 * L * a.ty + h01 * c.y + h11 * L * c.ty;
    const double d00 = 6 * u2 - 6 * u, d10 = 3 * u2 - 4 * u + 1, d01 = -d00, d11 = 3 * u2 - 2 * u;
    double dx = d00 * a.x / std::max(L, 1e-300) + d10 * a.tx + d01 * c.x / std::max(L, 1e-300) + d11 * c.tx;
    double dy = d00 * a.y / std::max(L, 1e-300) + d10 * a.ty + d01 * c.y / std::max(L, 1e-300) + d11 * c.ty;
    if (!(L > 0.0)) dx = a.tx, dy = a.ty;
    const double n = std::sqrt(dx * dx + dy * dy);
    if (n > 0.0) tx = dx / n, ty = dy / n; else tx = a.tx, ty = a.ty;
  }
};

Path straightPath(double r, double mu, double length) {
  const double sz = std::sqrt(std::max(0.0, (1.0 - mu) * (1.0 + mu)));
  Path p;
  p.length = length;
  p.knots.push_back({0.0, 0.0, r, sz, mu});
  p.knots.push_back({length, sz * length, r + mu * length, sz, mu});
  return p;
}

/// The ray traced by traceRay; stopAtGround: up to the first contact with the ground,
/// else all of it (through the ground, as Refraction.hpp continues it).
Path tracedPath(const RefractiveMedium& medium, double r, double mu, double stepM, bool stopAtGround) {
  Path p;
  TraceOptions o;
  o.stepM = stepM;
  bool stopped = false;
  o.point = [&](const RayPoint& q) {
    if (stopped) return;
    if (q.underGround && stopAtGround) {
      stopped = true;
      return;
    }
    if (!p.knots.empty() && q.pathLengthM <= p.knots.back().s + 1e-9) {
      if (p.knots.size() > 1) p.knots.back() = {q.pathLengthM, q.xM, q.yM, q.dirX, q.dirY};
      return;
    }
    p.knots.push_back({q.pathLengthM, q.xM, q.yM, q.dirX, q.dirY});
  };
  traceRay(medium, r, mu, o);
  if (p.knots.empty()) {
    const double sz = std::sqrt(std::max(0.0, (1.0 - mu) * (1.0 + mu)));
    p.knots.push_back({0.0, 0.0, r, sz, mu});
  }
  p.length = p.knots.back().s - p.knots.front().s;
  // traceRay starts at 0 from inside the shell; shift in case it entered from above.
  const double s0 = p.knots.front().s;
  for (Knot& k : p.knots) k.s -= s0;
  return p;
}

// ---- the model restricted to what the integrals need ----------------------------------------

struct Lobe {  // A (1 + B c^2) / (1 + g^2 - 2 g c)^{3/2}, or a table uniform in c
  double A = 0.0, B = 0.0, g = 0.0;
  std::vector<double> table;
};

struct PhaseModel {
  double a = 0.0, b = 0.0;                    // a + b c^2
  std::vector<std::pair<int, double>> lobes;  // (lobe index, weight)
};

constexpr int kPhaseTableSize = 8192;

struct Model {
  const Atmosphere& atm;
  const PrecomputeOptions& o;
  double b, t, thickness;
  int nl, nc;
  std::vector<const DensityProfile*> profile;  // per component
  std::vector<double> ext;                     // [c * nl + l]
  std::vector<int> scatterers;                 // component indices
  std::vector<double> sca;                     // [s * nl + l] of the scatterers
  std::vector<PhaseModel> phase;               // [s * nl + l]
  std::vector<Lobe> lobes;
  std::vector<std::vector<int>> lobeUsers;     // per lobe: the wavelengths that use it
  std::vector<double> kinkRadii;               // where a profile's derivative jumps

  Model(const Atmosphere& a, const PrecomputeOptions& opt)
      : atm(a), o(opt), b(a.bottomRadiusM), t(a.topRadiusM), thickness(a.topRadiusM - a.bottomRadiusM),
        nl(static_cast<int>(a.wavelengthsNm.size())), nc(static_cast<int>(a.components.size())) {
    for (int c = 0; c < nc; ++c) {
      const Component& comp = a.components[c];
      profile.push_back(&comp.density);
      for (int l = 0; l < nl; ++l) ext.push_back(comp.extinctionPerM(l));
      if (comp.scatters()) scatterers.push_back(c);
      std::vector<double> kinks;
      if (comp.density.kind == DensityProfile::Kind::Tent)
        kinks = {comp.density.centreM - comp.density.halfWidthM, comp.density.centreM,
                 comp.density.centreM + comp.density.halfWidthM};
      if (comp.density.kind == DensityProfile::Kind::Tabulated) kinks = comp.density.altitudesM;
      for (double h : kinks)
        if (h > 0.0 && h < thickness) kinkRadii.push_back(b + h);
    }
    std::map<std::string, int> lobeIndex;
    for (int c : scatterers) {
      const Component& comp = a.components[c];
      for (int l = 0; l < nl; ++l) {
        sca.push_back(comp.scatteringPerM[l]);
        phase.push_back(phaseModel(comp.phase(l), l, lobeIndex));
      }
    }
  }

  int addLobe(const Lobe& lobe, int l, const std::string& key, std::map<std::string, int>& index) {
    auto it = index.find(key);
    int i;
    if (it == index.end()) {
      i = static_cast<int>(lobes.size());
      lobes.push_back(lobe);
      lobeUsers.emplace_back();
      index[key] = i;
    } else {
      i = it->second;
    }
    if (std::find(lobeUsers[i].begin(), lobeUsers[i].end(), l) == lobeUsers[i].end()) lobeUsers[i].push_back(l);
    return i;
  }

  /// Where cosine c falls in a tabulated lobe: between entries i and i + 1, weight w on i + 1.
  static void tablePosition(double c, int& i, double& w) {
    const double f = (std::clamp(c, -1.0, 1.0) + 1.0) * 0.5 * (kPhaseTableSize - 1);
    i = std::min(static_cast<int>(f), kPhaseTableSize - 2);
    w = f - i;
  }
  static double evalLobe(const Lobe& lobe, double c) {
    if (!lobe.table.empty()) {
      int i;
      double w;
      tablePosition(c, i, w);
      return (1 - w) * lobe.table[i] + w * lobe.table[i + 1];
    }
    const double d = 1.0 + lobe.g * lobe.g - 2.0 * lobe.g * c;
    return lobe.A * (1.0 + lobe.B * c * c) / (d * std::sqrt(d));
  }

  PhaseModel phaseModel(const PhaseFunction& p, int l, std::map<std::string, int>& index) {
    PhaseModel m;
    using K = PhaseFunction::Kind;
    auto hg = [](double g) { return Lobe{(1.0 - g * g) / (4.0 * kPi), 0.0, g, {}}; };
    switch (p.kind()) {
      case K::Isotropic:
      case K::Rayleigh:
      case K::Penndorf:
        m.a = p(0.0), m.b = p(1.0) - p(0.0);
        break;
      case K::HenyeyGreenstein:
        m.lobes.push_back({addLobe(hg(p.g()), l, "hg" + std::to_string(p.g()), index), 1.0});
        break;
      case K::DoubleHenyeyGreenstein:
        m.lobes.push_back({addLobe(hg(p.g()), l, "hg" + std::to_string(p.g()), index), p.alpha()});
        m.lobes.push_back({addLobe(hg(p.g2()), l, "hg" + std::to_string(p.g2()), index), 1.0 - p.alpha()});
        break;
      case K::CornetteShanks: {
        const double g = p.g();
        Lobe cs{3.0 / (8.0 * kPi) * (1.0 - g * g) / (2.0 + g * g), 1.0, g, {}};
        m.lobes.push_back({addLobe(cs, l, "cs" + std::to_string(g), index), 1.0});
        break;
      }
      case K::Tabulated:
        break;
    }
    // Check the closed form against the function; fall back to a table when they differ
    // (or the function is tabulated).
    bool ok = p.kind() != K::Tabulated;
    for (int i = 0; ok && i <= 16; ++i) {
      const double c = -1.0 + i / 8.0;
      double v = m.a + m.b * c * c;
      for (auto [li, w] : m.lobes) v += w * evalLobe(lobes[li], c);
      if (std::abs(v - p(c)) > 1e-9 * std::max(1.0, std::abs(p(c)))) ok = false;
    }
    if (!ok) {
      m = PhaseModel{};
      Lobe tab;
      tab.table.resize(kPhaseTableSize);
      for (int i = 0; i < kPhaseTableSize; ++i) tab.table[i] = p(-1.0 + 2.0 * i / (kPhaseTableSize - 1));
      // keyed by the table's bytes: equal tables share a lobe, different ones (e.g. one
      // Lorenz-Mie table per wavelength, all with the same sample count) never do
      const std::string key(reinterpret_cast<const char*>(tab.table.data()), tab.table.size() * sizeof(double));
      m.lobes.push_back({addLobe(tab, l, "table:" + key, index), 1.0});
    }
    return m;
  }

  double density(int c, double altitudeM) const {
    return profile[c]->at(std::clamp(altitudeM, 0.0, thickness));
  }

  /// Per-component column densities (integral of rho_c ds) along a path from s0 to s1,
  /// Simpson's rule with n (even) intervals; added to col[0..nc). On straight paths the
  /// interval is split where the ray crosses the profiles' kinks (tent, tabulated), so that
  /// piecewise-smooth profiles are integrated to rounding.
  void columns(const Path& path, double s0, double s1, int n, std::size_t& seg, double* col) const {
    if (!(s1 > s0)) return;
    if (!kinkRadii.empty()) {
      std::vector<double> cuts{s0, s1};
      if (path.knots.size() == 2) {
        const double r = path.knots[0].y, mu = path.knots[0].ty;
        for (double R : kinkRadii) {
          const double disc = r * r * (mu * mu - 1.0) + R * R;
          if (disc < 0.0) continue;
          for (double sgn : {-1.0, 1.0}) {
            const double s = -r * mu + sgn * std::sqrt(disc);
            if (s > s0 && s < s1) cuts.push_back(s);
          }
        }
      } else {
        // Traced: sign changes of r - R_k on a grid finer than the knots, then bisection.
        std::size_t c = 0;
        auto radiusAt = [&](double sv) {
          double x, y, tx, ty;
          path.eval(sv, c, x, y, tx, ty);
          return std::sqrt(x * x + y * y);
        };
        std::size_t inside = 0;
        for (const Knot& k : path.knots) inside += (k.s > s0 && k.s < s1);
        const int M = static_cast<int>(4 * inside + 8);
        double sa = s0, ra = radiusAt(s0);
        for (int i = 1; i <= M; ++i) {
          const double sb = s0 + (s1 - s0) * i / M, rb = radiusAt(sb);
          for (double R : kinkRadii) {
            if (ra == R && sa > s0) cuts.push_back(sa);
            if ((ra - R) * (rb - R) >= 0.0) continue;
            double lo = sa, hi = sb, flo = ra - R;
            for (int it = 0; it < 60 && hi - lo > 1e-7; ++it) {
              const double mid = 0.5 * (lo + hi), fm = radiusAt(mid) - R;
              if ((fm < 0.0) == (flo < 0.0)) lo = mid, flo = fm; else hi = mid;
            }
            cuts.push_back(0.5 * (lo + hi));
          }
          sa = sb, ra = rb;
        }
      }
      if (cuts.size() > 2) {
        std::sort(cuts.begin(), cuts.end());
        for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
          const double len = cuts[i + 1] - cuts[i];
          if (!(len > 0.0)) continue;
          int k = static_cast<int>(std::ceil(n * len / (s1 - s0) / 2.0)) * 2;
          simpson(path, cuts[i], cuts[i + 1], std::max(2, k), seg, col);
        }
        return;
      }
    }
    simpson(path, s0, s1, n, seg, col);
  }
  void simpson(const Path& path, double s0, double s1, int n, std::size_t& seg, double* col) const {
    const double h = (s1 - s0) / n;
    for (int i = 0; i <= n; ++i) {
      const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
      double x, y, tx, ty;
      path.eval(s0 + i * h, seg, x, y, tx, ty);
      const double alt = std::sqrt(x * x + y * y) - b;
      for (int c = 0; c < nc; ++c) col[c] += w * h / 3.0 * density(c, alt);
    }
  }
  void opticalDepth(const double* col, double* tau) const {
    for (int l = 0; l < nl; ++l) {
      double s = 0.0;
      for (int c = 0; c < nc; ++c) s += ext[c * nl + l] * col[c];
      tau[l] = s;
    }
  }
};

// ---- progress and parallel loops -----------------------------------------------------------

class Runner {
public:
  Runner(const PrecomputeProgress& progress, int threads, double begin, double end)
      : progress_(progress), threads_(threads), begin_(begin), end_(end) {}

  void setStages(double totalWeight) { total_ = totalWeight; }

  /// f(i) for i in [0, n), OpenMP dynamic schedule, reported in chunks.
  template <class F>
  void run(const std::string& stage, double weight, int n, F&& f) {
    const auto t0 = std::chrono::steady_clock::now();
    const int chunks = std::max(1, std::min(n, 16));
    for (int k = 0; k < chunks; ++k) {
      const int lo = static_cast<int>(static_cast<long long>(n) * k / chunks);
      const int hi = static_cast<int>(static_cast<long long>(n) * (k + 1) / chunks);
      ParallelErrors errors;
#ifdef _OPENMP
      const int nt = threads_ > 0 ? threads_ : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt)
#endif
      for (int i = lo; i < hi; ++i) errors.run([&] { f(i); });
      errors.rethrow();
      report(stage, done_ + weight * (k + 1) / chunks);
    }
    done_ += weight;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    timings[stage] += s;
    if (std::find(order.begin(), order.end(), stage) == order.end()) order.push_back(stage);
  }

  std::map<std::string, double> timings;
  std::vector<std::string> order;

private:
  void report(const std::string& stage, double done) {
    if (!progress_) return;
    const double f = begin_ + (end_ - begin_) * std::clamp(total_ > 0 ? done / total_ : 1.0, 0.0, 1.0);
    if (!progress_(f, stage)) throw PrecomputeCancelled();
  }
  const PrecomputeProgress& progress_;
  int threads_;
  double begin_, end_, total_ = 1.0, done_ = 0.0;
};

// ---- one batch of wavelengths ---------------------------------------------------------------

/// A view ray's samples: positions, tangents, radii and the transmittance from the start.
struct RaySamples {
  int n = 0;          // intervals (n + 1 samples)
  double ds = 0.0;    // interval length
  bool ground = false;
  std::vector<double> r, xr, yr, tx, ty, mu;  // per sample; xr = x / r, yr = y / r; mu local
  std::vector<double> T;                      // [i * nl + l]
  std::vector<double> rhoT;  // [(i * ns + q) * nl + l]: int rho_q T_view hat_i ds
};

/// The 2D tables of a batch; its 3D tables go straight into the final ones (single, multiple:
/// all wavelengths wide, the batch's channels from l0 on), so that no batch-wide copy of
/// them is ever held.
struct BatchResult {
  Table2D transmittance, directIrradiance, irradiance;
  std::vector<std::vector<double>> orderMean;
};

BatchResult computeBatch(const Atmosphere& atm, const PrecomputeOptions& o, Runner& run, std::vector<Table3D>& single,
                         Table3D& multiple, int l0) {
  const Model m(atm, o);
  const int nl = m.nl, nc = m.nc, ns = static_cast<int>(m.scatterers.size());
  const ShellRadii shell{atm.bottomRadiusM, atm.topRadiusM};
  const double b = m.b, t = m.t;
  const ScatterGeometry g(shell, {o.scatteringR, o.scatteringMu, o.scatteringMuS, o.scatteringNu}, o.muSMin);
  const int W = o.scatteringNu * o.scatteringMuS, MU = o.scatteringMu, R = o.scatteringR, MUS = o.scatteringMuS;
  const std::size_t texels = static_cast<std::size_t>(W) * MU * R;
  BatchResult out;

  // Refractive media: one per distinct refractivity (dispersion) for the transmittance,
  // the reference wavelength's for the scattering paths.
  std::vector<RefractiveMedium> media;
  std::vector<std::vector<int>> mediumUsers;
  RefractiveMedium referenceMedium;
  if (o.refraction) {
    std::map<double, int> seen;
    for (int l = 0; l < nl; ++l) {
      const double key = dispersionRatio(atm.dispersion, atm.wavelengthsNm[l], atm.refractivityReferenceWavelengthNm);
      auto it = seen.find(key);
      if (it == seen.end()) {
        seen[key] = static_cast<int>(media.size());
        media.push_back(refractiveMedium(atm, atm.wavelengthsNm[l]));
        mediumUsers.push_back({l});
      } else {
        mediumUsers[it->second].push_back(l);
      }
    }
    referenceMedium = refractiveMedium(atm, atm.refractivityReferenceWavelengthNm);
  }

  // ---- transmittance -----------------------------------------------------------------------
  const int TW = o.transmittanceWidth, TH = o.transmittanceHeight;
  out.transmittance.resize(TW, TH, nl);
  run.run("transmittance", 1.0, TW * TH, [&](int i) {
    const int x = i % TW, y = i / TW;
    const RadiusMu rm = rMuAtTexel(shell, x, y, TW, TH);
    std::vector<double> col(nc), tau(nl);
    double* T = out.transmittance.at(x, y);
    if (!o.refraction) {
      const Path p = straightPath(rm.radiusM, rm.mu, distanceToTopBoundaryM(t, rm.radiusM, rm.mu));
      std::size_t seg = 0;
      m.columns(p, 0.0, p.length, o.transmittanceSamples, seg, col.data());
      m.opticalDepth(col.data(), tau.data());
      for (int l = 0; l < nl; ++l) T[l] = std::exp(-tau[l]);
      return;
    }
    for (std::size_t k = 0; k < media.size(); ++k) {
      const Path p = tracedPath(media[k], rm.radiusM, rm.mu, o.refractionStepM, false);
      std::fill(col.begin(), col.end(), 0.0);
      std::size_t seg = 0;
      m.columns(p, 0.0, p.length, o.transmittanceSamples, seg, col.data());
      m.opticalDepth(col.data(), tau.data());
      for (int l : mediumUsers[k]) T[l] = std::exp(-tau[l]);
    }
  });
  const Table2D& Ttab = out.transmittance;

  // ---- direct irradiance -------------------------------------------------------------------
  const int IW = o.irradianceWidth, IH = o.irradianceHeight;
  out.directIrradiance.resize(IW, IH, nl);
  out.irradiance.resize(IW, IH, nl);
  const double alpha = o.sunAngularRadiusRad;
  auto irradianceTexel = [&](int x, int y, double& r, double& muS) {
    r = b + (t - b) * y / (IH - 1.0);
    muS = clampCosine(-1.0 + 2.0 * x / (IW - 1.0));
  };
  run.run("direct irradiance", 0.05, IH, [&](int y) {
    for (int x = 0; x < IW; ++x) {
      double r, muS;
      irradianceTexel(x, y, r, muS);
      directIrradianceAt(Ttab, shell, alpha, r, muS, out.directIrradiance.at(x, y));
    }
  });

  // ---- view-ray samples, per (r, mu) -------------------------------------------------------
  auto buildSamples = [&](int N, std::vector<RaySamples>& rays) {
    rays.assign(static_cast<std::size_t>(R) * MU, RaySamples{});
    run.run("view rays", 0.3, R * MU, [&](int i) {
      const int y = i % MU, z = i / MU;
      const ScatteringPoint p = g.texel(0, y, z);
      RaySamples& s = rays[i];
      s.ground = p.rayIntersectsGround;
      const double L = s.ground ? distanceToBottomBoundaryM(b, p.r, p.mu) : distanceToTopBoundaryM(t, p.r, p.mu);
      Path path = !o.refraction || !(L > 0.0)
                      ? straightPath(p.r, p.mu, L)
                      : tracedPath(referenceMedium, p.r, p.mu, std::min(o.refractionStepM, std::max(1.0, L / N)), true);
      s.n = N;
      s.ds = path.length / N;
      s.r.resize(N + 1), s.xr.resize(N + 1), s.yr.resize(N + 1), s.tx.resize(N + 1), s.ty.resize(N + 1);
      s.mu.resize(N + 1);
      s.T.resize(static_cast<std::size_t>(N + 1) * nl);
      std::vector<double> col(nc, 0.0), tau(nl), tauAll(static_cast<std::size_t>(N + 1) * nl);
      std::size_t seg = 0, seg2 = 0;
      for (int k = 0; k <= N; ++k) {
        const double sk = k * s.ds;
        if (k > 0) m.columns(path, sk - s.ds, sk, o.opticalDepthSubsamples, seg2, col.data());
        double x, yy, tx, ty;
        path.eval(sk, seg, x, yy, tx, ty);
        if (!(std::isfinite(x) && std::isfinite(yy) && std::isfinite(tx) && std::isfinite(ty) && std::isfinite(s.ds)))
          throwNonFiniteLookup();
        const double r = std::max(std::sqrt(x * x + yy * yy), 1e-3);
        s.r[k] = r, s.xr[k] = x / r, s.yr[k] = yy / r, s.tx[k] = tx, s.ty[k] = ty;
        s.mu[k] = clampCosine((x * tx + yy * ty) / r);
        m.opticalDepth(col.data(), tau.data());
        for (int l = 0; l < nl; ++l) {
          s.T[static_cast<std::size_t>(k) * nl + l] = std::exp(-tau[l]);
          tauAll[static_cast<std::size_t>(k) * nl + l] = tau[l];
        }
      }
      // Hat-function weights of rho_q * T_view for the single-scattering sum: Simpson on
      // the sub-intervals, T_view there from the trapezoidal shape of the interval's
      // optical depth scaled to its Simpson total. Exact for any density variation that the
      // sub-intervals resolve, whatever the sample count (the sun's transmittance is then
      // interpolated linearly between samples).
      s.rhoT.assign(static_cast<std::size_t>(N + 1) * ns * nl, 0.0);
      const int msub = o.opticalDepthSubsamples;
      std::vector<double> rhoSub(static_cast<std::size_t>(msub + 1) * nc), cum(msub + 1);
      std::size_t seg3 = 0;
      for (int k = 1; k <= N && s.ds > 0.0; ++k) {
        const double s0 = (k - 1) * s.ds, h = s.ds / msub;
        for (int j = 0; j <= msub; ++j) {
          double x, yy, tx, ty;
          path.eval(s0 + j * h, seg3, x, yy, tx, ty);
          const double alt = std::sqrt(x * x + yy * yy) - b;
          for (int c = 0; c < nc; ++c) rhoSub[j * nc + c] = m.density(c, alt);
        }
        for (int l = 0; l < nl; ++l) {
          cum[0] = 0.0;
          double ePrev = 0.0;
          for (int j = 0; j <= msub; ++j) {
            double e = 0.0;
            for (int c = 0; c < nc; ++c) e += m.ext[c * nl + l] * rhoSub[j * nc + c];
            if (j > 0) cum[j] = cum[j - 1] + 0.5 * h * (e + ePrev);
            ePrev = e;
          }
          const double tau0 = tauAll[static_cast<std::size_t>(k - 1) * nl + l];
          const double dtau = tauAll[static_cast<std::size_t>(k) * nl + l] - tau0;
          for (int j = 0; j <= msub; ++j) {
            const double frac = cum[msub] > 0.0 ? cum[j] / cum[msub] : 0.0;
            const double Tj = std::exp(-(tau0 + dtau * frac));
            const double wj = h / 3.0 * ((j == 0 || j == msub) ? 1.0 : (j % 2 ? 4.0 : 2.0)) * Tj;
            const double u = static_cast<double>(j) / msub;
            for (int q = 0; q < ns; ++q) {
              const double v = wj * rhoSub[j * nc + m.scatterers[q]];
              s.rhoT[(static_cast<std::size_t>(k - 1) * ns + q) * nl + l] += v * (1.0 - u);
              s.rhoT[(static_cast<std::size_t>(k) * ns + q) * nl + l] += v * u;
            }
          }
        }
      }
    });
  };
  std::vector<RaySamples> singleRays, multipleRays;
  buildSamples(o.singleScatteringSamples, singleRays);
  const bool sameRays = o.multipleScatteringSamples == o.singleScatteringSamples;
  if (!sameRays && o.orders > 1) buildSamples(o.multipleScatteringSamples, multipleRays);
  const std::vector<RaySamples>& mRays = sameRays ? singleRays : multipleRays;

  // The sun's direction in the ray's frame (x: the view's azimuth).
  auto sunX = [](const ScatteringPoint& p) {
    const double sz = std::sqrt(std::max(0.0, (1.0 - p.mu) * (1.0 + p.mu)));
    const double ss = std::sqrt(std::max(0.0, (1.0 - p.muS) * (1.0 + p.muS)));
    if (sz < 1e-12) return ss;
    return std::clamp((p.nu - p.mu * p.muS) / sz, -ss, ss);
  };

  // ---- single scattering -------------------------------------------------------------------
  run.run("single scattering", 1.0, R * MU, [&](int i) {
    const int y = i % MU, z = i / MU;
    const RaySamples& s = singleRays[i];
    const int N = s.n;
    // A[k][q][l] = beta_s * int rho_q T_view hat_k
    std::vector<double> A(static_cast<std::size_t>(N + 1) * ns * nl);
    for (int k = 0; k <= N; ++k)
      for (int q = 0; q < ns; ++q)
        for (int l = 0; l < nl; ++l) {
          const std::size_t idx = (static_cast<std::size_t>(k) * ns + q) * nl + l;
          A[idx] = m.sca[q * nl + l] * s.rhoT[idx];
        }
    // Samples outer, texels inner: the sample's radius fixes the transmittance row
    // (blended once) and the horizon; the texels' sun cosines are computed together.
    std::vector<double> sxA(W), muSA(W), visA(W), fxA(W), Trow(static_cast<std::size_t>(TW) * nl);
    std::vector<double> acc(static_cast<std::size_t>(W) * ns * nl, 0.0);
    for (int x = 0; x < W; ++x) {
      const ScatteringPoint p = g.texel(x, y, z);
      sxA[x] = sunX(p), muSA[x] = p.muS;
    }
    for (int k = 0; k <= N && s.ds > 0.0; ++k) {
      const TransmittanceCoords rc = transmittanceCoordsFromRMu(shell, s.r[k], 1.0);
      const double fy = rc.xR * (TH - 1);
      const int iy = std::min(static_cast<int>(fy), TH - 2);
      const double wy = fy - iy;
      const double* row0 = Ttab.at(0, iy);
      const double* row1 = Ttab.at(0, iy + 1);
      for (std::size_t i = 0; i < Trow.size(); ++i) Trow[i] = (1 - wy) * row0[i] + wy * row1[i];
      sunTexels(shell, alpha, s.r[k], s.xr[k], s.yr[k], sxA.data(), muSA.data(), W, TW, visA.data(), fxA.data());
      const double* a = A.data() + static_cast<std::size_t>(k) * ns * nl;  // A is empty without scatterers
      for (int x = 0; x < W; ++x) {
        const double vis = visA[x];
        if (vis == 0.0) continue;
        const int ix = std::min(static_cast<int>(fxA[x]), TW - 2);
        const double wx = fxA[x] - ix;
        const double* T0 = &Trow[static_cast<std::size_t>(ix) * nl];
        const double* T1 = T0 + nl;
        double* ax = acc.data() + static_cast<std::size_t>(x) * ns * nl;
        for (int q = 0; q < ns; ++q)
          for (int l = 0; l < nl; ++l) ax[q * nl + l] += a[q * nl + l] * ((1 - wx) * T0[l] + wx * T1[l]) * vis;
      }
    }
    for (int x = 0; x < W; ++x)
      for (int q = 0; q < ns; ++q)
        std::copy_n(&acc[(static_cast<std::size_t>(x) * ns + q) * nl], nl, single[q].at(x, y, z) + l0);
  });

  auto meanOf = [&](auto&& texelValue) {
    std::vector<double> sum(nl, 0.0);
    std::vector<double> v(nl);
    for (int z = 0; z < R; ++z)
      for (int y = 0; y < MU; ++y)
        for (int x = 0; x < W; ++x) {
          texelValue(x, y, z, v.data());
          for (int l = 0; l < nl; ++l) sum[l] += v[l];
        }
    for (double& s : sum) s /= static_cast<double>(texels);
    return sum;
  };
  // L_1 (phases included) at a texel, for the statistics.
  out.orderMean.push_back(meanOf([&](int x, int y, int z, double* v) {
    const ScatteringPoint p = g.texel(x, y, z);
    std::fill(v, v + nl, 0.0);
    for (int q = 0; q < ns; ++q) {
      const Component& comp = atm.components[m.scatterers[q]];
      const double* S = single[q].at(x, y, z) + l0;
      for (int l = 0; l < nl; ++l) v[l] += S[l] * comp.phase(l)(p.nu);
    }
  }));

  // The single-scattering weights are spent: free them before the working tables.
  for (std::vector<RaySamples>* rays : {&singleRays, &multipleRays})
    for (RaySamples& s : *rays) std::vector<double>().swap(s.rhoT);
  if (o.orders < 2) return out;

  // L_{k-1}(r, mu, mu_s, nu) added into v: order 1 from the single tables, else delta.
  Table3D delta, density;
  delta.resize(W, MU, R, nl);
  density.resize(W, MU, R, nl);
  auto incoming = [&](int order, double r, double mu, double muS, double nu, bool ground, double* v) {
    const RMuCell a = rMuCell(g, r, mu, ground);
    const SNuCell c = sNuCell(g, muS, nu);
    if (order == 1) {
      std::vector<double> tmp(nl);
      for (int q = 0; q < ns; ++q) {
        std::fill(tmp.begin(), tmp.end(), 0.0);
        accumulate4(single[q], a, c, 1.0, tmp.data(), l0, nl);
        const Component& comp = atm.components[m.scatterers[q]];
        for (int l = 0; l < nl; ++l) v[l] += tmp[l] * comp.phase(l)(nu);
      }
    } else {
      accumulate4(delta, a, c, 1.0, v);
    }
  };

  // Sphere of directions for the density, per radius: Gauss-Legendre in mu on each side
  // of the ground's horizon mu_h(r) (n/2 nodes below it, n - n/2 above; the nodes crowd
  // towards the ends, so both sides of the horizon, where the sky is brightest and the
  // radiance jumps to the ground's, are sampled within a degree or two), midpoint rule in
  // phi (n over (0, pi)). The incoming radiance is symmetric about the plane of the zenith
  // and the sun (phi -> -phi: the same (mu, mu_s, nu)), so only phi in (0, pi) is looked
  // up, each direction standing for itself and its mirror (wy -> -wy) with twice the solid
  // angle. A midpoint rule in theta missed the band along the horizon that lights the
  // shadowed air in twilight (docs/accuracy-vs-speed.md, "Twilight").
  const int nTh = o.sphereSamples, nPh = nTh, nDir = nTh * nPh;
  const double dA = kPi / nTh;
  const std::size_t RD = static_cast<std::size_t>(R) * nDir;
  std::vector<double> wxAll(RD), wyAll(RD), wzAll(RD), wdoAll(RD);
  const int nGround = nTh / 2, nSky = nTh - nGround;
  const GaussLegendreRule glSky(nSky), glGround(nGround);
  // Transmittance from (r_z, theta_l) to the ground along straight rays (for the ground term).
  std::vector<double> groundT(static_cast<std::size_t>(R) * nTh * nl, 0.0), groundD(static_cast<std::size_t>(R) * nTh, -1.0);
  for (int z = 0; z < R; ++z) {
    const double r = g.rFromU((z + 0.5) / R);
    const double muH = -std::sqrt(std::max(0.0, 1.0 - (b / r) * (b / r)));
    for (int lt = 0; lt < nTh; ++lt) {
      const bool sky = lt < nSky;
      const GaussLegendreRule& q = sky ? glSky : glGround;
      const int i = sky ? lt : lt - nSky;
      const double lo = sky ? muH : -1.0, hi = sky ? 1.0 : muH;
      const double mu = 0.5 * (lo + hi) + 0.5 * (hi - lo) * q.x[i], dMu = 0.5 * (hi - lo) * q.w[i];
      const double sinTh = std::sqrt(std::max(0.0, 1.0 - mu * mu));
      for (int mp = 0; mp < nPh; ++mp) {
        const double ph = (mp + 0.5) * dA;
        const std::size_t j = static_cast<std::size_t>(z) * nDir + lt * nPh + mp;
        wxAll[j] = std::cos(ph) * sinTh, wyAll[j] = std::sin(ph) * sinTh, wzAll[j] = mu;
        wdoAll[j] = 2.0 * dA * dMu;
      }
      if (sky || !rayIntersectsGround(b, r, mu)) continue;
      const double d = distanceToBottomBoundaryM(b, r, mu);
      groundD[z * nTh + lt] = d;
      const Path p = straightPath(r, mu, d);
      std::vector<double> col(nc, 0.0), tau(nl);
      std::size_t seg = 0;
      m.columns(p, 0.0, d, o.transmittanceSamples, seg, col.data());
      m.opticalDepth(col.data(), tau.data());
      for (int l = 0; l < nl; ++l) groundT[(static_cast<std::size_t>(z) * nTh + lt) * nl + l] = std::exp(-tau[l]);
    }
  }

  // The exact integral of each phase lobe over the sphere (trapezoid in cos theta, 2^17
  // pieces: a Henyey-Greenstein lobe of g = 0.95 peaks over 1e-3 in cos theta). The sum
  // over the directions above is renormalised to it per view (below): a forward peak
  // narrower than the directions' spacing is otherwise over- or under-counted depending on
  // where the view falls between them.
  std::vector<double> lobeIntegral(m.lobes.size(), 0.0);
  for (std::size_t li = 0; li < m.lobes.size(); ++li) {
    const int n = 1 << 17;
    double sum = 0.5 * (Model::evalLobe(m.lobes[li], -1.0) + Model::evalLobe(m.lobes[li], 1.0));
    for (int i = 1; i < n; ++i) sum += Model::evalLobe(m.lobes[li], -1.0 + 2.0 * i / n);
    lobeIntegral[li] = 2.0 * kPi * sum * 2.0 / n;
  }

  Table2D deltaE;  // E_{k-2}, from order 3 on (order 2's ground takes E_0 from directIrradianceAt)
  Table2D nextE;
  nextE.resize(IW, IH, nl);
  const int nIrTh = o.irradianceSamples / 2, nIrPh = 2 * o.irradianceSamples;
  const double dI = kPi / o.irradianceSamples;

  for (int order = 2; order <= o.orders; ++order) {
    // ---- scattering density J_order, one (r, mu_s) slice per task --------------------------
    run.run("scattering density", 2.0, R * MUS, [&](int task) {
      const int z = task / MUS, is = task % MUS;
      const ScatteringPoint p0 = g.texel(is, 0, z);
      const double r = p0.r, muS = p0.muS, sinS = std::sqrt(std::max(0.0, 1.0 - muS * muS));
      const double alt = r - b;
      const std::size_t zd = static_cast<std::size_t>(z) * nDir;
      const double *wx = &wxAll[zd], *wy = &wyAll[zd], *wz = &wzAll[zd], *wdo = &wdoAll[zd];
      // Incoming radiance per direction, times the solid angle: Lw[l][j].
      std::vector<double> Lw(static_cast<std::size_t>(nl) * nDir), v(nl), E(nl);
      std::vector<double> M0(nl, 0.0), M2(static_cast<std::size_t>(nl) * 6, 0.0);
      for (int j = 0; j < nDir; ++j) {
        const int lt = j / nPh;
        const double nu = clampCosine(wx[j] * sinS + wz[j] * muS);
        const bool ground = groundD[z * nTh + lt] >= 0.0;
        std::fill(v.begin(), v.end(), 0.0);
        incoming(order - 1, r, wz[j], muS, nu, ground, v.data());
        if (ground) {
          const double d = groundD[z * nTh + lt];
          const double muSg = clampCosine((r * muS + d * nu) / b);
          if (order == 2) {
            directIrradianceAt(Ttab, shell, alpha, b, muSg, E.data());  // E_0, exact at the setting Sun
          } else {
            lookupIrradiance(deltaE, shell, b, muSg, E.data());
          }
          const double* Tg = &groundT[(static_cast<std::size_t>(z) * nTh + lt) * nl];
          for (int l = 0; l < nl; ++l) v[l] += Tg[l] * atm.groundAlbedo[l] / kPi * E[l];
        }
        for (int l = 0; l < nl; ++l) {
          const double L = v[l] * wdo[j];
          Lw[static_cast<std::size_t>(l) * nDir + j] = L;
          M0[l] += L;
          double* M = &M2[l * 6];
          // xy and yz cancel with the mirror (M[3] = M[5] = 0)
          M[0] += wx[j] * wx[j] * L, M[1] += wy[j] * wy[j] * L, M[2] += wz[j] * wz[j] * L;
          M[4] += wx[j] * wz[j] * L;
        }
      }
      std::vector<double> rho(ns);
      for (int q = 0; q < ns; ++q) rho[q] = m.density(m.scatterers[q], alt);
      // cj: the cosines with the view of the directions [0, nDir) and of their mirrors.
      std::vector<double> cj(2 * nDir), pj(2 * nDir), pPair(nDir), lobeSum(m.lobes.size() * nl), J(nl);
      // Tabulated lobes (one per wavelength for Lorenz-Mie) share the cosines: the table
      // index and weight of each, computed once per view (as Model::evalLobe does).
      std::vector<int> tableIndex(2 * nDir);
      std::vector<double> tableWeight(2 * nDir);
      bool anyTable = false;
      for (const Lobe& lobe : m.lobes) anyTable = anyTable || !lobe.table.empty();
      for (int y = 0; y < MU; ++y) {
        for (int k = 0; k < o.scatteringNu; ++k) {
          const int x = k * MUS + is;
          const ScatteringPoint p = g.texel(x, y, z);
          const double sz = std::sqrt(std::max(0.0, 1.0 - p.mu * p.mu));
          double vx = sinS > 1e-12 ? std::clamp((p.nu - p.mu * muS) / sinS, -sz, sz) : sz;
          const double vy = std::sqrt(std::max(0.0, sz * sz - vx * vx)), vz = p.mu;
          if (!m.lobes.empty()) {
#pragma omp simd
            for (int j = 0; j < nDir; ++j) {
              cj[j] = wx[j] * vx + wy[j] * vy + wz[j] * vz;
              cj[nDir + j] = wx[j] * vx - wy[j] * vy + wz[j] * vz;
            }
          }
          if (anyTable) {
            for (int j = 0; j < 2 * nDir; ++j) Model::tablePosition(cj[j], tableIndex[j], tableWeight[j]);
          }
          for (std::size_t li = 0; li < m.lobes.size(); ++li) {
            const Lobe& lobe = m.lobes[li];
            if (lobe.table.empty()) {
              lobeValues(lobe.A, lobe.B, lobe.g, cj.data(), pj.data(), 2 * nDir);
            } else {
              const double* T = lobe.table.data();
              for (int j = 0; j < 2 * nDir; ++j) {
                const int i = tableIndex[j];
                const double w = tableWeight[j];
                pj[j] = (1 - w) * T[i] + w * T[i + 1];
              }
            }
#pragma omp simd
            for (int j = 0; j < nDir; ++j) pPair[j] = 0.5 * (pj[j] + pj[nDir + j]);
            const double norm = dot(pPair.data(), wdo, nDir);
            const double scale = norm > 0.0 ? lobeIntegral[li] / norm : 1.0;
            for (int l : m.lobeUsers[li]) {
              lobeSum[li * nl + l] = scale * dot(pPair.data(), &Lw[static_cast<std::size_t>(l) * nDir], nDir);
            }
          }
          std::fill(J.begin(), J.end(), 0.0);
          for (int q = 0; q < ns; ++q) {
            for (int l = 0; l < nl; ++l) {
              const PhaseModel& pm = m.phase[q * nl + l];
              double s = 0.0;
              if (pm.a != 0.0 || pm.b != 0.0) {
                const double* M = &M2[l * 6];
                const double vMv = vx * vx * M[0] + vy * vy * M[1] + vz * vz * M[2] +
                                   2.0 * (vx * vy * M[3] + vx * vz * M[4] + vy * vz * M[5]);
                s += pm.a * M0[l] + pm.b * vMv;
              }
              for (auto [li, w] : pm.lobes) s += w * lobeSum[li * nl + l];
              J[l] += m.sca[q * nl + l] * rho[q] * s;
            }
          }
          std::copy_n(J.data(), nl, density.at(x, y, z));
        }
      }
    });

    // ---- indirect irradiance E_{order-1} from L_{order-1} ----------------------------------
    run.run("indirect irradiance", 0.1, IH, [&](int y) {
      std::vector<double> v(nl);
      for (int x = 0; x < IW; ++x) {
        double r, muS;
        irradianceTexel(x, y, r, muS);
        const double sinS = std::sqrt(std::max(0.0, 1.0 - muS * muS));
        std::vector<double> E(nl, 0.0);
        for (int jt = 0; jt < nIrTh; ++jt) {
          const double th = (jt + 0.5) * dI, cz = std::cos(th), sth = std::sin(th);
          for (int ip = 0; ip < nIrPh; ++ip) {
            const double ph = (ip + 0.5) * dI;
            const double nu = clampCosine(std::cos(ph) * sth * sinS + cz * muS);
            std::fill(v.begin(), v.end(), 0.0);
            incoming(order - 1, r, cz, muS, nu, false, v.data());
            const double w = cz * sth * dI * dI;
            for (int l = 0; l < nl; ++l) E[l] += v[l] * w;
          }
        }
        std::copy_n(E.data(), nl, nextE.at(x, y));
        double* acc = out.irradiance.at(x, y);
        for (int l = 0; l < nl; ++l) acc[l] += E[l];
      }
    });
    deltaE = nextE;

    // ---- multiple scattering L_order from J_order ------------------------------------------
    run.run("multiple scattering", 1.0, R * MU, [&](int i) {
      const int y = i % MU, z = i / MU;
      const RaySamples& s = mRays[i];
      const int N = s.n;
      std::vector<RMuCell> cells(N + 1);
      for (int k = 0; k <= N; ++k)
        cells[k] = rMuCell(g, s.r[k], s.mu[k], rayIntersectsGround(b, s.r[k], s.mu[k]));
      // Samples outer, texels inner. J is linear in the (r, mu) weights, which depend on
      // the sample only: the sample's four (r, mu) rows are blended once into one row of
      // (mu_s, nu) texels, and each texel reads that row bilinearly (4 reads, not 16).
      const std::size_t rowSize = static_cast<std::size_t>(W) * nl;
      std::vector<double> sxA(W), muSA(W), wsA(W), wnA(W), acc(rowSize, 0.0), blend(rowSize);
      std::vector<int> x00A(W);
      for (int x = 0; x < W; ++x) {
        const ScatteringPoint p = g.texel(x, y, z);
        sxA[x] = sunX(p), muSA[x] = p.muS;
      }
      for (int k = 0; k <= N && s.ds > 0.0; ++k) {
        const double w = s.ds * ((k == 0 || k == N) ? 0.5 : 1.0);
        const double* T = &s.T[static_cast<std::size_t>(k) * nl];
        blendRows(density, cells[k], blend.data());
        const double xr = s.xr[k], yr = s.yr[k], tx = s.tx[k], ty = s.ty[k];
        sNuTexels(g, xr, yr, tx, ty, sxA.data(), muSA.data(), W, x00A.data(), wsA.data(), wnA.data());
        const std::size_t up = static_cast<std::size_t>(MUS) * nl;
        for (int x = 0; x < W; ++x) {
          const double* p00 = &blend[static_cast<std::size_t>(x00A[x]) * nl];
          const double* p01 = p00 + nl;
          const double* p10 = p00 + up;
          const double* p11 = p10 + nl;
          const double ws = wsA[x], wn = wnA[x];
          const double w00 = w * (1 - wn) * (1 - ws), w01 = w * (1 - wn) * ws, w10 = w * wn * (1 - ws), w11 = w * wn * ws;
          double* a = &acc[static_cast<std::size_t>(x) * nl];
          for (int l = 0; l < nl; ++l) a[l] += T[l] * (w00 * p00[l] + w01 * p01[l] + w10 * p10[l] + w11 * p11[l]);
        }
      }
      for (int x = 0; x < W; ++x) {
        const double* a = &acc[static_cast<std::size_t>(x) * nl];
        std::copy_n(a, nl, delta.at(x, y, z));
        double* sum = multiple.at(x, y, z) + l0;
        for (int l = 0; l < nl; ++l) sum[l] += a[l];
      }
    });
    out.orderMean.push_back(meanOf([&](int x, int y, int z, double* v) { std::copy_n(delta.at(x, y, z), nl, v); }));
  }
  return out;
}

Atmosphere subAtmosphere(const Atmosphere& atm, const std::vector<int>& ls) {
  Atmosphere s = atm;
  auto pick = [&](const std::vector<double>& v) {
    std::vector<double> r;
    for (int l : ls) r.push_back(v[l]);
    return r;
  };
  s.wavelengthsNm = pick(atm.wavelengthsNm);
  s.groundAlbedo = pick(atm.groundAlbedo);
  for (std::size_t c = 0; c < atm.components.size(); ++c) {
    const Component& a = atm.components[c];
    Component& d = s.components[c];
    d.scatteringPerM = pick(a.scatteringPerM);
    d.absorptionPerM = pick(a.absorptionPerM);
    d.phases.clear();
    for (int l : ls) d.phases.push_back(a.phases.at(l));
  }
  return s;
}

void copyChannels2D(const Table2D& from, Table2D& to, const std::vector<int>& ls) {
  const std::size_t n = static_cast<std::size_t>(from.width) * from.height;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < ls.size(); ++k) to.values[i * to.channels + ls[k]] = from.values[i * from.channels + k];
}
}  // namespace

namespace detail {
void lobeValuesBaseline(double A, double B, double g, const double* c, double* p, int n) {
  lobeValuesPlain(A, B, g, c, p, n);
}
void lobeValuesDispatched(double A, double B, double g, const double* c, double* p, int n) {
  lobeValues(A, B, g, c, p, n);
}
}  // namespace detail

ScatteringCoords scatteringCoordsFromRMuMuSNu(const ShellRadii& shell, const ScatteringTableSize& size,
                                              double muSMin, double r, double mu, double muS, double nu,
                                              bool rayIntersectsGround) {
  const ScatterGeometry g(shell, size, muSMin);
  return {ScatterGeometry::uNu(nu), g.uMuS(muS), g.uMu(r, mu, rayIntersectsGround), g.uR(r)};
}

ScatteringPoint rMuMuSNuFromScatteringCoords(const ShellRadii& shell, const ScatteringTableSize& size,
                                             double muSMin, const ScatteringCoords& c) {
  const ScatterGeometry g(shell, size, muSMin);
  ScatteringPoint p;
  p.r = g.rFromU(c.uR);
  p.mu = g.muFromU(p.r, c.uMu, p.rayIntersectsGround);
  p.muS = g.muSFromU(c.uMuS);
  p.nu = clampCosine(2.0 * c.uNu - 1.0);
  return p;
}

ScatteringPoint scatteringTexelPoint(const ShellRadii& shell, const ScatteringTableSize& size, double muSMin,
                                     int x, int y, int z) {
  return ScatterGeometry(shell, size, muSMin).texel(x, y, z);
}

// ---- precompute ------------------------------------------------------------------------------

int densityDirectionsFor(const Atmosphere& atmosphere) {
  double halfWidthRad = kPi / 2;  // of the narrowest forward peak
  for (const Component& c : atmosphere.components) {
    if (!c.scatters()) continue;
    for (std::size_t l = 0; l < atmosphere.wavelengthsNm.size(); ++l) {
      const PhaseFunction& p = c.phase(l);
      const double forward = p(1.0);
      for (double deg = 0.05; deg < halfWidthRad * 180.0 / kPi; deg += 0.05)
        if (p(std::cos(deg * kPi / 180.0)) <= 0.5 * forward) {
          halfWidthRad = deg * kPi / 180.0;
          break;
        }
    }
  }
  const int n = static_cast<int>(std::ceil(kPi / (1.5 * halfWidthRad) / 8.0)) * 8;
  return std::clamp(n, kMinDensityDirections, 64);
}

AtmosphereTables precompute(const Atmosphere& atmosphere, const PrecomputeOptions& optionsIn,
                            const PrecomputeProgress& progress) {
  if (const std::string e = optionsIn.validate(); !e.empty()) throw std::invalid_argument("PrecomputeOptions: " + e);
  if (const std::string e = atmosphere.validate(); !e.empty()) throw std::invalid_argument("Atmosphere: " + e);
  PrecomputeOptions options = optionsIn;
  if (options.sphereSamples == 0) options.sphereSamples = densityDirectionsFor(atmosphere);
  const int nl = static_cast<int>(atmosphere.wavelengthsNm.size());
  if (nl == 0) throw std::invalid_argument("Atmosphere: no wavelengths");
  const auto t0 = std::chrono::steady_clock::now();

  AtmosphereTables tables;
  tables.options = options;
  tables.bottomRadiusM = atmosphere.bottomRadiusM;
  tables.topRadiusM = atmosphere.topRadiusM;
  tables.wavelengthsNm = atmosphere.wavelengthsNm;
  for (const Component& c : atmosphere.components)
    if (c.scatters()) tables.scatteringComponents.push_back(c.name);

  const int batch = options.wavelengthBatch > 0 ? std::min(options.wavelengthBatch, nl) : nl;
  const int batches = (nl + batch - 1) / batch;
  std::map<std::string, double> timings;
  std::vector<std::string> order;
  const int orders = options.orders;
  const double weight = 1.0 + 0.05 + 0.3 * (options.multipleScatteringSamples != options.singleScatteringSamples ? 2 : 1) +
                        1.0 + (orders - 1) * (2.0 + 0.1 + 1.0);
  const int W = options.scatteringNu * options.scatteringMuS;
  tables.singleScattering.resize(tables.scatteringComponents.size());
  for (Table3D& T : tables.singleScattering) T.resize(W, options.scatteringMu, options.scatteringR, nl);
  tables.multipleScattering.resize(W, options.scatteringMu, options.scatteringR, nl);
  for (int bi = 0; bi < batches; ++bi) {
    std::vector<int> ls;
    for (int l = bi * batch; l < std::min(nl, (bi + 1) * batch); ++l) ls.push_back(l);
    Runner runner(progress, options.threads, static_cast<double>(bi) / batches, static_cast<double>(bi + 1) / batches);
    runner.setStages(weight);
    BatchResult r = computeBatch(batches == 1 ? atmosphere : subAtmosphere(atmosphere, ls), options, runner,
                                 tables.singleScattering, tables.multipleScattering, ls.front());
    if (batches == 1) {
      tables.transmittance = std::move(r.transmittance);
      tables.directIrradiance = std::move(r.directIrradiance);
      tables.irradiance = std::move(r.irradiance);
      tables.orderMeanRadiance = std::move(r.orderMean);
    } else {
      if (bi == 0) {
        auto size2 = [&](Table2D& d, const Table2D& s) { d.resize(s.width, s.height, nl); };
        size2(tables.transmittance, r.transmittance);
        size2(tables.directIrradiance, r.directIrradiance);
        size2(tables.irradiance, r.irradiance);
        tables.orderMeanRadiance.assign(r.orderMean.size(), std::vector<double>(nl, 0.0));
      }
      copyChannels2D(r.transmittance, tables.transmittance, ls);
      copyChannels2D(r.directIrradiance, tables.directIrradiance, ls);
      copyChannels2D(r.irradiance, tables.irradiance, ls);
      for (std::size_t k = 0; k < r.orderMean.size(); ++k)
        for (std::size_t i = 0; i < ls.size(); ++i) tables.orderMeanRadiance[k][ls[i]] = r.orderMean[k][i];
    }
    for (const std::string& s : runner.order) {
      if (std::find(order.begin(), order.end(), s) == order.end()) order.push_back(s);
      timings[s] += runner.timings[s];
    }
  }
  for (const std::string& s : order) tables.timings.push_back({s, timings[s]});
  tables.timings.push_back({"total", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()});
  if (progress && !progress(1.0, "done")) throw PrecomputeCancelled();
  return tables;
}

// ---- lookups ---------------------------------------------------------------------------------

void transmittanceToTop(const AtmosphereTables& tables, double r, double mu, double* out) {
  lookupTransmittance(tables.transmittance, tables.shell(), r, mu, out);
}

std::vector<double> transmittanceToTop(const AtmosphereTables& tables, double r, double mu) {
  std::vector<double> v(tables.wavelengthCount());
  transmittanceToTop(tables, r, mu, v.data());
  return v;
}

std::vector<double> lookupScattering(const AtmosphereTables& tables, const Table3D& table, double r, double mu,
                                     double muS, double nu, bool rayIntersectsGround) {
  const ScatterGeometry g = geometryOf(tables);
  std::vector<double> v(table.channels, 0.0);
  accumulate4(table, rMuCell(g, r, mu, rayIntersectsGround), sNuCell(g, muS, nu), 1.0, v.data());
  return v;
}

std::vector<double> transmittanceAlong(const AtmosphereTables& tables, double r, double mu, double d,
                                       bool rayIntersectsGround, bool endsOnGround) {
  const double b = tables.bottomRadiusM;
  const double rd = endsOnGround ? b : std::clamp(std::sqrt(d * d + 2.0 * r * mu * d + r * r), b, tables.topRadiusM);
  const double mud = clampCosine((r * mu + d) / rd);
  const std::vector<double> a = rayIntersectsGround ? transmittanceToTop(tables, rd, -mud) : transmittanceToTop(tables, r, mu);
  const std::vector<double> c = rayIntersectsGround ? transmittanceToTop(tables, r, -mu) : transmittanceToTop(tables, rd, mud);
  std::vector<double> out(a.size());
  for (std::size_t l = 0; l < a.size(); ++l) out[l] = std::min(a[l] / std::max(c[l], 1e-300), 1.0);
  return out;
}

namespace {

/// skyRadiance's table lookups at a Sun within the tables (muS >= muSMin).
std::vector<double> tableRadiance(const AtmosphereTables& tables, const Atmosphere& atmosphere, double r, double mu,
                                  double muS, double nu, bool ground) {
  std::vector<double> L = lookupScattering(tables, tables.multipleScattering, r, mu, muS, nu, ground);
  for (std::size_t q = 0; q < tables.singleScattering.size(); ++q) {
    const Component& c = atmosphere.component(tables.scatteringComponents[q]);
    const std::vector<double> S = lookupScattering(tables, tables.singleScattering[q], r, mu, muS, nu, ground);
    for (std::size_t l = 0; l < L.size(); ++l) L[l] += S[l] * c.phase(l)(nu);
  }
  return L;
}

}  // namespace

std::vector<double> skyRadiance(const AtmosphereTables& tables, const Atmosphere& atmosphere, double r, double mu,
                                double muS, double nu, const std::vector<double>& solarIrradiance) {
  const int nl = static_cast<int>(tables.wavelengthCount());
  const double b = tables.bottomRadiusM, muSMin = tables.options.muSMin;
  const bool ground = rayIntersectsGround(b, r, mu);
  std::vector<double> L;
  if (muS >= muSMin) {
    L = tableRadiance(tables, atmosphere, r, mu, muS, nu, ground);
  } else {
    const double end = ground ? distanceToBottomBoundaryM(b, r, mu) : distanceToTopBoundaryM(tables.topRadiusM, r, mu);
    const double d = distanceToSunCosineM(r, mu, muS, nu, muSMin);
    if (!(d < end)) return std::vector<double>(nl, 0.0);
    const double rd = std::clamp(std::sqrt(d * d + 2.0 * r * mu * d + r * r), b, tables.topRadiusM);
    L = tableRadiance(tables, atmosphere, rd, clampCosine((r * mu + d) / rd), muSMin, nu, ground);
    const std::vector<double> T = transmittanceAlong(tables, r, mu, d, ground);
    for (int l = 0; l < nl; ++l) L[l] *= T[l];
  }
  if (!solarIrradiance.empty())
    for (int l = 0; l < nl; ++l) L[l] *= solarIrradiance.at(l);
  return L;
}

std::vector<double> indirectIrradiance(const AtmosphereTables& tables, double r, double muS) {
  std::vector<double> v(tables.wavelengthCount(), 0.0);
  if (muS < tables.options.muSMin) return v;
  lookupIrradiance(tables.irradiance, tables.shell(), r, muS, v.data());
  return v;
}

double sunDiscCosine(double muS, double alphaRad) {
  if (muS < -alphaRad) return 0.0;
  if (muS > alphaRad) return muS;
  return (muS + alphaRad) * (muS + alphaRad) / (4.0 * alphaRad);
}

std::vector<double> directIrradiance(const AtmosphereTables& tables, double r, double muS) {
  std::vector<double> v(tables.wavelengthCount());
  directIrradianceAt(tables.transmittance, tables.shell(), tables.options.sunAngularRadiusRad, r, muS, v.data());
  return v;
}

}  // namespace umbra::atmosphere
