// The precomputation's pieces one by one (atmosphere/precompute/), each against a closed
// form or a brute-force sum: the paths, the 4D parametrisation and its lookups, the
// model's column densities, the parallel runner and the kernels.
#include "Atmosphere.hpp"
#include "precompute/Kernels.hpp"
#include "precompute/Model.hpp"
#include "precompute/Parametrisation.hpp"
#include "precompute/Paths.hpp"
#include "precompute/Runner.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <tuple>
#include <vector>

using namespace umbra::atmosphere;
using namespace umbra::atmosphere::stages;

namespace {
const ShellRadii kEarth{6360e3, 6420e3};
}  // namespace

// A straight path: position (sin z s, r + mu s) and a constant tangent; a path traced through
// a medium without refractivity is the same line (to a micrometre over 300 km).
TEST(PrecomputeStages, PathsStraightAndTracedWithoutRefraction) {
  const double r = 6361e3, mu = 0.3, sz = std::sqrt(1.0 - mu * mu);
  const Path straight = straightPath(r, mu, 300e3);
  RefractiveMedium vacuum;
  vacuum.bottomRadiusM = kEarth.bottomRadiusM;
  vacuum.topRadiusM = kEarth.topRadiusM;
  vacuum.refractivity = [](double) { return 0.0; };
  vacuum.refractivityDerivativePerM = [](double) { return 0.0; };
  const Path traced = tracedPath(vacuum, r, mu, 10e3, false);
  std::size_t a = 0, b = 0;
  for (double s = 0.0; s <= std::min(straight.length, traced.length); s += 7e3) {
    double x, y, tx, ty, x2, y2, tx2, ty2;
    straight.eval(s, a, x, y, tx, ty);
    traced.eval(s, b, x2, y2, tx2, ty2);
    EXPECT_NEAR(x, sz * s, 1e-6);
    EXPECT_NEAR(y, r + mu * s, 1e-6);
    EXPECT_NEAR(tx, sz, 1e-12);
    EXPECT_NEAR(ty, mu, 1e-12);
    EXPECT_NEAR(x2, x, 1e-6) << s;
    EXPECT_NEAR(y2, y, 1e-6) << s;
  }
}

// The 4D parametrisation: each coordinate's inverse gives the value back, on both halves of
// mu (rays to the ground and to the sky; on the ground itself the downward rays share one
// row); a texel's point lies inside the shell with a nu
// that the geometry allows.
TEST(PrecomputeStages, ParametrisationRoundTrips) {
  const ScatterGeometry g(kEarth, {32, 128, 32, 8}, std::cos(102.0 * kPi / 180.0));
  for (double r : {6360e3, 6361e3, 6380e3, 6419e3}) {
    EXPECT_NEAR(g.rFromU(g.uR(r)), r, 1e-6 * r);
    const double horizon = -std::sqrt(1.0 - std::pow(kEarth.bottomRadiusM / r, 2));
    for (double mu : {-0.9, horizon - 0.01, horizon + 0.01, 0.0, 0.5, 1.0}) {
      const bool ground = mu < horizon;
      if (ground && r == kEarth.bottomRadiusM) continue;  // on the ground every downward ray is one texel row
      bool back = false;
      EXPECT_NEAR(g.muFromU(r, g.uMu(r, mu, ground), back), mu, 1e-9) << r << " " << mu;
      EXPECT_EQ(back, ground);
    }
  }
  for (double muS : {-0.2, 0.0, 0.4, 1.0}) EXPECT_NEAR(g.muSFromU(g.uMuS(muS)), muS, 1e-9) << muS;
  for (int z = 0; z < 32; z += 7)
    for (int y = 0; y < 128; y += 13)
      for (int x = 0; x < 8 * 32; x += 29) {
        const ScatteringPoint p = g.texel(x, y, z);
        EXPECT_GE(p.r, kEarth.bottomRadiusM);
        EXPECT_LE(p.r, kEarth.topRadiusM);
        const double s = std::sqrt((1 - p.mu * p.mu) * (1 - p.muS * p.muS));
        EXPECT_GE(p.nu, p.mu * p.muS - s - 1e-12);
        EXPECT_LE(p.nu, p.mu * p.muS + s + 1e-12);
      }
}

// A bilinear lookup reproduces a bilinear function exactly, and a 4D cell's weights sum to 1.
TEST(PrecomputeStages, LookupsReproduceLinearFunctions) {
  Table2D t;
  t.resize(9, 5, 2);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 9; ++x) {
      t.at(x, y)[0] = 2.0 * x / 8.0 + 3.0 * y / 4.0;
      t.at(x, y)[1] = (x / 8.0) * (y / 4.0);
    }
  for (double xu : {0.0, 0.13, 0.5, 0.87, 1.0})
    for (double yu : {0.0, 0.31, 1.0}) {
      double out[2];
      bilinearUnit(t, xu, yu, out);
      EXPECT_NEAR(out[0], 2.0 * xu + 3.0 * yu, 1e-12);
      EXPECT_NEAR(out[1], xu * yu, 1e-12);
    }
  const ScatterGeometry g(kEarth, {8, 32, 8, 4}, -0.2);
  const SNuCell c = sNuCell(g, 0.37, -0.21);
  EXPECT_NEAR(c.w00 + c.w01 + c.w10 + c.w11, 1.0, 1e-15);
}

// Column densities along the vertical from the ground to the top: each component's against
// its closed form (exponential: H (1 - exp(-L / H)); tent: its half width, when it lies in
// the shell; the boundary layer's integral) or a brute-force midpoint sum (10^6 steps); the optical depth is the columns
// times the extinctions.
TEST(PrecomputeStages, ModelColumnsAgainstClosedForms) {
  for (const char* preset : {"earth", "mars"}) {
    const Atmosphere atm = loadAtmosphere(preset, {680.0, 550.0, 440.0});
    const PrecomputeOptions o;
    const Model m(atm, o);
    const double L = atm.topRadiusM - atm.bottomRadiusM;
    const Path up = straightPath(atm.bottomRadiusM, 1.0, L);
    std::vector<double> col(m.nc, 0.0);
    std::size_t seg = 0;
    m.columns(up, 0.0, L, 2000, seg, col.data());
    for (int c = 0; c < m.nc; ++c) {
      const DensityProfile& p = atm.components[c].density;
      double expected = 0.0;
      if (p.kind == DensityProfile::Kind::Exponential) {
        expected = p.scaleHeightM * (1.0 - std::exp(-L / p.scaleHeightM));
      } else if (p.kind == DensityProfile::Kind::Tent && p.centreM - p.halfWidthM >= 0.0 &&
                 p.centreM + p.halfWidthM <= L) {
        expected = p.halfWidthM;
      } else if (p.kind == DensityProfile::Kind::BoundaryLayer) {
        expected = p.integral(0.0, L);  // closed form, Gauss-Legendre across the blends
      } else {
        const int n = 1000000;
        for (int i = 0; i < n; ++i) expected += p.at((i + 0.5) * L / n) * L / n;
      }
      // Simpson takes 10 intervals across a 500 m blending zone of the boundary layer: 3e-7.
      const double tolerance = p.kind == DensityProfile::Kind::BoundaryLayer ? 1e-6 : 1e-7;
      EXPECT_NEAR(col[c], expected, tolerance * expected) << preset << " " << atm.components[c].name;
    }
    std::vector<double> tau(m.nl);
    m.opticalDepth(col.data(), tau.data());
    for (int l = 0; l < m.nl; ++l) {
      double sum = 0.0;
      for (int c = 0; c < m.nc; ++c) sum += atm.components[c].extinctionPerM(l) * col[c];
      EXPECT_DOUBLE_EQ(tau[l], sum);
    }
  }
}

// The runner calls each index once, reports progress from begin to end without going back,
// and a progress callback that says stop cancels it.
TEST(PrecomputeStages, RunnerCoversEveryIndexAndCancels) {
  std::vector<double> reported;
  const PrecomputeProgress progress = [&](double f, const std::string&) {
    reported.push_back(f);
    return true;
  };
  Runner run(progress, 2, 0.2, 0.8);
  run.setStages(2.0);
  std::vector<std::atomic<int>> calls(1000);
  run.run("a", 1.0, 1000, [&](int i) { ++calls[i]; });
  run.run("b", 1.0, 10, [](int) {});
  for (const auto& c : calls) EXPECT_EQ(c.load(), 1);
  ASSERT_FALSE(reported.empty());
  for (std::size_t i = 1; i < reported.size(); ++i) EXPECT_GE(reported[i], reported[i - 1]);
  EXPECT_NEAR(reported.back(), 0.8, 1e-12);
  const PrecomputeProgress stop = [](double, const std::string&) { return false; };
  Runner cancelled(stop, 1, 0.0, 1.0);
  EXPECT_THROW(cancelled.run("c", 1.0, 10, [](int) {}), PrecomputeCancelled);
}

// The kernels against plain sums: a constant 4D table blends to its constant (the lobes':
// Precompute.LobeKernelDispatchedMatchesTheClosedForm).
TEST(PrecomputeStages, KernelsAgainstPlainSums) {
  FloatTable3D t;
  t.resize(6, 4, 3, 2);
  std::fill(t.values.begin(), t.values.end(), 0.75);
  std::vector<double> out(6 * 2);
  blendRows(t, RMuCell{1, 2, 0.3, 0.6}, out.data());
  for (double v : out) EXPECT_DOUBLE_EQ(v, 0.75);

  // tablePositions as Model::tablePosition.
  std::vector<double> cosines(74), weight(74);
  std::vector<int> index(74);
  for (int j = 0; j < 74; ++j) cosines[j] = std::cos(0.083 * j + 0.01);
  tablePositions(cosines.data(), 74, index.data(), weight.data());
  for (int j = 0; j < 74; ++j) {
    int i;
    double wj;
    Model::tablePosition(cosines[j], i, wj);
    EXPECT_EQ(index[j], i);
    EXPECT_EQ(weight[j], wj);
  }
  // cosineModes (AVX-512 where there is one) against the portable loop: 37 samples, 16 and
  // 12 modes (the latter always the loop).
  for (int modes : {16, 12}) {
    std::vector<double> f(37), cosTable(37 * modes), fast(modes), plain(modes);
    for (int q = 0; q < 37; ++q) {
      f[q] = 1.0 + 0.1 * q;
      for (int m = 0; m < modes; ++m) cosTable[q * modes + m] = std::cos(0.1 * q * m);
    }
    cosineModes(f.data(), cosTable.data(), 37, modes, fast.data());
    cosineModesPlain(f.data(), cosTable.data(), 37, modes, plain.data());
    for (int m = 0; m < modes; ++m) {
      double expected = 0.0;
      for (int q = 0; q < 37; ++q) expected += f[q] * cosTable[q * modes + m];
      EXPECT_NEAR(fast[m], expected, 1e-12) << modes << " " << m;
      EXPECT_NEAR(plain[m], expected, 1e-12) << modes << " " << m;
    }
  }
  // modeProducts against the plain sums: 3 rings, 5 modes, rows 2 and 0 of 3, one lobe's
  // modes for both and then one per row.
  const int rings = 3, modes = 5;
  std::vector<double> alpha(3 * rings * modes), gamma(2 * rings * modes), products(2 * modes);
  for (std::size_t i = 0; i < alpha.size(); ++i) alpha[i] = std::sin(0.7 * i) + 0.1;
  for (std::size_t i = 0; i < gamma.size(); ++i) gamma[i] = std::cos(0.3 * i);
  const int rows[2] = {2, 0};
  for (std::size_t stride : {std::size_t{0}, std::size_t{rings * modes}}) {
    modeProducts(alpha.data(), rows, 2, gamma.data(), stride, rings, modes, products.data());
    for (int u = 0; u < 2; ++u)
      for (int m = 0; m < modes; ++m) {
        double expected = 0.0;
        for (int lt = 0; lt < rings; ++lt)
          expected += alpha[(rows[u] * rings + lt) * modes + m] * gamma[u * stride + lt * modes + m];
        EXPECT_NEAR(products[u * modes + m], expected, 1e-14) << stride << " " << u << " " << m;
      }
  }
}

// The density's azimuth integral by cosine modes against a brute-force integral: a light
// with three modes, known at 8 azimuths, gives them back exactly (the discrete cosine
// transform); its integral against a Henyey-Greenstein lobe (g = 0.6, and 0.9 at a
// grazing ring where the peak is a few degrees wide) seen from several azimuths, as
// sum_m alpha_m gamma_m cos(m phi_v), matches 200 000 midpoints of the product.
TEST(PrecomputeStages, AzimuthModesIntegrateTheLightAgainstALobe) {
  const int nPh = 8;
  const AzimuthModes am(nPh);
  const auto light = [](double phi) { return 1.0 + 0.5 * std::cos(phi) + 0.25 * std::cos(2.0 * phi); };
  std::vector<double> L(nPh), alpha(nPh);
  for (int i = 0; i < nPh; ++i) L[i] = light((i + 0.5) * kPi / nPh);
  cosineModes(L.data(), am.phiModes.data(), nPh, nPh, alpha.data());
  const double expectedAlpha[3] = {1.0, 0.5, 0.25};
  for (int m = 0; m < nPh; ++m) EXPECT_NEAR(alpha[m], m < 3 ? expectedAlpha[m] : 0.0, 1e-14) << m;
  for (auto [g, a, b] : {std::tuple{0.6, 0.3, 0.5}, std::tuple{0.9, 0.02, 0.97}}) {
    const double A = (1.0 - g * g) / (4.0 * kPi);
    std::vector<double> c(am.Q), p(am.Q), gamma(nPh);
    for (int q = 0; q < am.Q; ++q) c[q] = a + b * am.qCos[q];
    lobeValues(A, 0.0, g, c.data(), p.data(), am.Q);
    cosineModes(p.data(), am.qModes.data(), am.Q, nPh, gamma.data());
    for (double phiV : {0.0, 0.4, 1.3, 2.9}) {
      double modes = 0.0;
      for (int m = 0; m < nPh; ++m) modes += alpha[m] * gamma[m] * std::cos(m * phiV);
      const int n = 200000;
      double brute = 0.0;
      for (int i = 0; i < n; ++i) {
        const double phi = (i + 0.5) * 2.0 * kPi / n, cosine = a + b * std::cos(phi - phiV);
        brute += light(phi) * A / std::pow(1.0 + g * g - 2.0 * g * cosine, 1.5);
      }
      brute *= 2.0 * kPi / n;
      EXPECT_NEAR(modes, brute, 1e-6 * brute) << g << " " << phiV;
    }
  }
}

// The irradiance table: bilinear where its mu_s cell reaches the horizon or above (a linear
// function comes back exactly), geometric across the cells wholly below it (an exponential
// in mu_s, the ground's light after sunset, comes back exactly between its nodes), and
// linear again where a node is dark.
TEST(PrecomputeStages, IrradianceLookupIsGeometricBelowTheHorizon) {
  Table2D t;
  t.resize(17, 3, 2);  // nodes every 0.125 in mu_s; node 8 at mu_s = 0
  auto muOf = [](int x) { return -1.0 + 2.0 * x / 16.0; };
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 17; ++x) {
      t.at(x, y)[0] = muOf(x) > 0.0 ? 1.0 + muOf(x) + y : std::exp(20.0 * muOf(x)) * (1.0 + y);
      t.at(x, y)[1] = x < 3 ? 0.0 : std::exp(20.0 * muOf(x));
    }
  const double top = kEarth.topRadiusM, bottom = kEarth.bottomRadiusM;
  double out[2];
  for (double mu : {-0.9, -0.52, -0.3, -0.125, -0.01}) {
    for (double h : {0.0, 0.25, 1.0}) {
      lookupIrradiance(t, kEarth, bottom + h * (top - bottom), mu, out);
      // Rows 0, 1, 2 at h = 0, 0.5, 1, linear in r between them; the cell from -0.125 to 0
      // ends at the horizon and is below it.
      const double expected = std::exp(20.0 * mu) * (1.0 + 2.0 * h);
      EXPECT_NEAR(out[0], expected, 1e-12 * expected) << mu << " " << h;
    }
  }
  // Above the horizon (the cell from 0 to 0.125 and on): linear, exact for 1 + mu + y.
  for (double mu : {0.01, 0.3, 0.99}) {
    lookupIrradiance(t, kEarth, bottom, mu, out);
    EXPECT_NEAR(out[0], 1.0 + mu, 1e-12);
  }
  // A dark node (channel 1 is zero below mu_s = -0.625): the straight line to it.
  lookupIrradiance(t, kEarth, bottom, -0.7, out);
  const double lit = std::exp(20.0 * -0.625);
  EXPECT_NEAR(out[1], 0.4 * lit, 1e-15);
}
