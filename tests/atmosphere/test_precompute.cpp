// Bruneton 2017 precomputation (Precompute.hpp): closed-form and brute-force checks of
// transmittance, single and multiple scattering, the 4D parametrisation, robustness at
// the boundaries, and refraction. Small tables keep the suite fast.
#include "ModelTestSupport.hpp"
#include "Precompute.hpp"
#include "PrecomputeTestSupport.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace umbra::atmosphere {
namespace detail {
// The density's lobe kernel (atmosphere/precompute/Kernels.cpp): the plain loop and the one chosen at run time
// (the AVX-512 reciprocal square root where the CPU has it).
void lobeValuesBaseline(double A, double B, double g, const double* c, double* p, int n);
void lobeValuesDispatched(double A, double B, double g, const double* c, double* p, int n);
} // namespace detail

namespace {

using umbra::test::kPi;

PrecomputeOptions smallOptions() { return umbra::test::smallPrecomputeOptions(); }

Component makeComponent(const std::string& name, DensityProfile density, double scattering, double absorption,
                        PhaseFunction phase, std::size_t nl) {
  Component c;
  c.name = name;
  c.density = density;
  c.scatteringPerM.assign(nl, scattering);
  c.absorptionPerM.assign(nl, absorption);
  c.phases.assign(nl, phase);
  return c;
}

Atmosphere shellAtmosphere(std::vector<Component> components, double albedo = 0.0, std::size_t nl = 1) {
  Atmosphere a;
  a.name = "test";
  a.bottomRadiusM = 6360e3;
  a.topRadiusM = 6420e3;
  for (std::size_t i = 0; i < nl; ++i) a.wavelengthsNm.push_back(550.0 + 50.0 * i);
  a.groundAlbedo.assign(nl, albedo);
  a.components = std::move(components);
  a.refractivityFollows.clear();
  return a;
}

/// 0, the distances in (0, d) where a straight ray from (r, mu) crosses an altitude at
/// which a component's density or its slope jumps (Profiles.hpp, kinksM), and d: the
/// pieces a quadrature integrates smoothly.
std::vector<double> kinkSplits(const Atmosphere& a, double r, double mu, double d) {
  std::vector<double> at{0.0, d};
  for (const Component& c : a.components)
    for (double h : c.density.kinksM()) {
      const double R = a.bottomRadiusM + h, disc = r * r * (mu * mu - 1.0) + R * R;
      if (!(disc >= 0.0)) continue;
      for (double s : {-r * mu - std::sqrt(disc), -r * mu + std::sqrt(disc)})
        if (s > 0.0 && s < d) at.push_back(s);
    }
  std::sort(at.begin(), at.end());
  return at;
}

/// The pieces a rule of n points shares out along a ray: between kinkSplits, each with a
/// share of n by its length (even, at least 2).
std::vector<std::pair<double, int>> rayPieces(const Atmosphere& a, double r, double mu, double d, int n) {
  const std::vector<double> at = kinkSplits(a, r, mu, d);
  std::vector<std::pair<double, int>> pieces;  // (start, count); the last start is d
  for (std::size_t k = 0; k + 1 < at.size(); ++k) {
    const int m = std::max(2, 2 * static_cast<int>(std::lround(0.5 * n * (at[k + 1] - at[k]) / d)));
    pieces.push_back({at[k], m});
  }
  pieces.push_back({d, 0});
  return pieces;
}

/// Independent optical depth along a straight ray, Gauss-Kronrod per component.
std::vector<double> opticalDepth(const Atmosphere& a, double r, double mu, double d) {
  std::vector<double> tau(a.wavelengthsNm.size(), 0.0);
  for (const Component& c : a.components) {
    const auto rho = [&](double s) {
      const double h = std::sqrt(s * s + 2.0 * r * mu * s + r * r) - a.bottomRadiusM;
      return c.density.at(std::clamp(h, 0.0, a.topRadiusM - a.bottomRadiusM));
    };
    // split at the lowest point to help the quadrature
    const double sLow = std::clamp(-r * mu, 0.0, d);
    double col = 0.0;
    if (sLow > 0.0) col += umbra::test::integrate(rho, 0.0, sLow);
    if (d > sLow) col += umbra::test::integrate(rho, sLow, d);
    for (std::size_t l = 0; l < tau.size(); ++l) tau[l] += col * c.extinctionPerM(l);
  }
  return tau;
}

template <class Values>
bool allFiniteNonNegative(const Values& v, std::string& where, const std::string& name) {
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]) || v[i] < 0.0) {
      where = name + "[" + std::to_string(i) + "] = " + std::to_string(v[i]);
      return false;
    }
  return true;
}

void expectTablesSane(const AtmosphereTables& t) {
  std::string where;
  EXPECT_TRUE(allFiniteNonNegative(t.transmittance.values, where, "transmittance")) << where;
  EXPECT_TRUE(allFiniteNonNegative(t.directIrradiance.values, where, "directIrradiance")) << where;
  EXPECT_TRUE(allFiniteNonNegative(t.irradiance.values, where, "irradiance")) << where;
  EXPECT_TRUE(allFiniteNonNegative(t.multipleScattering.values, where, "multiple")) << where;
  for (const FloatTable3D& s : t.singleScattering) EXPECT_TRUE(allFiniteNonNegative(s.values, where, "single")) << where;
  for (double v : t.transmittance.values) EXPECT_LE(v, 1.0);
}

// ---- the parametrisation ----------------------------------------------------------------------

TEST(Precompute, LobeKernelDispatchedMatchesTheClosedForm) {
  // 37 cosines: whole 8-lane blocks and a scalar tail; g from forward to backward lobes;
  // against A (1 + B c^2) / (1 + g^2 - 2 g c)^(3/2) written out here.
  std::vector<double> c(37);
  for (std::size_t j = 0; j < c.size(); ++j) c[j] = -1.0 + 2.0 * j / (c.size() - 1);
  for (double g : {-0.76, 0.0, 0.3, 0.8, 0.99}) {
    std::vector<double> plain(c.size()), fast(c.size());
    detail::lobeValuesBaseline(0.07, 0.5, g, c.data(), plain.data(), static_cast<int>(c.size()));
    detail::lobeValuesDispatched(0.07, 0.5, g, c.data(), fast.data(), static_cast<int>(c.size()));
    for (std::size_t j = 0; j < c.size(); ++j) {
      const double expected = 0.07 * (1.0 + 0.5 * c[j] * c[j]) / std::pow(1.0 + g * g - 2.0 * g * c[j], 1.5);
      EXPECT_NEAR(plain[j], expected, 1e-13 * expected) << g << " " << c[j];
      EXPECT_NEAR(fast[j], expected, 1e-13 * expected) << g << " " << c[j];
    }
  }
}

TEST(Precompute, ScatteringCoordsRoundTripAtTexelCentres) {
  const ShellRadii shell{6360e3, 6420e3};
  const ScatteringTableSize size{32, 128, 32, 8};
  const double muSMin = std::cos(102.0 * kPi / 180.0);
  int checked = 0;
  for (int z = 0; z < size.r; z += 3)
    for (int y = 0; y < size.mu; y += 5)
      for (int i = 0; i < size.muS; i += 3) {
        const ScatteringPoint p = scatteringTexelPoint(shell, size, muSMin, i, y, z);
        const ScatteringCoords c =
            scatteringCoordsFromRMuMuSNu(shell, size, muSMin, p.r, p.mu, p.muS, p.nu, p.rayIntersectsGround);
        EXPECT_NEAR(c.uR, (z + 0.5) / size.r, 1e-9);
        // On the ground (z = 0) every ground ray has d = d_min = d_max: one point.
        if (z > 0 || y >= size.mu / 2) {
          EXPECT_NEAR(c.uMu, (y + 0.5) / size.mu, 1e-7) << "y " << y << " z " << z;
        }
        EXPECT_NEAR(c.uMuS, (i + 0.5) / size.muS, 1e-9);
        EXPECT_EQ(p.rayIntersectsGround, y < size.mu / 2);
        ++checked;
      }
  EXPECT_GT(checked, 1000);
  // The ends: zenith, horizon, lowest and highest sun.
  const ScatteringPoint top = scatteringTexelPoint(shell, size, muSMin, size.muS - 1, size.mu / 2, 5);
  EXPECT_DOUBLE_EQ(top.mu, 1.0);
  EXPECT_DOUBLE_EQ(top.muS, 1.0);
  const ScatteringPoint low = scatteringTexelPoint(shell, size, muSMin, 0, size.mu - 1, 5);
  EXPECT_NEAR(low.mu, horizonCosine(shell.bottomRadiusM, low.r), 1e-12);
  EXPECT_NEAR(low.muS, muSMin, 1e-12);
}

// ---- transmittance ---------------------------------------------------------------------------

TEST(Precompute, VerticalTransmittanceIsExpOfVerticalOpticalDepth) {
  const Atmosphere earth = loadAtmosphere("earth", {680.0, 550.0, 440.0});
  PrecomputeOptions o = smallOptions();
  o.transmittanceWidth = 256;
  o.transmittanceHeight = 64;
  o.orders = 1;
  const AtmosphereTables t = precompute(earth, o);
  const double b = earth.bottomRadiusM, top = earth.topRadiusM;
  double worstTexel = 0.0, worstLookup = 0.0;
  for (int y = 0; y < o.transmittanceHeight; ++y) {
    const RadiusMu rm = rMuAtTexel(t.shell(), 0, y, o.transmittanceWidth, o.transmittanceHeight);
    ASSERT_DOUBLE_EQ(rm.mu, 1.0);
    const std::vector<double> tau = earth.verticalOpticalDepth(rm.radiusM - b, top - b);
    for (int l = 0; l < 3; ++l)
      worstTexel = std::max(worstTexel, std::abs(t.transmittance.at(0, y)[l] / std::exp(-tau[l]) - 1.0));
  }
  for (double h = 0.0; h <= 100e3; h += 1234.5) {  // between rows: the table's resolution
    const std::vector<double> T = transmittanceToTop(t, b + h, 1.0);
    const std::vector<double> tau = earth.verticalOpticalDepth(h, top - b);
    for (int l = 0; l < 3; ++l) worstLookup = std::max(worstLookup, std::abs(T[l] / std::exp(-tau[l]) - 1.0));
  }
  std::printf("vertical transmittance: worst relative error %.3g at texels, %.3g by lookup\n", worstTexel, worstLookup);
  // Measured 1.5e-6 and 1.0e-4: the columns take 10 Simpson intervals across each 500 m
  // blending zone of the boundary layer, and the rows are 1.6 km apart there.
  EXPECT_LT(worstTexel, 5e-6);
  EXPECT_LT(worstLookup, 2e-4);
}

TEST(Precompute, HorizontalTransmittanceMatchesHighSampleIntegral) {
  DensityProfile air = DensityProfile::exponential(8000.0);
  const Atmosphere a = shellAtmosphere({makeComponent("air", air, 1.2e-5, 1e-6, PhaseFunction::rayleigh(), 1)});
  PrecomputeOptions o = smallOptions();
  o.transmittanceWidth = 256;
  o.transmittanceHeight = 64;
  o.orders = 1;
  const AtmosphereTables t = precompute(a, o);
  double worst = 0.0;
  for (int y : {0, 5, 20, 40, 63}) {
    for (int x : {255, 254, 200, 128}) {  // the horizon and near it
      const RadiusMu rm = rMuAtTexel(t.shell(), x, y, 256, 64);
      const double d = distanceToTopBoundaryM(a.topRadiusM, rm.radiusM, rm.mu);
      const double reference = std::exp(-opticalDepth(a, rm.radiusM, rm.mu, d)[0]);
      const double T = t.transmittance.at(x, y)[0];
      worst = std::max(worst, std::abs(T - reference) / std::max(reference, 1e-300));
      EXPECT_NEAR(T, reference, 1e-7 * reference + 1e-300) << x << " " << y;
    }
  }
  // A horizontal ray 5 km up, between texels.
  const double r = a.bottomRadiusM + 5e3;
  const double reference =
      std::exp(-opticalDepth(a, r, 0.0, distanceToTopBoundaryM(a.topRadiusM, r, 0.0))[0]);
  const double T = transmittanceToTop(t, r, 0.0)[0];
  std::printf("horizontal transmittance: worst texel relative error %.3g; 5 km, mu = 0: %.6g vs %.6g\n", worst, T,
              reference);
  EXPECT_NEAR(T / reference, 1.0, 2e-2);
}

TEST(Precompute, OzoneOnlyTentTransmittance) {
  const Atmosphere a = shellAtmosphere(
      {makeComponent("ozone", DensityProfile::tent(25e3, 15e3), 0.0, 2e-6, PhaseFunction::isotropic(), 1)});
  PrecomputeOptions o = smallOptions();
  o.orders = 3;
  const AtmosphereTables t = precompute(a, o);
  EXPECT_TRUE(t.singleScattering.empty());
  for (int y = 0; y < o.transmittanceHeight; ++y) {
    const RadiusMu rm = rMuAtTexel(t.shell(), 0, y, o.transmittanceWidth, o.transmittanceHeight);
    const double tau = a.verticalOpticalDepth(rm.radiusM - a.bottomRadiusM, a.thicknessM())[0];
    EXPECT_NEAR(t.transmittance.at(0, y)[0], std::exp(-tau), 1e-10) << y;
    for (int x : {10, 40, 63}) {
      const RadiusMu s = rMuAtTexel(t.shell(), x, y, o.transmittanceWidth, o.transmittanceHeight);
      const double d = distanceToTopBoundaryM(a.topRadiusM, s.radiusM, s.mu);
      EXPECT_NEAR(t.transmittance.at(x, y)[0], std::exp(-opticalDepth(a, s.radiusM, s.mu, d)[0]), 1e-9) << x << " " << y;
    }
  }
  // 30 Dobson-like layer: vertical optical depth from the ground = 2e-6 * 15 km = 0.03.
  EXPECT_NEAR(t.transmittance.at(0, 0)[0], std::exp(-0.03), 1e-9);
  // Absorption only: no scattering of any order, no indirect irradiance.
  for (float v : t.multipleScattering.values) EXPECT_EQ(v, 0.0f);
  for (double v : t.irradiance.values) EXPECT_EQ(v, 0.0);
  for (const auto& m : t.orderMeanRadiance) EXPECT_EQ(m[0], 0.0);
}

// ---- single scattering -----------------------------------------------------------------------

TEST(Precompute, SingleScatteringOpticallyThinLimit) {
  // Constant density (huge scale height), beta_s = 1e-9 / m: tau < 1e-3 on any path, so
  // S = beta_s * path length within 0.2 %.
  const double beta = 1e-9;
  const Atmosphere a = shellAtmosphere(
      {makeComponent("thin", DensityProfile::exponential(1e13), beta, 0.0, PhaseFunction::rayleigh(), 1)});
  PrecomputeOptions o = smallOptions();
  o.orders = 1;
  const AtmosphereTables t = precompute(a, o);
  const ScatteringTableSize size{o.scatteringR, o.scatteringMu, o.scatteringMuS, o.scatteringNu};
  const ShellRadii shell = t.shell();
  int checked = 0;
  double worst = 0.0;
  for (int z = 0; z < o.scatteringR; ++z)
    for (int y = 0; y < o.scatteringMu; ++y)
      for (int x = 0; x < o.scatteringNu * o.scatteringMuS; ++x) {
        const ScatteringPoint p = scatteringTexelPoint(shell, size, o.muSMin, x, y, z);
        const double L = p.rayIntersectsGround ? distanceToBottomBoundaryM(shell.bottomRadiusM, p.r, p.mu)
                                               : distanceToTopBoundaryM(shell.topRadiusM, p.r, p.mu);
        // sun above the horizon all along the ray: at the start and the end
        const double rEnd = std::sqrt(L * L + 2 * p.r * p.mu * L + p.r * p.r);
        const double muSEnd = (p.r * p.muS + L * p.nu) / rEnd;
        if (p.muS < 0.1 || muSEnd < 0.1 || L < 1.0) continue;
        const double S = t.singleScattering[0].at(x, y, z)[0];
        worst = std::max(worst, std::abs(S / (beta * L) - 1.0));
        EXPECT_NEAR(S, beta * L, 2e-3 * beta * L) << x << " " << y << " " << z;
        ++checked;
      }
  EXPECT_GT(checked, 200);
  // The radiance by lookup for a horizontal view from 1 km up with the sun at 60 deg
  // elevation in the view's vertical plane: beta P(theta) L.
  const double r = shell.bottomRadiusM + 1e3, mu = 0.0, muS = 0.5, nu = std::sqrt(0.75);
  const double L = distanceToTopBoundaryM(shell.topRadiusM, r, mu);
  const double expected = beta * PhaseFunction::rayleigh()(nu) * L;
  const double got = skyRadiance(t, a, r, mu, muS, nu)[0];
  std::printf("thin layer: worst texel error %.3g over %d texels; lookup %.6g vs %.6g\n", worst, checked, got, expected);
  EXPECT_NEAR(got, expected, 0.03 * expected);
}

// Bruneton's thin haze (earth-bruneton). In the default sky's haze the small tables' view
// rays (50 samples) are 3.5-4.5 % under the brute force for views along the ground, where
// the haze's horizontal optical depth (~0.6 per 10 km) puts the light in the first samples.
TEST(Precompute, SingleScatteringMatchesBruteForceIntegral) {
  const Atmosphere earth = loadAtmosphere("earth-bruneton", {680.0, 550.0, 440.0});
  PrecomputeOptions o = smallOptions();
  o.transmittanceWidth = 256;
  o.transmittanceHeight = 64;
  o.orders = 1;
  const AtmosphereTables t = precompute(earth, o);
  const ShellRadii shell = t.shell();
  const ScatteringTableSize size{o.scatteringR, o.scatteringMu, o.scatteringMuS, o.scatteringNu};
  const double b = shell.bottomRadiusM, top = shell.topRadiusM;
  double worst = 0.0;
  int checked = 0;
  // Texels with the sun well above the horizon, sky and ground rays.
  for (int z : {0, 2, 5}) {
    for (int y : {3, 12, 17, 20, 28}) {
      for (int x : {o.scatteringMuS - 1, o.scatteringMuS + 5, 2 * o.scatteringMuS + 6, 3 * o.scatteringMuS - 3}) {
        const ScatteringPoint p = scatteringTexelPoint(shell, size, o.muSMin, x, y, z);
        if (p.muS < 0.3) continue;
        const double L = p.rayIntersectsGround ? distanceToBottomBoundaryM(b, p.r, p.mu)
                                               : distanceToTopBoundaryM(top, p.r, p.mu);
        // Simpson between the crossings of the profiles' kinks (the boundary layer's blending
        // zones, the stratosphere's ramps), about 200 intervals in all; the optical depths
        // once per node for every component and wavelength.
        const std::size_t nq = t.scatteringComponents.size();
        std::vector<double> ref(nq * 3, 0.0);
        const auto pieces = rayPieces(earth, p.r, p.mu, L, 200);
        for (std::size_t k = 0; k + 1 < pieces.size(); ++k) {
          const int n = pieces[k].second;
          const double a0 = pieces[k].first, h = (pieces[k + 1].first - a0) / n;
          for (int i = 0; i <= n; ++i) {
            const double d = a0 + h * i, w = (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0)) * h / 3.0;
            const double rd = std::sqrt(d * d + 2 * p.r * p.mu * d + p.r * p.r);
            const double muSd = (p.r * p.muS + d * p.nu) / rd;
            const std::vector<double> tauView = opticalDepth(earth, p.r, p.mu, d);
            const std::vector<double> tauSun = opticalDepth(earth, rd, muSd, distanceToTopBoundaryM(top, rd, muSd));
            for (std::size_t q = 0; q < nq; ++q) {
              const Component& c = earth.component(t.scatteringComponents[q]);
              for (int l = 0; l < 3; ++l)
                ref[q * 3 + l] += w * std::exp(-tauView[l] - tauSun[l]) * c.density.at(rd - b) * c.scatteringPerM[l];
            }
          }
        }
        for (std::size_t q = 0; q < nq; ++q) {
          for (int l = 0; l < 3; ++l) {
            const double want = ref[q * 3 + l], got = t.singleScattering[q].at(x, y, z)[l];
            worst = std::max(worst, std::abs(got / want - 1.0));
            EXPECT_NEAR(got, want, 0.01 * want) << t.scatteringComponents[q] << " l " << l << " texel " << x << " " << y
                                                << " " << z;
            ++checked;
          }
        }
      }
    }
  }
  std::printf("single scattering vs brute force: worst relative error %.3g over %d values\n", worst, checked);
  EXPECT_GT(checked, 50);
}

/// Brute-force optical depth per wavelength along the straight ray (r0, mu0) over distance
/// d: the midpoint rule over about n pieces, split where the profiles jump.
std::vector<double> bruteForceOpticalDepth(const Atmosphere& a, double r0, double mu0, double d, int n = 400) {
  const double b = a.bottomRadiusM, top = a.topRadiusM;
  std::vector<double> tau(a.wavelengthsNm.size(), 0.0);
  if (!(d > 0.0)) return tau;
  const auto pieces = rayPieces(a, r0, mu0, d, n);
  for (std::size_t k = 0; k + 1 < pieces.size(); ++k) {
    const double s0 = pieces[k].first, len = pieces[k + 1].first - s0;
    const int m = pieces[k].second;
    for (int i = 0; i < m; ++i) {
      const double s = s0 + len * (i + 0.5) / m;
      const double h = std::clamp(std::sqrt(s * s + 2.0 * r0 * mu0 * s + r0 * r0) - b, 0.0, top - b);
      for (const Component& c : a.components)
        for (std::size_t l = 0; l < tau.size(); ++l) tau[l] += c.density.at(h) * len / m * c.extinctionPerM(l);
    }
  }
  return tau;
}

/// Brute-force single scattering along the straight ray (r, mu) to its end (the ground or
/// the top), the Sun's ray blocked by the ground: Simpson over about `steps`, split where
/// the profiles jump, optical depths by the midpoint rule over 400 pieces. Per wavelength,
/// phase included.
std::vector<double> bruteForceSingleScattering(const Atmosphere& a, double r, double mu, double muS, double nu,
                                               int steps = 400) {
  const double b = a.bottomRadiusM, top = a.topRadiusM;
  const auto depth = [&](double r0, double mu0, double d) { return bruteForceOpticalDepth(a, r0, mu0, d); };
  std::vector<double> L(a.wavelengthsNm.size(), 0.0);
  const double end = rayIntersectsGround(b, r, mu) ? distanceToBottomBoundaryM(b, r, mu) : distanceToTopBoundaryM(top, r, mu);
  if (!(end > 0.0)) return L;
  const auto pieces = rayPieces(a, r, mu, end, steps);
  for (std::size_t k = 0; k + 1 < pieces.size(); ++k) {
    const double s0 = pieces[k].first, len = pieces[k + 1].first - s0;
    const int m = pieces[k].second;
    for (int i = 0; i <= m; ++i) {
      // Just inside the piece at its ends: the density there is the piece's own.
      const double s = s0 + len * std::clamp(static_cast<double>(i) / m, 1e-9, 1.0 - 1e-9);
      const double w = (i == 0 || i == m ? 1.0 : (i % 2 ? 4.0 : 2.0)) * len / m / 3.0;
      const double rs = std::sqrt(s * s + 2.0 * r * mu * s + r * r), muSs = (r * muS + s * nu) / rs;
      if (rayIntersectsGround(b, rs, muSs)) continue;
      const std::vector<double> view = depth(r, mu, s), sun = depth(rs, muSs, distanceToTopBoundaryM(top, rs, muSs));
      for (const Component& c : a.components)
        for (std::size_t l = 0; l < L.size(); ++l)
          L[l] += w * std::exp(-view[l] - sun[l]) * c.density.at(rs - b) * c.scatteringPerM[l] * c.phase(l)(nu);
    }
  }
  return L;
}

/// Single scattering only, fine enough in mu, mu_s and nu for the twilight's steep
/// gradients (the tests below the tables' lowest Sun; ~0.3 s each).
PrecomputeOptions belowTheLowestSunOptions() {
  PrecomputeOptions o = smallOptions();
  o.transmittanceWidth = 256;
  o.transmittanceHeight = 64;
  o.scatteringMu = 128;
  o.scatteringMuS = 16;
  o.scatteringNu = 16;
  o.orders = 1;
  return o;
}

// Below the tables' lowest Sun (mu_s,min = cos 102 deg) skyRadiance takes the light from
// where the ray first reaches sunlit air. Against the brute-force single scattering of the
// ray (the Sun's ray blocked by the ground), from the ground and from 30 km, with the Sun
// 103-110 deg from the zenith, towards the Sun's azimuth (the twilight arch), 40 deg off
// it, and away from it; errors relative to the brightest of these views. Reading the
// lowest row at the observer instead (what a clamped lookup does) is off by far more. A
// Sun 125 deg down leaves every ray in the dark: exactly 0 (as it leaves every view but
// the horizon's at 110 deg from the ground).
TEST(Precompute, NightSkyBelowTheLowestSunMatchesBruteForce) {
  const Atmosphere earth = loadAtmosphere("earth", {680.0, 550.0, 440.0});
  const PrecomputeOptions o = belowTheLowestSunOptions();
  const AtmosphereTables t = precompute(earth, o);
  const double b = t.bottomRadiusM;
  double worst = 0.0, worstClamped = 0.0;
  int lit = 0, dark = 0;
  for (double altitude : {10.0, 30e3}) {
    const double r = b + altitude;
    for (double sunZenithDeg : {103.0, 106.0, 110.0}) {
      const double sz = sunZenithDeg * kPi / 180.0, muS = std::cos(sz);
      struct Value {
        double got, clamped, ref;
      };
      std::vector<Value> values[3];
      for (double viewZenithDeg : {60.0, 80.0, 86.0, 89.0}) {
        for (double azimuthDeg : {0.0, 40.0, 180.0}) {
          const double vz = viewZenithDeg * kPi / 180.0, mu = std::cos(vz);
          const double nu = mu * muS + std::sin(vz) * std::sin(sz) * std::cos(azimuthDeg * kPi / 180.0);
          const std::vector<double> got = skyRadiance(t, earth, r, mu, muS, nu);
          const std::vector<double> clamped = skyRadiance(t, earth, r, mu, o.muSMin, nu);
          const std::vector<double> ref = bruteForceSingleScattering(earth, r, mu, muS, nu);
          for (int l = 0; l < 3; ++l) values[l].push_back({got[l], clamped[l], ref[l]});
        }
      }
      for (int l = 0; l < 3; ++l) {
        double scale = 0.0;
        for (const Value& v : values[l]) scale = std::max(scale, v.ref);
        for (const Value& v : values[l]) {
          const double err = scale > 0.0 ? std::abs(v.got - v.ref) / scale : v.got;
          worst = std::max(worst, err);
          if (scale > 0.0) worstClamped = std::max(worstClamped, std::abs(v.clamped - v.ref) / scale);
          EXPECT_LT(err, 0.15) << "altitude " << altitude << " sun " << sunZenithDeg << " l " << l << ": " << v.got
                               << " vs " << v.ref << " (brightest " << scale << ")";
          if (v.ref == 0.0) {
            if (scale == 0.0) {
              EXPECT_EQ(v.got, 0.0);  // else err holds it
            }
            ++dark;
          } else {
            ++lit;
          }
        }
      }
    }
  }
  std::printf("night sky vs brute force: worst |error| %.3g of the brightest view (lowest row read at the "
              "observer: %.3g) over %d lit and %d dark values\n",
              worst, worstClamped, lit, dark);
  EXPECT_GT(lit, 40);
  EXPECT_GT(dark, 40);
  EXPECT_GT(worstClamped, 5.0 * worst);
  for (double mu : {-0.5, 0.0, 0.02, 0.3, 1.0})
    for (double nu : {-0.9, 0.0, 0.5, 0.9})
      for (double v : skyRadiance(t, earth, b + 10.0, mu, std::cos(125.0 * kPi / 180.0), nu)) EXPECT_EQ(v, 0.0);
}

// SkyRadianceLookup (the table geometry and phase functions found once, one search of the
// Lorenz-Mie samples for every wavelength) gives skyRadiance's values to the bit: in the
// tables' Sun range and below it (the ray's first sunlit air), looking up, down and along
// the horizon, for OPAC's tabulated aerosols and Bruneton's closed-form ones.
TEST(Precompute, SkyRadianceLookupGivesSkyRadiancesValues) {
  for (const std::string preset : {"earth", "earth-bruneton"}) {
    const Atmosphere atm = loadAtmosphere(preset, {680.0, 550.0, 440.0});
    const AtmosphereTables t = precompute(atm, belowTheLowestSunOptions());
    const SkyRadianceLookup lookup(t, atm);
    int nonzero = 0;
    for (double r : {t.bottomRadiusM + 10.0, t.bottomRadiusM + 20e3, t.topRadiusM})
      for (double mu : {-0.8, -0.1, 0.0, 0.05, 0.7})
        for (double muS : {-0.5, -0.25, 0.0, 0.4, 1.0})
          for (double nu : {-0.95, 0.0, 0.6, 0.999}) {
            std::vector<double> got(3);
            lookup(r, mu, muS, nu, got.data());
            const std::vector<double> want = skyRadiance(t, atm, r, mu, muS, nu);
            for (int l = 0; l < 3; ++l) EXPECT_EQ(got[l], want[l]) << preset << " " << r << " " << mu << " " << muS;
            nonzero += want[1] > 0.0;
          }
    EXPECT_GT(nonzero, 100) << preset;
  }
}

// Second-order twilight: with the Sun 16 deg down no sunlit air is above the observer
// (the Earth's shadow is 256 km up at the zenith), so the zenith's only light is sunlight
// scattered once in the sunlit air around and then again in the shadowed air overhead.
// Tables that hold the Sun down to 130 deg (muSMin) carry it; against brute force:
//     L2 = int_0^top T(0, s) sum_k sigma_k(s) int_4pi p_k(up . w) L1(s, w) dw ds,
// L1 the brute-force single scattering seen from height s along w (Simpson in s, midpoint
// over the sphere, 36 x 72 directions: within 2 % of 72 x 144), no ground reflection
// (albedo 0), 2 orders. The tables with the usual lowest Sun, 102 deg, have the zenith
// black. The light comes from a band a few degrees wide along the horizon towards the Sun,
// and the tables need fine mu_s cells, radii and density directions to hold it (R 16,
// mu_s 128, 24 x 48 directions here: +18 / +7 / +15 % at 680 / 550 / 440 nm; with
// 16 x 32 directions and R 8, mu_s 64: +83 %; finer still, 33 s: within 13 %;
// docs/accuracy-vs-speed/atmosphere-tables.md, "Twilight"). Bruneton's thin haze (earth-bruneton): the
// default sky's aerosols put the tables at +62 / +2 / +14 % with the same sizes.
TEST(Precompute, SecondOrderTwilightAtTheZenithMatchesBruteForce) {
  Atmosphere earth = loadAtmosphere("earth-bruneton", {680.0, 550.0, 440.0});
  earth.groundAlbedo.assign(3, 0.0);
  PrecomputeOptions o = belowTheLowestSunOptions();
  o.orders = 2;
  o.scatteringR = 16;
  o.scatteringMuS = 128;
  o.scatteringNu = 8;
  o.sphereSamples = 24;
  o.muSMin = std::cos(130.0 * kPi / 180.0);
  const AtmosphereTables t = precompute(earth, o);
  const double b = earth.bottomRadiusM, top = earth.topRadiusM;
  const double r = b + 10.0, muS = std::cos(106.0 * kPi / 180.0), sinS = std::sqrt(1.0 - muS * muS);
  for (double v : bruteForceSingleScattering(earth, r, 1.0, muS, muS)) EXPECT_EQ(v, 0.0);

  std::vector<double> ref(3, 0.0);
  const int steps = 16, polar = 36, azimuth = 72;
  for (int i = 0; i <= steps; ++i) {
    const double s = (top - r) * i / steps, w = (i == 0 || i == steps ? 1.0 : (i % 2 ? 4.0 : 2.0)) * (top - r) / steps / 3.0;
    const std::vector<double> tau = bruteForceOpticalDepth(earth, r, 1.0, s, 100);  // observer to s
    std::vector<double> inScattered(3, 0.0);
    for (int p = 0; p < polar; ++p) {
      const double theta = kPi * (p + 0.5) / polar, dOmega = std::sin(theta) * (kPi / polar) * (2.0 * kPi / azimuth);
      for (int q = 0; q < azimuth; ++q) {
        const double phi = 2.0 * kPi * (q + 0.5) / azimuth;
        const double mu = std::cos(theta), nu = mu * muS + std::sin(theta) * std::cos(phi) * sinS;
        const std::vector<double> L1 = bruteForceSingleScattering(earth, r + s, mu, muS, nu, 60);
        for (const Component& c : earth.components)
          for (int l = 0; l < 3; ++l)
            inScattered[l] += dOmega * L1[l] * c.density.at(10.0 + s) * c.scatteringPerM[l] * c.phase(l)(mu);
      }
    }
    for (int l = 0; l < 3; ++l) ref[l] += w * std::exp(-tau[l]) * inScattered[l];
  }

  PrecomputeOptions usual = o;
  usual.muSMin = PrecomputeOptions().muSMin;
  const std::vector<double> got = skyRadiance(t, earth, r, 1.0, muS, muS);
  const std::vector<double> black = skyRadiance(precompute(earth, usual), earth, r, 1.0, muS, muS);
  for (int l = 0; l < 3; ++l) {
    std::printf("second-order twilight at the zenith, %g nm: tables %.4g, brute force %.4g (%+.1f %%)\n",
                earth.wavelengthsNm[l], got[l], ref[l], 100.0 * (got[l] / ref[l] - 1.0));
    EXPECT_GT(ref[l], 0.0);
    EXPECT_NEAR(got[l], ref[l], 0.3 * ref[l]) << earth.wavelengthsNm[l] << " nm";
    EXPECT_EQ(black[l], 0.0);
  }
  EXPECT_GT(ref[2], ref[0]);  // blue: Rayleigh twice
  EXPECT_LT(ref[1], ref[0]);  // ozone's Chappuis band takes 550 nm from the long twilight path
}

// The density directions follow the narrowest forward peak: for a Henyey-Greenstein lobe
// the half width is closed-form, 1 + g^2 - 2 g cos(theta) = (1 - g)^2 2^(2/3); the polar
// spacing pi / n must be no wider than 1.5 times it, n a multiple of 8 in [16, 64].
TEST(Precompute, DensityDirectionsFollowTheNarrowestForwardPeak) {
  const auto hgAtmosphere = [](double g) {
    return shellAtmosphere({makeComponent("haze", DensityProfile::exponential(1200.0), 2e-5, 0.0,
                                          PhaseFunction::henyeyGreenstein(g), 1)});
  };
  for (double g : {0.5, 0.9, 0.95, 0.99}) {
    const double c = (1.0 + g * g - (1.0 - g) * (1.0 - g) * std::cbrt(4.0)) / (2.0 * g);
    const double halfWidth = std::acos(c);
    const int expected = std::clamp(static_cast<int>(std::ceil(kPi / (1.5 * halfWidth) / 8.0)) * 8, 16, 64);
    EXPECT_EQ(densityDirectionsFor(hgAtmosphere(g)), expected) << g << ": half width " << halfWidth * 180 / kPi;
  }
  EXPECT_EQ(densityDirectionsFor(hgAtmosphere(0.9)), 32);   // 4.63 deg
  EXPECT_EQ(densityDirectionsFor(hgAtmosphere(0.95)), 56);  // 2.25 deg
  EXPECT_EQ(densityDirectionsFor(hgAtmosphere(0.99)), 64);  // clamped
  const Atmosphere earth = loadAtmosphere("earth", {680.0, 550.0, 440.0});
  const Atmosphere mars = loadAtmosphere("mars", {680.0, 550.0, 440.0});
  std::printf("density directions: earth %d, mars %d\n", densityDirectionsFor(earth), densityDirectionsFor(mars));
  EXPECT_EQ(densityDirectionsFor(earth), 16);
  EXPECT_GE(densityDirectionsFor(mars), 48);
}

// The eclipse LuTs look at Mars' limb from Phobos (2.8 Mars radii) and Deimos (6.9), in the
// umbra's centre: the view rays enter the top of the atmosphere with the Sun 112-124 deg
// from the zenith and reach sunlit air, if at all, only past the tangent point. Per tangent
// altitude, against the brute-force single scattering of the ray; errors relative to the
// brightest ray. From Phobos only rays through 5-30 km reach sunlit air (high on the far
// side), and that light crosses the thick limb: at most 5e-8 sr^-1 of the solar irradiance.
// Reading the lowest row at the entry point instead made it up to 1e6 times brighter
// (docs/accuracy-vs-speed/atmosphere-tables.md); from Deimos, 3.6 times.
TEST(Precompute, MarsLimbFromPhobosAndDeimosInTheUmbraMatchesBruteForce) {
  const Atmosphere mars = loadAtmosphere("mars", {680.0, 550.0, 440.0});
  const PrecomputeOptions o = belowTheLowestSunOptions();
  const AtmosphereTables t = precompute(mars, o);
  const double b = t.bottomRadiusM, top = t.topRadiusM;
  for (double distanceM : {9376e3, 23463e3}) {
    std::vector<std::vector<double>> got, clamped, ref;
    for (double h = 0.0; h <= 80e3; h += 5e3) {
      // Observer at (-distance, 0), the Sun along +x; the ray tangent at altitude h.
      const double p = b + h, theta = std::asin(p / distanceM);
      const double wx = std::cos(theta), wy = std::sin(theta);
      const double s = distanceM * wx - std::sqrt((top - p) * (top + p));
      const double x = -distanceM + s * wx, y = s * wy;
      const double mu = (x * wx + y * wy) / top, muS = x / top, nu = wx;
      got.push_back(skyRadiance(t, mars, top, mu, muS, nu));
      clamped.push_back(skyRadiance(t, mars, top, mu, o.muSMin, nu));
      ref.push_back(bruteForceSingleScattering(mars, top, mu, muS, nu));
    }
    for (int l = 0; l < 3; ++l) {
      double scale = 0.0, worst = 0.0, worstClamped = 0.0;
      for (const auto& v : ref) scale = std::max(scale, v[l]);
      ASSERT_GT(scale, 0.0);
      for (std::size_t k = 0; k < ref.size(); ++k) {
        worst = std::max(worst, std::abs(got[k][l] - ref[k][l]) / scale);
        worstClamped = std::max(worstClamped, std::abs(clamped[k][l] - ref[k][l]) / scale);
      }
      std::printf("Mars limb from %.0f km, channel %d: brightest ray %.3g, worst |error| %.3g of it (lowest row at "
                  "the entry: %.3g)\n",
                  distanceM / 1e3, l, scale, worst, worstClamped);
      EXPECT_LT(worst, 0.1) << distanceM << " " << l;
      EXPECT_GT(worstClamped, 1.0) << distanceM << " " << l;
    }
  }
}

// ---- multiple scattering ---------------------------------------------------------------------

TEST(Precompute, OrdersDecreaseInAPurelyScatteringAtmosphere) {
  const Atmosphere a = shellAtmosphere(
      {makeComponent("air", DensityProfile::exponential(8000.0), 2e-5, 0.0, PhaseFunction::rayleigh(), 1),
       makeComponent("haze", DensityProfile::exponential(1200.0), 4e-6, 0.0, PhaseFunction::cornetteShanks(0.8), 1)});
  PrecomputeOptions o = smallOptions();
  o.orders = 5;
  const AtmosphereTables t = precompute(a, o);
  ASSERT_EQ(t.orderMeanRadiance.size(), 5u);
  for (int k = 0; k < 5; ++k) std::printf("order %d: mean radiance %.6g\n", k + 1, t.orderMeanRadiance[k][0]);
  for (int k = 1; k < 5; ++k) {
    EXPECT_GT(t.orderMeanRadiance[k][0], 0.0);
    EXPECT_LT(t.orderMeanRadiance[k][0], t.orderMeanRadiance[k - 1][0]);
  }
  // ratio of successive orders below the single-scattering albedo bound (< 1) and steady
  EXPECT_LT(t.orderMeanRadiance[4][0] / t.orderMeanRadiance[3][0], 0.9);
  expectTablesSane(t);
}

TEST(Precompute, TabulatedPhasesPerWavelengthStayApart) {
  // One table per wavelength, all with the same number of samples (as Lorenz-Mie gives
  // them): the multiple scattering must follow each wavelength's own table, i.e. agree
  // with the closed forms they sample (HG 0.8 at the first wavelength, HG 0.2 at the second).
  auto table = [](double g) {
    std::vector<double> deg, v;
    for (int i = 0; i <= 720; ++i) deg.push_back(i * 0.25);
    for (double d : deg) v.push_back(PhaseFunction::henyeyGreenstein(g)(std::cos(d * kPi / 180.0)));
    return PhaseFunction::tabulatedDegrees(deg, v);
  };
  Component closed = makeComponent("haze", DensityProfile::exponential(1200.0), 4e-5, 0.0, PhaseFunction::isotropic(), 2);
  Component tabulated = closed;
  closed.phases = {PhaseFunction::henyeyGreenstein(0.8), PhaseFunction::henyeyGreenstein(0.2)};
  tabulated.phases = {table(0.8), table(0.2)};
  PrecomputeOptions o = smallOptions();
  o.orders = 2;
  const AtmosphereTables a = precompute(shellAtmosphere({closed}, 0.0, 2), o);
  const AtmosphereTables b = precompute(shellAtmosphere({tabulated}, 0.0, 2), o);
  double worst = 0.0, scale = 0.0, differ = 0.0;
  const std::vector<double> va(a.multipleScattering.values.begin(), a.multipleScattering.values.end());
  const std::vector<double> vb(b.multipleScattering.values.begin(), b.multipleScattering.values.end());
  ASSERT_EQ(va.size(), vb.size());
  for (std::size_t i = 0; i + 1 < va.size(); i += 2) {
    worst = std::max({worst, std::abs(va[i] - vb[i]), std::abs(va[i + 1] - vb[i + 1])});
    scale = std::max({scale, va[i], va[i + 1]});
    differ = std::max(differ, std::abs(va[i] - va[i + 1]));
  }
  EXPECT_GT(differ, 0.1 * scale);   // the two wavelengths' phases give different skies...
  EXPECT_LT(worst, 0.01 * scale);   // ...and each tabulated one its own closed form's
}

TEST(Precompute, EarthSecondOrderPositiveAndSmallerThanSingle) {
  const Atmosphere earth = loadAtmosphere("earth", {680.0, 550.0, 440.0});
  PrecomputeOptions o = smallOptions();
  o.orders = 2;
  const AtmosphereTables t = precompute(earth, o);
  ASSERT_EQ(t.orderMeanRadiance.size(), 2u);
  for (int l = 0; l < 3; ++l) {
    std::printf("earth %.0f nm: order 1 %.5g, order 2 %.5g (ratio %.3f)\n", earth.wavelengthsNm[l],
                t.orderMeanRadiance[0][l], t.orderMeanRadiance[1][l],
                t.orderMeanRadiance[1][l] / t.orderMeanRadiance[0][l]);
    EXPECT_GT(t.orderMeanRadiance[1][l], 0.0);
    EXPECT_LT(t.orderMeanRadiance[1][l], t.orderMeanRadiance[0][l]);
  }
  // Blue scatters more: relatively more multiple scattering at 440 nm than at 680 nm.
  EXPECT_GT(t.orderMeanRadiance[1][2] / t.orderMeanRadiance[0][2], t.orderMeanRadiance[1][0] / t.orderMeanRadiance[0][0]);
  // Zenith sky from the ground, sun at 30 deg: multiple scattering is a fraction of the total.
  const double b = earth.bottomRadiusM;
  const std::vector<double> total = skyRadiance(t, earth, b, 1.0, 0.5, 0.5);
  const std::vector<double> multiple = lookupScattering(t, t.multipleScattering, b, 1.0, 0.5, 0.5, false);
  for (int l = 0; l < 3; ++l) {
    EXPECT_GT(multiple[l], 0.0);
    EXPECT_LT(multiple[l], 0.5 * total[l]);
  }
  // Indirect irradiance on the ground with the sun up: positive, below the direct one.
  const std::vector<double> Ei = indirectIrradiance(t, b, 0.5), Ed = directIrradiance(t, b, 0.5);
  for (int l = 0; l < 3; ++l) {
    EXPECT_GT(Ei[l], 0.0);
    EXPECT_LT(Ei[l], Ed[l]);
  }
  // Below the tables' lowest Sun the sky is dark, and so is its light on the ground (the
  // table's cells there hold what the precomputation leaks, not night); at it, twilight.
  const double below = std::nextafter(t.options.muSMin, -1.0);
  const std::vector<double> night = indirectIrradiance(t, b, below), deepNight = indirectIrradiance(t, b, -1.0);
  const std::vector<double> lowest = indirectIrradiance(t, b, t.options.muSMin);
  for (int l = 0; l < 3; ++l) {
    EXPECT_EQ(night[l], 0.0);
    EXPECT_EQ(deepNight[l], 0.0);
    EXPECT_GT(lowest[l], 0.0);
  }
}

// E_0 on a horizontal surface (directIrradiance): the transmittance to the top times the
// share of the Sun's disc above the horizon, sunDiscCosine. At the direct irradiance
// table's texels it is the table's value; between them it is not the table's
// interpolation (which across the Sun's setting, with 64 cells 1.8 deg wide, was x19 too
// bright with the Sun on the horizon): with the Sun's centre on the horizon it is
// T(b, 0) alpha / 4, half of the disc's area seen but weighted by its height.
TEST(Precompute, DirectIrradianceIsTheTransmittanceTimesTheVisibleDisc) {
  const Atmosphere earth = loadAtmosphere("earth", {680.0, 550.0, 440.0});
  PrecomputeOptions o = smallOptions();
  o.orders = 1;
  const AtmosphereTables t = precompute(earth, o);
  const double b = t.bottomRadiusM, a = o.sunAngularRadiusRad;
  const int w = t.directIrradiance.width, h = t.directIrradiance.height;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double r = b + (t.topRadiusM - b) * y / (h - 1.0), muS = -1.0 + 2.0 * x / (w - 1.0);
      const std::vector<double> E = directIrradiance(t, r, muS);
      for (int l = 0; l < 3; ++l)
        ASSERT_NEAR(E[l], t.directIrradiance.at(x, y)[l], 1e-12 * (1.0 + std::abs(E[l]))) << x << ", " << y;
    }
  EXPECT_EQ(sunDiscCosine(-a, a), 0.0);
  EXPECT_EQ(sunDiscCosine(-0.5, a), 0.0);
  EXPECT_DOUBLE_EQ(sunDiscCosine(0.0, a), a / 4.0);
  EXPECT_DOUBLE_EQ(sunDiscCosine(a, a), a);
  EXPECT_DOUBLE_EQ(sunDiscCosine(0.5, a), 0.5);
  const std::vector<double> horizon = directIrradiance(t, b, 0.0), T = transmittanceToTop(t, b, 0.0);
  for (int l = 0; l < 3; ++l) EXPECT_NEAR(horizon[l], T[l] * a / 4.0, 1e-15);
  EXPECT_EQ(directIrradiance(t, b, -2.0 * a)[0], 0.0);
}

TEST(Precompute, GroundAlbedoAddsLight) {
  auto make = [](double albedo) {
    return shellAtmosphere(
        {makeComponent("air", DensityProfile::exponential(8000.0), 1.5e-5, 0.0, PhaseFunction::rayleigh(), 1)},
        albedo);
  };
  PrecomputeOptions o = smallOptions();
  o.orders = 2;
  const AtmosphereTables dark = precompute(make(0.0), o), bright = precompute(make(0.8), o);
  EXPECT_DOUBLE_EQ(dark.orderMeanRadiance[0][0], bright.orderMeanRadiance[0][0]);
  EXPECT_GT(bright.orderMeanRadiance[1][0], 1.2 * dark.orderMeanRadiance[1][0]);
}

// ---- robustness ------------------------------------------------------------------------------

void checkPreset(const std::string& name) {
  const Atmosphere a = loadAtmosphere(name, {680.0, 550.0, 440.0});
  PrecomputeOptions o = smallOptions();
  o.orders = 3;
  const AtmosphereTables t = precompute(a, o);
  expectTablesSane(t);
  const double b = a.bottomRadiusM, top = a.topRadiusM;
  for (double r : {b, b + 1.0, 0.5 * (b + top), top - 1.0, top}) {
    for (double mu : {-1.0, horizonCosine(b, r), std::nextafter(horizonCosine(b, r), 1.0), 0.0, 0.3, 1.0}) {
      for (double muS : {-1.0, o.muSMin, 0.0, 0.5, 1.0}) {
        for (double nu : {-1.0, 0.0, 1.0}) {
          std::string where;
          EXPECT_TRUE(allFiniteNonNegative(skyRadiance(t, a, r, mu, muS, nu), where, "sky")) << name << " " << where;
        }
        std::string where;
        EXPECT_TRUE(allFiniteNonNegative(indirectIrradiance(t, r, muS), where, "E")) << where;
      }
      std::string where;
      EXPECT_TRUE(allFiniteNonNegative(transmittanceToTop(t, r, mu), where, "T")) << where;
    }
  }
}

TEST(Precompute, EarthTablesFiniteAndNonNegative) { checkPreset("earth"); }
TEST(Precompute, MarsTablesFiniteAndNonNegative) { checkPreset("mars"); }

TEST(Precompute, WavelengthBatchesGiveTheSameTables) {
  const Atmosphere earth = loadAtmosphere("earth", {680.0, 550.0, 440.0});
  PrecomputeOptions o = smallOptions();
  o.orders = 2;
  o.scatteringR = 4;
  o.scatteringMu = 8;
  const AtmosphereTables all = precompute(earth, o);
  o.wavelengthBatch = 1;
  const AtmosphereTables one = precompute(earth, o);
  EXPECT_EQ(all.multipleScattering.values, one.multipleScattering.values);
  EXPECT_EQ(all.singleScattering[0].values, one.singleScattering[0].values);
  EXPECT_EQ(all.irradiance.values, one.irradiance.values);
}

// A sink gets each batch's tables as they are finished (each component's single
// scattering, then the multiple), a batch's channels wide: put side by side they are the
// tables precompute() gives without one, to the bit; the tables it returns then hold no 4D
// values. One order: a multiple scattering of zeros.
TEST(Precompute, ASinkGetsEachBatchsTablesOnceFinished) {
  const Atmosphere earth = loadAtmosphere("earth", {680.0, 620.0, 550.0, 500.0, 440.0});
  PrecomputeOptions o = smallOptions();
  o.scatteringR = 4;
  o.scatteringMu = 8;
  for (int orders : {1, 2}) {
    o.orders = orders;
    o.wavelengthBatch = 0;
    const AtmosphereTables all = precompute(earth, o);
    const int ns = static_cast<int>(all.singleScattering.size());
    ASSERT_GE(ns, 2);
    std::vector<FloatTable3D> put(ns + 1);
    for (int q = 0; q <= ns; ++q) put[q].resize(all.multipleScattering.width, all.multipleScattering.height,
                                                all.multipleScattering.depth, 5);
    std::vector<std::pair<int, int>> calls;  // (first channel, table)
    o.wavelengthBatch = 2;
    const AtmosphereTables sunk = precompute(earth, o, {}, [&](int first, int table, const FloatTable3D& v) {
      calls.emplace_back(first, table);
      ASSERT_EQ(v.channels, first == 4 ? 1 : 2);
      ASSERT_EQ(v.values.size() / v.channels, put[table].values.size() / 5);
      for (std::size_t i = 0; i < v.values.size() / v.channels; ++i)
        for (int k = 0; k < v.channels; ++k) put[table].values[i * 5 + first + k] = v.values[i * v.channels + k];
    });
    std::vector<std::pair<int, int>> expected;
    for (int first : {0, 2, 4})
      for (int q = 0; q <= ns; ++q) expected.emplace_back(first, q);
    EXPECT_EQ(calls, expected) << orders;
    for (int q = 0; q < ns; ++q) EXPECT_EQ(put[q].values, all.singleScattering[q].values) << orders << " " << q;
    EXPECT_EQ(put[ns].values, all.multipleScattering.values) << orders;
    if (orders == 1) {
      EXPECT_TRUE(std::all_of(put[ns].values.begin(), put[ns].values.end(), [](float v) { return v == 0.0f; }));
    }
    EXPECT_TRUE(sunk.singleScattering.empty());
    EXPECT_TRUE(sunk.multipleScattering.values.empty());
    EXPECT_EQ(sunk.transmittance.values, all.transmittance.values);
    EXPECT_EQ(sunk.irradiance.values, all.irradiance.values);
  }
}

// The batch that fits a memory budget: all wavelengths when they fit, else the fewest
// batches that do, as even as they can be.
TEST(Precompute, WavelengthBatchForFitsTheBudgetEvenly) {
  const PrecomputeOptions o;
  const std::size_t per = batchBytesPerWavelength(o, 2);
  // 4D: single x 2 + J_2 (3 tables in float); the rays do not grow with the wavelengths.
  const std::size_t texels = 8u * 32 * 128 * 32;
  EXPECT_EQ(per, 3 * texels * 4);
  EXPECT_EQ(wavelengthBatchFor(o, 2, 15, 15 * per), 15);
  EXPECT_EQ(wavelengthBatchFor(o, 2, 15, 15 * per - 1), 8);  // 14 fit: 2 batches, 8 + 7
  EXPECT_EQ(wavelengthBatchFor(o, 2, 47, 22 * per), 16);     // 16 + 16 + 15, not 22 + 22 + 3
  EXPECT_EQ(wavelengthBatchFor(o, 2, 47, 3 * per), 3);
  EXPECT_EQ(wavelengthBatchFor(o, 2, 47, 0), 1);
  // One order keeps no J nor L: one table more than the scatterers.
  PrecomputeOptions single = o;
  single.orders = 1;
  EXPECT_EQ(batchBytesPerWavelength(single, 1), 2 * texels * 4);
  // Spilled: J_k whole, kSpilledSlices r slices of two tables (L_k and the sum, or the two
  // single-scattering tables).
  PrecomputeOptions spilled = o;
  spilled.spillTables = true;
  EXPECT_EQ(batchBytesPerWavelength(spilled, 2), texels * 4 + 2 * (texels / 32) * 4 * kSpilledSlices);
  EXPECT_EQ(wavelengthBatchFor(spilled, 2, 15, 15 * batchBytesPerWavelength(spilled, 2)), 15);
}

// A spilled table (SpilledTableMemory): zero when made; its values survive letting its
// slices go (release) and come back; the slices written through its file
// (copySpilledTableMemory) read back the same; a copy of it is the heap's, not spilled.
TEST(Precompute, SpilledTableKeepsItsValues) {
  FloatTable3D t;
  t.resize(64, 32, 8, 64, true);  // 4 MiB
  ASSERT_TRUE(t.spilled.on);
  EXPECT_TRUE(std::all_of(t.values.begin(), t.values.end(), [](float v) { return v == 0.0f; }));
  for (std::size_t i = 0; i < t.values.size(); ++i) t.values[i] = static_cast<float>(i % 1000003);
  t.release(0, 5);
  t.populate(2, 4);
  t.releaseAll();
  for (std::size_t i = 0; i < t.values.size(); i += 977) ASSERT_EQ(t.values[i], static_cast<float>(i % 1000003)) << i;
  const std::size_t slice = t.offset(0, 0, 1);
  std::vector<float> in(slice, 2.5f), out(slice);
  copySpilledTableMemory(t.values.data(), 3 * slice * sizeof(float), in.data(), slice * sizeof(float), true);
  EXPECT_EQ(*t.at(0, 0, 3), 2.5f);
  EXPECT_EQ(*t.at(0, 0, 4), static_cast<float>(4 * slice % 1000003));
  copySpilledTableMemory(t.values.data(), 3 * slice * sizeof(float), out.data(), slice * sizeof(float), false);
  EXPECT_EQ(out, in);
  const FloatTable3D copy = t;
  EXPECT_FALSE(copy.spilled.on);
  EXPECT_EQ(copy.values, t.values);
  FloatTable3D small;
  small.resize(4, 4, 4, 4, true);  // below 2 MiB: the heap's
  EXPECT_FALSE(small.spilled.on);
  EXPECT_THROW(copySpilledTableMemory(small.values.data(), 0, out.data(), 4, false), std::logic_error);
}

// The spilled precomputation (options.spillTables, with a sink) hands on the same tables,
// to the bit, as the one in memory.
TEST(Precompute, SpilledTablesAreTheSame) {
  const Atmosphere earth = loadAtmosphere("earth", {680.0, 550.0, 500.0, 440.0});
  PrecomputeOptions o = smallOptions();
  o.scatteringR = 16, o.scatteringMu = 32, o.scatteringMuS = 16, o.scatteringNu = 16;  // 2 MiB at 4 wavelengths
  o.orders = 3;
  std::map<std::pair<bool, int>, std::vector<float>> got;
  int tables = 0;
  for (bool spill : {false, true}) {
    o.spillTables = spill;
    const AtmosphereTables t = precompute(earth, o, {}, [&](int, int table, const FloatTable3D& v) {
      EXPECT_EQ(v.spilled.on, spill) << table;
      got[std::make_pair(spill, table)].assign(v.values.begin(), v.values.end());
    });
    tables = static_cast<int>(t.scatteringComponents.size()) + 1;
  }
  ASSERT_GE(tables, 3);
  for (int table = 0; table < tables; ++table) {
    const std::vector<float>&spilled = got[std::make_pair(true, table)], &inMemory = got[std::make_pair(false, table)];
    EXPECT_FALSE(spilled.empty()) << table;
    EXPECT_EQ(spilled, inMemory) << table;
  }
}

TEST(Precompute, ProgressIsReportedAndCanCancel) {
  const Atmosphere earth = loadAtmosphere("earth", {550.0});
  PrecomputeOptions o = smallOptions();
  o.scatteringR = 4;
  o.scatteringMu = 8;
  o.orders = 2;
  std::vector<double> fractions;
  std::vector<std::string> stages;
  precompute(earth, o, [&](double f, const std::string& s) {
    fractions.push_back(f);
    if (stages.empty() || stages.back() != s) stages.push_back(s);
    return true;
  });
  ASSERT_FALSE(fractions.empty());
  for (std::size_t i = 1; i < fractions.size(); ++i) EXPECT_GE(fractions[i], fractions[i - 1]);
  EXPECT_DOUBLE_EQ(fractions.back(), 1.0);
  EXPECT_GE(stages.size(), 6u);
  EXPECT_THROW(precompute(earth, o, [](double f, const std::string&) { return f < 0.3; }), PrecomputeCancelled);
  o.scatteringMu = 7;
  EXPECT_THROW(precompute(earth, o), std::invalid_argument);
}

// ---- refraction ------------------------------------------------------------------------------

TEST(Precompute, RefractionKeepsVerticalRaysAndChangesGrazingOnes) {
  const Atmosphere earth = loadAtmosphere("earth", {680.0, 550.0, 440.0});
  PrecomputeOptions o = smallOptions();
  o.orders = 2;
  const AtmosphereTables off = precompute(earth, o);
  o.refraction = true;
  const AtmosphereTables on = precompute(earth, o);
  expectTablesSane(on);
  const int TW = o.transmittanceWidth, TH = o.transmittanceHeight;
  for (int y = 0; y < TH; ++y)
    for (int l = 0; l < 3; ++l)
      EXPECT_NEAR(on.transmittance.at(0, y)[l], off.transmittance.at(0, y)[l], 1e-6 * off.transmittance.at(0, y)[l]);
  // Vertical view and vertical sun: single scattering identical too.
  const int x = o.scatteringMuS - 1, yz = o.scatteringMu / 2;
  for (int z = 0; z < o.scatteringR; ++z)
    for (std::size_t q = 0; q < off.singleScattering.size(); ++q)
      for (int l = 0; l < 3; ++l) {
        const double a = off.singleScattering[q].at(x, yz, z)[l], c = on.singleScattering[q].at(x, yz, z)[l];
        EXPECT_NEAR(c, a, 1e-6 * a) << "z " << z << " q " << q;
      }
  // Near the horizon, from the ground and from 20 km up: different, finite, in [0, 1].
  int differ = 0;
  for (int y : {0, TH / 4}) {
    for (int xx : {TW - 1, TW - 2, TW - 4}) {
      for (int l = 0; l < 3; ++l) {
        const double a = off.transmittance.at(xx, y)[l], c = on.transmittance.at(xx, y)[l];
        EXPECT_TRUE(std::isfinite(c) && c >= 0.0 && c <= 1.0);
        if (std::abs(c - a) > 1e-3 * a) ++differ;
      }
    }
  }
  std::printf("horizon from the ground, 550 nm: T = %.4g straight, %.4g refracted\n",
              off.transmittance.at(TW - 1, 0)[1], on.transmittance.at(TW - 1, 0)[1]);
  EXPECT_GE(differ, 9);
}

// ---- timing (not a test: --gtest_also_run_disabled_tests --gtest_filter=*Timing*) ------------

TEST(Precompute, DISABLED_TimingDefaultSizes) {
  for (bool refraction : {false, true}) {
    const Atmosphere earth = loadAtmosphere("earth", {680.0, 550.0, 440.0});
    PrecomputeOptions o;
    o.refraction = refraction;
    const AtmosphereTables t = precompute(earth, o);
    std::printf("earth, 3 wavelengths, 4 orders, default sizes, refraction %s, tables %.1f MiB\n",
                refraction ? "on" : "off", t.bytes() / 1048576.0);
    for (const StageTiming& s : t.timings) std::printf("  %-22s %8.2f s\n", s.stage.c_str(), s.seconds);
    for (std::size_t k = 0; k < t.orderMeanRadiance.size(); ++k)
      std::printf("  order %zu mean radiance %.5g %.5g %.5g\n", k + 1, t.orderMeanRadiance[k][0],
                  t.orderMeanRadiance[k][1], t.orderMeanRadiance[k][2]);
  }
}


// The precomputed transmittance at the zenith, from the ground, gives back the optical depth
// the model holds at 550 nm (molecules, ozone, O2, the stratospheric sulphate and the
// tropospheric aerosols that "aerosolOpticalDepth550" scaled to 0.1) within 1 %, and so the
// requested aerosol part.
TEST(PrecomputeAerosols, ZenithTransmittanceGivesBackTheRequestedOpticalDepth) {
  const Atmosphere atm = loadAtmosphere("earth", {680.0, 550.0, 440.0});
  PrecomputeOptions o = umbra::test::smallPrecomputeOptions();
  o.orders = 1;
  const AtmosphereTables t = precompute(atm, o);
  const double tauTables = -std::log(t.transmittance.values[t.transmittance.offset(0, 0) + 1]);  // x_mu 0, x_r 0
  const double tauModel = atm.verticalOpticalDepth(0.0, atm.thicknessM())[1];
  const double tauAerosols = atm.verticalOpticalDepth(atm.component("troposphere"), 0.0, atm.thicknessM())[1];
  std::printf("  zenith optical depth at 550 nm: tables %.5f, model %.5f (aerosols %.5f)\n", tauTables, tauModel,
              tauAerosols);
  EXPECT_NEAR(tauTables / tauModel, 1.0, 0.01);
  EXPECT_NEAR((tauTables - (tauModel - tauAerosols)) / 0.1, 1.0, 0.01);
}

}  // namespace
}  // namespace umbra::atmosphere
