// Cloud layers in the render pass (AtmosphereRendering::SetClouds, sky/glsl/Clouds.glsl)
// against the CPU: the layer seen from below and from above over the tables' own lookups
// (atmosphere/Precompute.hpp) and the light model of sky/Clouds.hpp, the ground's light
// under a layer (the direct sunlight exp(-tau / mu0)), the noise of the GLSL twin against
// the CPU's, determinism, and the extremes (no NaN: ReadHdr throws on one).
#include "AtmosphereTestSupport.hpp"

#include "Clouds.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace umbra;
using namespace umbra::render;
using namespace umbra::render::test;

namespace {

using Layers = std::vector<AtmosphereRendering::CloudLayerView>;

struct Raw {
  std::vector<float> hdr;
  int w = 0, h = 0;
  glm::dvec3 at(int i, int j) const {
    const float* p = &hdr[3 * (static_cast<std::size_t>(j) * w + i)];
    return {p[0], p[1], p[2]};
  }
};

// The frame in the tables' channels (identity colour matrix), Earth's ground of `albedo`.
Raw renderClouds(const ViewCamera& cam, const glm::dvec3& sunDir, const Layers& layers, double albedo = 0.1, int size = 16) {
  const AtmosphereFixture& f = atmosphereFixture();
  AtmosphereScene scene(size, cam, sunDir, false);
  SphereBody earth{"Earth", {0.0, 0.0, 0.0}, f.tables.bottomRadiusM, glm::dvec3(albedo)};
  scene.view.SetBodies(scene.sun, {earth}, testLutImage());
  scene.view.GetAtmosphere().SetAtmosphere(f.model, f.tables, earth.centreM, earth.albedoRgb);
  scene.view.GetAtmosphere().SetColourMatrix(glm::dmat3(1.0));
  scene.view.GetAtmosphere().SetClouds(layers);
  scene.view.Render();
  Raw r;
  scene.view.ReadHdr(r.hdr, r.w, r.h);
  return r;
}

// A camera altitudeM above the north pole looking straight up (+1) or down (-1).
ViewCamera verticalCamera(double altitudeM, double sign, double fovDeg = 1.0) {
  ViewCamera c;
  c.positionM = {0.0, 0.0, atmosphereFixture().tables.bottomRadiusM + altitudeM};
  c.targetM = c.positionM + glm::dvec3(0.0, 0.0, sign);
  c.up = {1.0, 0.0, 0.0};
  c.fovDeg = fovDeg;
  return c;
}

AtmosphereRendering::CloudLayerView layer(double altitudeM, double tau, double coverage = 1.0, std::uint32_t seed = 1,
                                          double featureSizeM = 2000.0) {
  AtmosphereRendering::CloudLayerView v;
  v.layer.altitudeM = altitudeM;
  v.layer.opticalDepth = tau;
  v.layer.coverage = coverage;
  v.layer.seed = seed;
  v.layer.featureSizeM = featureSizeM;
  return v;
}

glm::dvec3 vec(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

// What the CPU expects along a vertical ray from the camera at radius r (mu = +-1) through
// a whole layer at radius rc, for the Sun at zenith cosine muS, per unit solar irradiance:
// S(x -> c) + T(x, c) L_cloud, plus t_v of what lies beyond (tiny for thick layers; given).
glm::dvec3 cpuVertical(double r, double mu, double rc, double tau, double muS, const glm::dvec3& beyond) {
  const auto& f = atmosphereFixture();
  const bool ground = mu < 0.0;
  const double d = std::abs(rc - r), nu = mu * muS;
  const glm::dvec3 T = vec(atmosphere::transmittanceAlong(f.tables, r, mu, d, ground));
  const glm::dvec3 S =
      vec(atmosphere::skyRadiance(f.tables, f.model, r, mu, muS, nu)) - T * vec(atmosphere::skyRadiance(f.tables, f.model, rc, mu, muS, nu));
  const glm::dvec3 eDirect = vec(atmosphere::directIrradiance(f.tables, rc, muS));
  const glm::dvec3 eSky = vec(atmosphere::indirectIrradiance(f.tables, rc, muS));
  const bool above = mu < 0.0;
  const double shareDirect = above ? sky::cloudReflectance(tau, muS) : sky::cloudDiffuseTransmittance(tau, muS);
  const double shareSky = above ? sky::cloudReflectance(tau, sky::kCloudDiffuseCosine)
                                : sky::cloudDiffuseTransmittance(tau, sky::kCloudDiffuseCosine);
  const glm::dvec3 light = (shareDirect * eDirect + shareSky * eSky) / kPi;
  const double tv = sky::cloudDirectTransmittance(tau, mu);
  return (1.0 - tv) * S + T * light + tv * beyond;
}

double maxRelative(const glm::dvec3& gpu, const glm::dvec3& cpu) {
  double m = 0.0;
  for (int c = 0; c < 3; ++c) m = std::max(m, std::abs(gpu[c] - cpu[c]) / cpu[c]);
  return m;
}

constexpr double kSunElevationDeg = 50.0;

}  // namespace

// From the ground looking up at an overcast deck 2 km up (tau 20): the zenith's radiance is
// the light through the deck, within 3 % of the CPU's.
TEST(CloudRender, OvercastSeenFromBelow) {
  const double b = atmosphereFixture().tables.bottomRadiusM, muS = std::sin(kSunElevationDeg * kPi / 180.0);
  const Raw f = renderClouds(verticalCamera(10.0, 1.0), directionFromAngles(kSunElevationDeg, 0.0), {layer(2000.0, 20.0)});
  const glm::dvec3 gpu = f.at(f.w / 2, f.h / 2) / kSolarIrradiance;
  const glm::dvec3 cpu = cpuVertical(b + 10.0, 1.0, b + 2000.0, 20.0, muS, glm::dvec3(0.0));
  std::printf("  below: GPU %.5g %.5g %.5g, CPU %.5g %.5g %.5g (per unit irradiance)\n", gpu.x, gpu.y, gpu.z, cpu.x, cpu.y, cpu.z);
  EXPECT_LT(maxRelative(gpu, cpu), 0.03);
}

// From 8 km looking down at the same deck: its lit face, within 3 % of the CPU's, and
// brighter than the face seen from below (1.9 times through the default sky's haze).
TEST(CloudRender, OvercastSeenFromAbove) {
  const double b = atmosphereFixture().tables.bottomRadiusM, muS = std::sin(kSunElevationDeg * kPi / 180.0);
  const glm::dvec3 sun = directionFromAngles(kSunElevationDeg, 0.0);
  const Raw f = renderClouds(verticalCamera(8000.0, -1.0), sun, {layer(2000.0, 20.0)});
  const glm::dvec3 gpu = f.at(f.w / 2, f.h / 2) / kSolarIrradiance;
  const glm::dvec3 cpu = cpuVertical(b + 8000.0, -1.0, b + 2000.0, 20.0, muS, glm::dvec3(0.0));
  std::printf("  above: GPU %.5g %.5g %.5g, CPU %.5g %.5g %.5g (per unit irradiance)\n", gpu.x, gpu.y, gpu.z, cpu.x, cpu.y, cpu.z);
  EXPECT_LT(maxRelative(gpu, cpu), 0.03);
  const Raw below = renderClouds(verticalCamera(10.0, 1.0), sun, {layer(2000.0, 20.0)});
  EXPECT_GT(gpu.y, 1.5 * below.at(below.w / 2, below.h / 2).y / kSolarIrradiance);
}

// The ground under a whole layer of optical depth tau: of the Sun's direct light exp(-tau /
// mu0) arrives unscattered and 1 - R - exp(-tau / mu0) scattered; of the sky's 1 - R(0.6).
// Three frames looking straight down from 10 m: ground of albedo 0.3 without and with the
// layer, and of albedo 0 (the air's light alone) to take away.
TEST(CloudRender, GroundUnderALayerGetsBeerLambertSunlight) {
  const auto& f = atmosphereFixture();
  const double b = f.tables.bottomRadiusM, muS = std::sin(kSunElevationDeg * kPi / 180.0);
  const glm::dvec3 sun = directionFromAngles(kSunElevationDeg, 0.0);
  const ViewCamera cam = verticalCamera(10.0, -1.0);
  const glm::dvec3 air = renderClouds(cam, sun, {}, 0.0).at(8, 8), clear = renderClouds(cam, sun, {}, 0.3).at(8, 8);
  const glm::dvec3 eDirect = vec(atmosphere::directIrradiance(f.tables, b, muS));
  const glm::dvec3 eSky = vec(atmosphere::indirectIrradiance(f.tables, b, muS));
  for (double tau : {0.5, 2.0, 8.0}) {
    const glm::dvec3 cloudy = renderClouds(cam, sun, {layer(2000.0, tau)}, 0.3).at(8, 8);
    const double direct = std::exp(-tau / muS);
    const double scattered = sky::cloudDiffuseTransmittance(tau, muS);
    const double skyThrough = 1.0 - sky::cloudReflectance(tau, sky::kCloudDiffuseCosine);
    for (int c = 0; c < 3; ++c) {
      const double expected = (eDirect[c] * (direct + scattered) + eSky[c] * skyThrough) / (eDirect[c] + eSky[c]);
      const double got = (cloudy[c] - air[c]) / (clear[c] - air[c]);
      EXPECT_NEAR(got, expected, 0.01) << "tau " << tau << " channel " << c;
    }
  }
}

// Partial cover: the GLSL noise against the CPU's. Looking down from 8 km on a broken layer
// 3 km up over a black ground (the noise's cells 2 km; a 120 deg view), each pixel against
// the CPU's noise at its crossing: where the CPU sees thick cloud the GPU shows a bright
// top, and the dim air where it sees none.
TEST(CloudRender, BrokenLayerFollowsTheCpuNoise) {
  const double b = atmosphereFixture().tables.bottomRadiusM, rc = b + 3000.0;
  const ViewCamera cam = verticalCamera(8000.0, -1.0, 120.0);
  const glm::dvec3 sun = directionFromAngles(kSunElevationDeg, 0.0);
  const Raw clear = renderClouds(cam, sun, {}, 0.0, 48);
  const Raw cloudy = renderClouds(cam, sun, {layer(3000.0, 30.0, 0.5, 9)}, 0.0, 48);
  int agree = 0, total = 0, cloudyPixels = 0;
  for (int j = 0; j < cloudy.h; j += 3)
    for (int i = 0; i < cloudy.w; i += 3) {
      const Ray ray = pixelRay(cam, cloudy.w, cloudy.h, i, j);
      const double r = glm::length(ray.origin), mu = glm::dot(ray.origin, ray.dir) / r;
      const double disc = (rc - r) * (rc + r) + r * r * mu * mu;
      if (disc < 0.0) continue;
      const double s = -r * mu - std::sqrt(disc);
      const glm::dvec3 u = glm::normalize(ray.origin + s * ray.dir);
      const double density = sky::cloudDensity(sky::cloudNoise(u * (rc / 2000.0), 9), 0.5);
      if (density > 0.05 && density < 0.95) continue;  // at a cloud's edge
      const double brighter = cloudy.at(i, j).y / clear.at(i, j).y;
      ++total;
      cloudyPixels += density >= 0.95;
      agree += (density >= 0.95) == (brighter > 2.0);
    }
  std::printf("  %d of %d pixels agree (%d cloudy)\n", agree, total, cloudyPixels);
  EXPECT_GT(total, 100);
  EXPECT_GT(cloudyPixels, total / 5);
  EXPECT_LT(cloudyPixels, total * 4 / 5);
  EXPECT_GE(agree, total - 2);
}

// At night (the Sun 60 deg down, below the tables' lowest Sun) a deck seen from below is
// dark: no sunlight reaches it, directly nor through the sky.
TEST(CloudRender, DarkAtNight) {
  const Raw f = renderClouds(verticalCamera(10.0, 1.0), directionFromAngles(-60.0, 0.0), {layer(2000.0, 20.0)});
  const glm::dvec3 cloud = f.at(f.w / 2, f.h / 2);
  const glm::dvec3 day = renderClouds(verticalCamera(10.0, 1.0), directionFromAngles(30.0, 0.0), {layer(2000.0, 20.0)})
                             .at(f.w / 2, f.h / 2);
  std::printf("  deck from below at night %.3g, by day %.3g W m^-2 sr^-1 (G)\n", cloud.y, day.y);
  EXPECT_LT(cloud.y, 1e-6 * day.y);
}

// The same layers give the same frame (the seed, not the clock, makes the clouds); another
// seed another.
TEST(CloudRender, DeterministicWithASeed) {
  const ViewCamera cam = verticalCamera(10.0, 1.0, 120.0);
  const glm::dvec3 sun = directionFromAngles(30.0, 40.0);
  const Raw a = renderClouds(cam, sun, {layer(3000.0, 5.0, 0.5, 4)}, 0.1, 24);
  const Raw b = renderClouds(cam, sun, {layer(3000.0, 5.0, 0.5, 4)}, 0.1, 24);
  const Raw c = renderClouds(cam, sun, {layer(3000.0, 5.0, 0.5, 5)}, 0.1, 24);
  const Raw none = renderClouds(cam, sun, {}, 0.1, 24);
  EXPECT_EQ(a.hdr, b.hdr);
  EXPECT_NE(a.hdr, none.hdr);
  EXPECT_NE(a.hdr, c.hdr);
}

// The extremes: a layer at 0 m and one above the top of the atmosphere (drawn within it),
// coverage 0 and 1, optical depth 0 and 1000, seen from the ground, from 8 km and from
// space; every frame finite (ReadHdr throws on NaN or infinity). Coverage 0 and depth 0
// change nothing.
TEST(CloudRender, ExtremesStayFinite) {
  const glm::dvec3 sun = directionFromAngles(20.0, 30.0);
  ViewCamera space;
  space.positionM = {2.0e7, 0.0, 1.0e7};
  space.targetM = {0.0, 0.0, 0.0};
  space.up = {0.0, 0.0, 1.0};
  space.fovDeg = 40.0;
  const double top = atmosphereFixture().tables.topRadiusM - atmosphereFixture().tables.bottomRadiusM;
  for (const ViewCamera& cam : {verticalCamera(1.0, 1.0, 150.0), verticalCamera(8000.0, -1.0, 150.0), space}) {
    const Raw none = renderClouds(cam, sun, {}, 0.1, 16);
    EXPECT_EQ(renderClouds(cam, sun, {layer(2000.0, 10.0, 0.0)}, 0.1, 16).hdr, none.hdr);
    const Raw thin = renderClouds(cam, sun, {layer(2000.0, 0.0, 1.0)}, 0.1, 16);
    for (std::size_t k = 0; k < none.hdr.size(); ++k) EXPECT_NEAR(thin.hdr[k], none.hdr[k], 1e-4 * (1.0 + none.hdr[k]));
    for (double alt : {0.0, top + 1.0e5})
      for (double tau : {0.0, 1000.0})
        for (double cover : {0.0, 0.5, 1.0}) EXPECT_NO_THROW(renderClouds(cam, sun, {layer(alt, tau, cover)}, 0.1, 16));
    EXPECT_NO_THROW(renderClouds(cam, sun, {layer(0.0, 1000.0), layer(1000.0, 3.0, 0.5, 2), layer(top, 1.0, 0.3, 3),
                                      layer(5000.0, 1000.0, 1.0)}, 0.1, 16));
  }
}

// More than four layers, a negative depth, a coverage outside [0, 1]: refused.
TEST(CloudRender, BadLayersAreRefused) {
  AtmosphereRendering a;
  EXPECT_THROW(a.SetClouds(Layers(5, layer(1000.0, 1.0))), std::invalid_argument);
  EXPECT_THROW(a.SetClouds({layer(1000.0, -1.0)}), std::invalid_argument);
  EXPECT_THROW(a.SetClouds({layer(1000.0, 1.0, 1.5)}), std::invalid_argument);
  EXPECT_THROW(a.SetClouds({layer(1000.0, std::nan(""))}), std::invalid_argument);
  EXPECT_THROW(a.SetClouds({layer(-1.0, 1.0)}), std::invalid_argument);
  EXPECT_THROW(a.SetClouds({layer(1000.0, 1.0)}, glm::dvec3(-1.0)), std::invalid_argument);
  EXPECT_NO_THROW(a.SetClouds({layer(1000.0, 1.0)}));
  EXPECT_EQ(a.GetNumberOfCloudLayers(), 1);
}
