#pragma once
// The 4D parametrisation of the scattering tables (Bruneton 2017) and the CPU lookups that
// twin glsl/Atmosphere.glsl, inline for the precomputation's inner loops: a texel's
// coordinates and back, the (r, mu) and (mu_s, nu) cells of a 4D lookup, the bilinear 2D
// lookups, the Sun's direct irradiance and its visibility over the horizon.
#include "Precompute.hpp"
#include "TextureCoords.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace umbra::atmosphere::stages {

constexpr double kPi = 3.14159265358979323846;

/// Bruneton's GetTextureCoordFromUnitRange, inline for the lookups' hot path.
inline double texCoord(double x, int n) { return (0.5 + x * (n - 1.0)) / n; }

inline double smoothstep(double e0, double e1, double x) {
  const double t = std::min(std::max((x - e0) / (e1 - e0), 0.0), 1.0);
  const double step = x < e0 ? 0.0 : 1.0;
  return e1 > e0 ? t * t * (3.0 - 2.0 * t) : step;
}

[[noreturn]] inline void throwNonFiniteLookup() {
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

// ---- the 4D parametrisation ----------------------------------------------------------------

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
    p.r = rFromU((z + 0.5) / R);
    p.mu = muFromU(p.r, (y + 0.5) / MU, p.rayIntersectsGround);
    p.muS = muSFromU((x % MUS + 0.5) / MUS);
    p.nu = texelNu(x / MUS, p.mu, p.muS);
    return p;
  }
  /// The nu of the texels of nu column k, within what mu and mu_s allow.
  double texelNu(int k, double mu, double muS) const {
    const double nu = clampCosine(2.0 * k / (NU - 1) - 1.0);
    const double s = std::sqrt(std::max(0.0, (1.0 - mu * mu) * (1.0 - muS * muS)));
    return std::clamp(nu, mu * muS - s, mu * muS + s);
  }
};

/// ScatterGeometry::texel with its inverse parametrisations tabulated per axis (r per z, mu
/// and the ground per (y, z), mu_s per column): the same points, for the stages that visit
/// every texel once an order.
struct TexelPoints {
  explicit TexelPoints(const ScatterGeometry& geometry) : g(geometry) {
    for (int z = 0; z < g.R; ++z) {
      const ScatteringPoint p = g.texel(0, 0, z);
      r.push_back(p.r);
      for (int y = 0; y < g.MU; ++y) {
        const ScatteringPoint q = g.texel(0, y, z);
        mu.push_back(q.mu), ground.push_back(q.rayIntersectsGround);
      }
    }
    for (int i = 0; i < g.MUS; ++i) muS.push_back(g.texel(i, 0, 0).muS);
  }
  ScatteringPoint operator()(int x, int y, int z) const {
    ScatteringPoint p;
    const std::size_t yz = static_cast<std::size_t>(z) * g.MU + y;
    p.r = r[z], p.mu = mu[yz], p.rayIntersectsGround = ground[yz], p.muS = muS[x % g.MUS];
    p.nu = g.texelNu(x / g.MUS, p.mu, p.muS);
    return p;
  }

private:
  ScatterGeometry g;
  std::vector<double> r, mu, muS;
  std::vector<char> ground;
};

inline ScatterGeometry geometryOf(const AtmosphereTables& t) {
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

/// out[0..n) += scale * table(r, mu, mu_s, nu) for the channels l0 .. l0 + n (n < 0: all).
template <class Value>
inline void accumulate4(const BasicTable3D<Value>& T, const RMuCell& a, const SNuCell& s, double scale, double* out,
                        int l0 = 0, int n = -1) {
  const int nc = T.channels, nr = n < 0 ? nc : n;
  for (int dz = 0; dz < 2; ++dz) {
    const double wz = (dz ? a.wz : 1.0 - a.wz) * scale;
    if (wz == 0.0) continue;
    for (int dy = 0; dy < 2; ++dy) {
      const double wzy = wz * (dy ? a.wy : 1.0 - a.wy);
      if (wzy == 0.0) continue;
      const Value* row = T.at(0, a.iy + dy, a.iz + dz) + l0;
      const Value* p00 = row + static_cast<std::size_t>(s.x00) * nc;
      const Value* p01 = row + static_cast<std::size_t>(s.x01) * nc;
      const Value* p10 = row + static_cast<std::size_t>(s.x10) * nc;
      const Value* p11 = row + static_cast<std::size_t>(s.x11) * nc;
      const double w00 = wzy * s.w00, w01 = wzy * s.w01, w10 = wzy * s.w10, w11 = wzy * s.w11;
      if (s.w10 == 0.0 && s.w11 == 0.0) {
        for (int l = 0; l < nr; ++l) out[l] += w00 * p00[l] + w01 * p01[l];
      } else {
        for (int l = 0; l < nr; ++l) out[l] += w00 * p00[l] + w01 * p01[l] + w10 * p10[l] + w11 * p11[l];
      }
    }
  }
}

/// Where unit coordinate u falls among n texels (centres on the ends): between i and i + 1,
/// weight w on i + 1.
inline void unitCell(double u, int n, int& i, double& w) {
  const double f = std::clamp(u, 0.0, 1.0) * (n - 1);
  i = std::min(static_cast<int>(f), n - 2);
  w = f - i;
}

/// Bilinear lookup in a 2D table of unit-range coordinates (texel centres on the ends).
inline void bilinearUnit(const Table2D& T, double xu, double yu, double* out) {
  int ix, iy;
  double wx, wy;
  unitCell(xu, T.width, ix, wx);
  unitCell(yu, T.height, iy, wy);
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

/// The irradiance table at (r, mu_s): bilinear, except across a mu_s cell wholly below the
/// horizon (its upper node at mu_s <= 0), which is geometric between positive nodes. After
/// sunset the ground's light falls by orders of magnitude within a cell, nearly
/// exponentially, and a straight line across the cell overestimates it (64 cells over
/// [-1, 1]: +44..64 % at 5.6 deg down; geometric: -4..+4 %). The GLSL twin is
/// umbraAtmIndirectIrradiance.
inline void lookupIrradiance(const Table2D& T, const ShellRadii& shell, double r, double muS, double* out) {
  int ix, iy;
  double wx, wy;
  unitCell(0.5 * (muS + 1.0), T.width, ix, wx);
  unitCell((r - shell.bottomRadiusM) / (shell.topRadiusM - shell.bottomRadiusM), T.height, iy, wy);
  const bool belowHorizon = 2.0 * (ix + 1) <= T.width - 1.0;  // the upper node's mu_s <= 0
  auto along = [&](int y, int l) {
    const double a = T.at(ix, y)[l], b = T.at(ix + 1, y)[l];
    return belowHorizon && a > 0.0 && b > 0.0 ? a * std::pow(b / a, wx) : a + wx * (b - a);
  };
  for (int l = 0; l < T.channels; ++l) out[l] = (1.0 - wy) * along(iy, l) + wy * along(iy + 1, l);
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

}  // namespace umbra::atmosphere::stages
