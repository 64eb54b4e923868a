// Cloud layers on the CPU (sky/Clouds.hpp): the light through a layer against its closed
// forms and invariants, the coverage noise's determinism and area, the wind's drift.
#include "Clouds.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <random>

using namespace umbra::sky;

namespace {
constexpr double kPi = 3.14159265358979323846;

// Points spread over the unit sphere, seeded.
std::vector<glm::dvec3> spherePoints(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<glm::dvec3> p(n);
  for (auto& v : p) v = glm::normalize(glm::dvec3(normal(rng), normal(rng), normal(rng)));
  return p;
}
}  // namespace

// Beer-Lambert for the direct beam, at several depths and slants.
TEST(Clouds, DirectLightIsBeerLambert) {
  for (double tau : {0.0, 0.1, 1.0, 10.0})
    for (double mu : {1.0, 0.5, 0.1, -0.5}) EXPECT_NEAR(cloudDirectTransmittance(tau, mu), std::exp(-tau / std::abs(mu)), 1e-15);
}

// Conservative scattering: reflected, diffusely transmitted and direct light add up to the
// light that came in, for every depth and slant; the reflected share grows with depth to 1.
TEST(Clouds, EnergyIsConserved) {
  for (double tau : {1e-6, 1e-3, 0.1, 1.0, 10.0, 100.0, 1000.0}) {
    for (double mu0 : {1.0, 0.7, 0.3, 0.05, 1e-3}) {
      const double r = cloudReflectance(tau, mu0), td = cloudDiffuseTransmittance(tau, mu0);
      const double t = cloudDirectTransmittance(tau, mu0);
      EXPECT_GE(r, 0.0);
      EXPECT_GE(td, 0.0);
      EXPECT_NEAR(r + td + t, 1.0, 1e-12) << tau << " " << mu0;
      // Lambertian radiance over each hemisphere: its flux (pi L) is the share times E mu0.
      EXPECT_NEAR(kPi * cloudRadiance(tau, mu0, true), r * mu0, 1e-12);
      EXPECT_NEAR(kPi * cloudRadiance(tau, mu0, false), td * mu0, 1e-12);
    }
  }
  EXPECT_LT(cloudReflectance(1.0, 0.8), cloudReflectance(10.0, 0.8));
  EXPECT_LT(cloudReflectance(10.0, 0.8), cloudReflectance(100.0, 0.8));
  EXPECT_GT(cloudReflectance(1000.0, 0.8), 0.99);
}

// At tau -> 0 the layer scatters what it takes out of the beam, tau / mu0 of it, and no more
// (single scattering: the scattered share over tau / mu0 tends to 1).
TEST(Clouds, ThinLayerScattersWhatTheBeamLoses) {
  for (double mu0 : {1.0, 0.5, 0.2}) {
    const double tau = 1e-7;
    const double scattered = cloudReflectance(tau, mu0) + cloudDiffuseTransmittance(tau, mu0);
    EXPECT_NEAR(scattered / (tau / mu0), 1.0, 1e-5) << mu0;
  }
  EXPECT_EQ(cloudReflectance(0.0, 0.5), 0.0);
  EXPECT_EQ(cloudDiffuseTransmittance(0.0, 0.5), 0.0);
}

// A thick overcast (tau 20, the Sun at 60 deg): a stratus deck reflects most of the light
// (delta-Eddington: 0.7 to 0.8 for such clouds) and lets the rest through diffusely.
TEST(Clouds, ThickDeckReflectsMost) {
  const double mu0 = 0.5, r = cloudReflectance(20.0, mu0);
  EXPECT_GT(r, 0.65);
  EXPECT_LT(r, 0.8);
  EXPECT_NEAR(cloudDiffuseTransmittance(20.0, mu0), 1.0 - r, 1e-15);  // exp(-40): no direct light
}

// The same layer seen from above and from below: lit from one face, the faces share the
// light; lit from the other face at the same slant, they swap (a slab is symmetric).
TEST(Clouds, AboveAndBelowSwapWithTheLight) {
  for (double tau : {0.3, 3.0, 30.0}) {
    const double lit = cloudRadiance(tau, 0.6, true), through = cloudRadiance(tau, 0.6, false);
    EXPECT_NEAR(lit + through, (1.0 - std::exp(-tau / 0.6)) * 0.6 / kPi, 1e-12);
    if (tau > 3.0) {
      EXPECT_GT(lit, through);  // thick: brighter on the lit face
    }
  }
}

// The noise: the same seed gives the same field, another seed another; values in [0, 1].
TEST(Clouds, NoiseIsSeeded) {
  const auto points = spherePoints(500, 3);
  int differ = 0;
  for (const auto& u : points) {
    const glm::dvec3 p = 300.0 * u;
    const double a = cloudNoise(p, 7), b = cloudNoise(p, 7), c = cloudNoise(p, 8);
    EXPECT_EQ(a, b);
    EXPECT_GE(a, 0.0);
    EXPECT_LE(a, 1.0);
    differ += std::abs(a - c) > 1e-3;
  }
  EXPECT_GT(differ, 450);
}

// Coverage: none at 0, all at 1, and the mean density over the sphere follows it.
TEST(Clouds, CoverageIsTheCloudyFraction) {
  const auto points = spherePoints(20000, 5);
  for (double coverage : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    double sum = 0.0;
    for (const auto& u : points) {
      const double d = cloudDensity(cloudNoise(318.0 * u, 11), coverage);
      if (coverage == 0.0) {
        EXPECT_EQ(d, 0.0);
      }
      if (coverage == 1.0) {
        EXPECT_EQ(d, 1.0);
      }
      sum += d;
    }
    EXPECT_NEAR(sum / points.size(), coverage, 0.06) << coverage;
  }
}

// The wind turns the layer rigidly: the point below the camera moves by speed x time along
// the wind's direction (east here), and the frame stays a rotation.
TEST(Clouds, WindDriftMovesThePointBelow) {
  CloudLayer layer;
  layer.windEastMs = 20.0;
  const double radius = 6.373e6, seconds = 3600.0;
  const glm::dvec3 foot = glm::normalize(glm::dvec3(1.0, 0.0, 1.0));  // 45 deg N, 0 E
  const glm::dmat3 m = cloudDrift(layer, foot, radius, 0.0, seconds);
  // The noise is looked up at m p: the cloud over p now was over m p at the epoch. The
  // cloud that was over the foot is now east of it: m (that point) = foot.
  const glm::dvec3 east(0.0, 1.0, 0.0);
  const double angle = 20.0 * seconds / radius;
  const glm::dvec3 moved = std::cos(angle) * foot + std::sin(angle) * east;
  EXPECT_NEAR(glm::length(m * moved - foot), 0.0, 1e-12);
  EXPECT_NEAR(glm::determinant(m), 1.0, 1e-12);
  EXPECT_NEAR(glm::length(m * glm::transpose(m) * glm::dvec3(1.0, 2.0, 3.0) - glm::dvec3(1.0, 2.0, 3.0)), 0.0, 1e-12);
  // No wind, or no time: the identity.
  EXPECT_EQ(cloudDrift(CloudLayer{}, foot, radius, 0.0, seconds), glm::dmat3(1.0));
  EXPECT_EQ(cloudDrift(layer, foot, radius, 5.0, 5.0), glm::dmat3(1.0));
}
