// The relief's normal (sky/NormalMap.hpp): a flat texel keeps the sphere's normal, a texel
// leaning east or south tilts it that way in the local frame, the strength scales the
// tilt's tangent, the poles have a frame; the fade with magnification.
#include "NormalMap.hpp"

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include <cmath>

using namespace umbra::sky;

namespace {
glm::dvec3 encode(const glm::dvec3& eastSouthUp) { return 0.5 * (glm::normalize(eastSouthUp) + glm::dvec3(1.0)); }
}  // namespace

TEST(NormalMap, FlatTexelKeepsTheSphereNormal) {
  for (const glm::dvec3 nb : {glm::dvec3(1, 0, 0), glm::normalize(glm::dvec3(0.3, -0.5, 0.8)), glm::dvec3(0, 0, 1),
                              glm::dvec3(0, 0, -1)}) {
    const glm::dvec3 n = reliefNormal(nb, encode({0, 0, 1}), 1.0);
    EXPECT_NEAR(glm::length(n - nb), 0.0, 1e-12);
  }
}

// At longitude 0, latitude 0 (nb = +x) east is +y and north +z. A texel leaning 30 deg
// east (red up) tilts the normal 30 deg towards +y; one leaning south (green up) towards -z.
// Strength 0.5 halves the tangent of the tilt.
TEST(NormalMap, TiltsInTheLocalFrame) {
  const double t = std::tan(30.0 * M_PI / 180.0);
  const glm::dvec3 east = reliefNormal({1, 0, 0}, encode({t, 0, 1}), 1.0);
  EXPECT_NEAR(east.x, std::cos(30.0 * M_PI / 180.0), 1e-12);
  EXPECT_NEAR(east.y, std::sin(30.0 * M_PI / 180.0), 1e-12);
  EXPECT_NEAR(east.z, 0.0, 1e-12);
  const glm::dvec3 south = reliefNormal({1, 0, 0}, encode({0, t, 1}), 1.0);
  EXPECT_NEAR(south.z, -std::sin(30.0 * M_PI / 180.0), 1e-12);
  const glm::dvec3 half = reliefNormal({1, 0, 0}, encode({t, 0, 1}), 0.5);
  EXPECT_NEAR(half.y / half.x, 0.5 * t, 1e-12);
  // At the north pole east is +y, north -x: a texel leaning north tilts towards -x.
  const glm::dvec3 pole = reliefNormal({0, 0, 1}, encode({0, -t, 1}), 1.0);
  EXPECT_NEAR(pole.x, -std::sin(30.0 * M_PI / 180.0), 1e-12);
  // A texel pointing down cannot turn the facet over.
  EXPECT_GT(glm::dot(reliefNormal({1, 0, 0}, glm::dvec3(0.5, 0.5, 0.0), 1.0), glm::dvec3(1, 0, 0)), 0.0);
}

TEST(NormalMap, FadesWithMagnification) {
  EXPECT_EQ(reliefFade(0.5), 1.0);
  EXPECT_EQ(reliefFade(4.0), 1.0);
  EXPECT_NEAR(reliefFade(8.0), 0.5, 1e-12);
  EXPECT_EQ(reliefFade(16.0), 0.0);
  EXPECT_EQ(reliefFade(1e9), 0.0);
}
