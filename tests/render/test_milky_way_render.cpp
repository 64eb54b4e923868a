// The Milky Way behind the stars (StarRendering::SetMilkyWay, sky/MilkyWay.hpp): the
// packaged panorama's stars lie at their catalogue places and come out of it; its
// brightest part renders at the published surface brightness; and a map's galactic centre
// renders where ERFA puts it.
#include "RenderTestSupport.hpp"
#include "MapFiles.h"
#include "MilkyWay.hpp"
#include "StarLight.hpp"
#include "scene/Bodies.hpp"

#include <erfa.h>

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

using namespace umbra;
using namespace umbra::render;
using namespace umbra::render::test;
using umbra::pipeline::milkyWayTexels;

namespace {

constexpr double kDeg = kPi / 180.0;

glm::dvec3 raDec(double raDeg, double decDeg) { return sky::icrsDirection(raDeg * kDeg, decDeg * kDeg); }

// The texels a view samples, as sky's functions take them.
sky::MilkyWayMap cpuMap(const MapTexels& t) {
  sky::MilkyWayMap m;
  m.width = t.width;
  m.height = t.height;
  vtkDataArray* v = t.texels->GetPointData()->GetScalars();
  m.rgb.resize(static_cast<std::size_t>(m.width) * m.height * 3);
  for (vtkIdType i = 0; i < v->GetNumberOfTuples(); ++i)
    for (int c = 0; c < 3; ++c) m.rgb[3 * i + c] = static_cast<float>(v->GetComponent(i, c) / 65535.0);
  return m;
}

std::string stellariumMilkyWay() {
  const auto named = scene::findNamedMilkyWayMap("stellarium");
  return named && std::filesystem::is_regular_file(named->file) ? named->file : "";
}

// A view from the origin towards `forward` (up: the ICRS pole), width x height, fovDeg
// high, with the Milky Way map at radiance scale `scale` and nothing else.
std::vector<float> renderSky(const std::shared_ptr<const MapTexels>& map, double scale, const glm::dvec3& forward,
                             int width, int height, double fovDeg) {
  BodyView view(width, height, true);
  useSharedDisplay(view.GetRenderWindow());
  SunLight sun;
  sun.positionM = -kAu * glm::normalize(glm::cross(forward, glm::dvec3(0.0, 0.0, 1.0)));  // off to the side
  view.SetBodies(sun, {}, testLutImage());
  ViewCamera c;
  c.positionM = glm::dvec3(0.0);
  c.targetM = forward;
  c.up = {0.0, 0.0, 1.0};
  c.fovDeg = fovDeg;
  view.SetCamera(c);
  view.SetMilkyWay(map, scale);
  view.Render();
  std::vector<float> rgb;
  int w = 0, h = 0;
  view.ReadHdr(rgb, w, h);
  return rgb;
}

// Isolated bright stars of the Hipparcos catalogue (J2000 RA, Dec in degrees; V), in dark
// parts of the map.
struct FixtureStar {
  const char* name;
  double raDeg, decDeg, vMag;
};
constexpr FixtureStar kIsolatedStars[] = {
    {"Arcturus", 213.9153, 19.1824, -0.05}, {"Regulus", 152.0930, 11.9672, 1.36},
    {"Diphda", 10.8974, -17.9866, 2.04},    {"Alphard", 141.8968, -8.6586, 1.99},
    {"Rasalhague", 263.7336, 12.5600, 2.08}, {"Hamal", 31.7934, 23.4624, 2.01},
    {"Alhena", 99.4280, 16.3993, 1.93},      {"Algieba", 154.9931, 19.8415, 2.01},
};

}  // namespace

// stellarium-data's panorama lies as sky/MilkyWay.hpp says: the dot of each isolated bright
// star is centred within 1.5 texels (0.26 deg) of its catalogue place, and on average
// within 0.3 texel; sky::removeStars takes each dot out (nothing left above the texels
// 4 to 6 texels around it).
TEST(MilkyWayRender, PackagedMapsStarsAtTheirPlacesAndTakenOut) {
  const std::string path = stellariumMilkyWay();
  if (path.empty()) GTEST_SKIP() << "stellarium-data is not installed";
  sky::MilkyWayMap m = cpuMap(*milkyWayTexels(path, "", sky::kMilkyWayStarsShownToV)->map);
  auto y = [&](int i, int j) {
    i = ((i % m.width) + m.width) % m.width;
    return sky::frameLuminance(glm::dvec3(m.at(i, std::clamp(j, 0, m.height - 1))));
  };
  std::vector<glm::dvec3> places;
  std::vector<double> vMags;
  double meanDx = 0.0, meanDy = 0.0;
  for (const FixtureStar& s : kIsolatedStars) {
    const glm::dvec2 uv = sky::milkyWayMapCoord(raDec(s.raDeg, s.decDeg));
    const double px = uv.x * m.width - 0.5, py = uv.y * m.height - 0.5;  // texel-centre coordinates
    double sx = 0.0, sy = 0.0, sw = 0.0;
    for (int j = int(std::lround(py)) - 3; j <= int(std::lround(py)) + 3; ++j)
      for (int i = int(std::lround(px)) - 3; i <= int(std::lround(px)) + 3; ++i) {
        sx += y(i, j) * i;
        sy += y(i, j) * j;
        sw += y(i, j);
      }
    ASSERT_GT(sw, 0.0) << s.name << ": no dot";
    const double dx = sx / sw - px, dy = sy / sw - py;
    std::printf("%-10s dot centred %+.2f, %+.2f texels from its place\n", s.name, dx, dy);
    EXPECT_LT(std::hypot(dx, dy), 1.5) << s.name;
    meanDx += dx / std::size(kIsolatedStars);
    meanDy += dy / std::size(kIsolatedStars);
    places.push_back(raDec(s.raDeg, s.decDeg));
    vMags.push_back(s.vMag);
  }
  // The highest texel within 2 texels of a star, and the highest of the ring 4 to 6 texels out.
  std::printf("mean offset %+.2f, %+.2f texels\n", meanDx, meanDy);
  EXPECT_LT(std::hypot(meanDx, meanDy), 0.3);  // no shift of the layout as a whole
  auto peaks = [&](const FixtureStar& s) {
    const glm::dvec2 uv = sky::milkyWayMapCoord(raDec(s.raDeg, s.decDeg));
    const int ci = static_cast<int>(uv.x * m.width), cj = static_cast<int>(uv.y * m.height);
    std::pair<double, double> p{0.0, 0.0};
    for (int j = cj - 6; j <= cj + 6; ++j)
      for (int i = ci - 6; i <= ci + 6; ++i) {
        const int r = std::max(std::abs(i - ci), std::abs(j - cj));
        if (r <= 2) p.first = std::max(p.first, y(i, j));
        else if (r >= 4) p.second = std::max(p.second, y(i, j));
      }
    return p;
  };
  std::vector<std::pair<double, double>> before;
  for (const FixtureStar& s : kIsolatedStars) before.push_back(peaks(s));
  sky::removeStars(m, places, vMags);
  for (std::size_t k = 0; k < before.size(); ++k) {
    const auto after = peaks(kIsolatedStars[k]);
    std::printf("%-10s highest within 2 texels: %.3g before, %.3g after; 4-6 texels out %.3g\n",
                kIsolatedStars[k].name, before[k].first, after.first, after.second);
    EXPECT_LE(after.first, after.second) << kIsolatedStars[k].name << ": its dot is left";
  }
}

// The brightest part of the packaged map (its brightest 1-deg cap: the Large Sagittarius Star
// Cloud) renders at 250 S10 = 21.79 V mag per square arcsecond (within 0.3; the render
// against the CPU's cap mean within 2 %), in a view without air.
TEST(MilkyWayRender, BrightestPartAtThePublishedSurfaceBrightness) {
  const std::string path = stellariumMilkyWay();
  if (path.empty()) GTEST_SKIP() << "stellarium-data is not installed";
  const auto texels = milkyWayTexels(path, "", sky::kMilkyWayStarsShownToV);
  const sky::MilkyWayMap m = cpuMap(*texels->map);
  const sky::BrightestCap cap = sky::brightestCap(m, sky::kMilkyWayCalibrationCapRad);
  const double ra = std::atan2(cap.direction.y, cap.direction.x) / kDeg, dec = std::asin(cap.direction.z) / kDeg;
  double l = 0.0, b = 0.0;
  eraIcrs2g(ra * kDeg, dec * kDeg, &l, &b);
  std::printf("brightest 1-deg cap at RA %.2f, Dec %.2f (l %.2f, b %.2f deg)\n", std::fmod(ra + 360.0, 360.0), dec,
              l / kDeg, b / kDeg);
  EXPECT_LT(std::abs(b / kDeg), 10.0);  // in the galactic plane
  std::printf("the map's mean over the sphere: 1/%.1f of that cap's\n", cap.meanLuminance / sky::sphereMeanLuminance(m));
  const double scale = texels->radiancePerSunIrradiance * 1361.0;
  constexpr int kSize = 96;
  constexpr double kFov = 3.0;
  const std::vector<float> rgb = renderSky(texels->map, scale, cap.direction, kSize, kSize, kFov);
  // The cap's pixels, weighted by solid angle (each pixel's ray from the pinhole model).
  const double s = 2.0 * std::tan(0.5 * kFov * kDeg) / kSize;
  glm::dvec3 sum(0.0);
  double weight = 0.0;
  for (int j = 0; j < kSize; ++j)
    for (int i = 0; i < kSize; ++i) {
      const double u = (i + 0.5 - 0.5 * kSize) * s, v = (0.5 * kSize - (j + 0.5)) * s;
      const double offRad = std::atan(std::hypot(u, v));
      if (offRad > sky::kMilkyWayCalibrationCapRad) continue;
      const double omega = s * s / std::pow(1.0 + u * u + v * v, 1.5);
      const float* p = &rgb[(static_cast<std::size_t>(j) * kSize + i) * 3];
      sum += omega * glm::dvec3(p[0], p[1], p[2]);
      weight += omega;
    }
  const double rendered = sky::frameLuminance(sum / weight);
  const double vMag = -2.5 * std::log10(rendered / sky::radianceOfSurfaceBrightnessWm2Sr(0.0, 1361.0));
  std::printf("rendered %.4e W m^-2 sr^-1 = %.3f V mag/arcsec^2 (published %.3f); CPU cap %.4e\n", rendered, vMag,
              sky::s10ToVMagPerArcsec2(sky::kMilkyWayBrightestS10), scale * cap.meanLuminance);
  EXPECT_NEAR(vMag, sky::s10ToVMagPerArcsec2(sky::kMilkyWayBrightestS10), 0.3);
  EXPECT_NEAR(rendered / (scale * cap.meanLuminance), 1.0, 0.02);
}

// Orientation: a map with a Gaussian glow (sigma 2 deg) centred on the galactic centre's
// published J2000 place (RA 17h45m37.2s, Dec -28d56m10s: l = b = 0) renders, in a view
// pointed where ERFA's eraG2icrs puts l = b = 0, with its centroid within a pixel
// (0.06 deg) of the image centre.
TEST(MilkyWayRender, GalacticCentreWhereErfaPutsIt) {
  const double publishedRa = (17.0 + 45.0 / 60.0 + 37.2 / 3600.0) * 15.0, publishedDec = -(28.0 + 56.0 / 60.0 + 10.0 / 3600.0);
  double raRad = 0.0, decRad = 0.0;
  eraG2icrs(0.0, 0.0, &raRad, &decRad);
  const glm::dvec3 erfa = raDec(raRad / kDeg, decRad / kDeg), published = raDec(publishedRa, publishedDec);
  const double apartArcsec = std::acos(std::min(1.0, glm::dot(erfa, published))) / kDeg * 3600.0;
  std::printf("galactic centre: ERFA RA %.5f Dec %.5f deg, %.2f\" from the published place\n", raRad / kDeg,
              decRad / kDeg, apartArcsec);
  EXPECT_LT(apartArcsec, 2.0);
  constexpr int kW = 720, kH = 360;
  const std::string path = writeRgbPng(
      kW, kH,
      [&](int i, int j) {
        const glm::dvec3 d = sky::milkyWayDirection({(i + 0.5) / kW, (j + 0.5) / kH});
        const double a = std::acos(std::min(1.0, glm::dot(d, published))) / (2.0 * kDeg);
        return glm::dvec3(std::exp(-0.5 * a * a));
      },
      "galactic-centre.png");
  const auto texels = milkyWayTexels(path, "", sky::kMilkyWayStarsShownToV);
  constexpr int kSize = 200;
  constexpr double kFov = 12.0;
  const std::vector<float> rgb = renderSky(texels->map, 1.0, erfa, kSize, kSize, kFov);
  double sx = 0.0, sy = 0.0, sw = 0.0;
  for (int j = 0; j < kSize; ++j)
    for (int i = 0; i < kSize; ++i) {
      const double g = rgb[(static_cast<std::size_t>(j) * kSize + i) * 3 + 1];
      sx += g * (i + 0.5);
      sy += g * (j + 0.5);
      sw += g;
    }
  ASSERT_GT(sw, 0.0);
  const double dx = sx / sw - 0.5 * kSize, dy = sy / sw - 0.5 * kSize;
  std::printf("rendered glow centred %+.3f, %+.3f px from ERFA's galactic centre (%.4f deg a pixel)\n", dx, dy,
              kFov / kSize);
  EXPECT_LT(std::hypot(dx, dy), 1.0);
}
