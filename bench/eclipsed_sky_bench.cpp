// The eclipsed sky's Monte-Carlo reference (atmosphere/MonteCarloSky.hpp): its radiance
// along the vertical through the Sun in totality and without the Moon, its statistical
// error against its time, and the time of one image. The scene is built, not looked up: an
// observer on the ground, the Sun at --sun-zenith-deg, the Moon on the line to the Sun at
// the distance that makes the umbra --umbra-km across through the observer
// (occluderDistanceForUmbraM), --offset-km off that line for a partial phase.
// With --fast, the quadrature (atmosphere/EclipsedSky.hpp) against it instead.
// Prints Markdown for docs/accuracy-vs-speed/atmosphere-tables.md ("The sky of a solar eclipse").
//
//   build/bench/umbra-bench-eclipsed-sky [--preset earth] [--sun-zenith-deg 26.1]
//       [--umbra-km 114.7] [--paths 100000] [--image 320x180 --image-paths 64]
//   build/bench/umbra-bench-eclipsed-sky --fast [--reference-paths 400000] [--image 320x180]
#include "Atmosphere.hpp"
#include "EclipsedSky.hpp"
#include "MonteCarloSky.hpp"
#include "ShadowLut.hpp"
#include "Sky.hpp"

#include <CLI/CLI.hpp>

#include <glm/geometric.hpp>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace umbra;

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr double kMoonRadiusM = 1737.4e3;

glm::dvec3 dir(double zenithRad, double azimuthRad) {
  return {std::sin(zenithRad) * std::cos(azimuthRad), std::sin(zenithRad) * std::sin(azimuthRad), std::cos(zenithRad)};
}

/// The quadrature against the reference at the zenith, 2 deg and 30 deg up at azimuths 0, 90,
/// 180 and 270 deg from the Sun, each wavelength, with the Moon and without; the Sun's
/// visible fraction from a 256 x 256 airless shadow LuT over the scene's distances (the
/// quadrature calls it some 10^7 times). The tables (4 orders, the sky's sizes) are made
/// once and not timed.
int fastAgainstReference(const atmosphere::Atmosphere& atm, const glm::dvec3& observer, const glm::dvec3& sunDirection,
                         const glm::dvec3& sunM, const glm::dvec3& moonM, double moonDistanceM,
                         const atmosphere::SunVisibility& exact, std::int64_t referencePaths, int imageW, int imageH,
                         const std::vector<std::string>& knobs) {
  std::vector<glm::dvec3> views{dir(0, 0)};
  std::vector<std::string> names{"zenith"};
  for (double up : {2.0, 30.0})
    for (double a : {0.0, 90.0, 180.0, 270.0}) {
      views.push_back(dir((90.0 - up) * kDeg, a * kDeg));
      names.push_back(std::to_string(static_cast<int>(up)) + "° up, " + std::to_string(static_cast<int>(a)) + "°");
    }
  const eclipse::SunOccluderSystem system{eclipse::kSunRadiusM, kMoonRadiusM, glm::length(sunM - moonM)};
  const eclipse::LutRange range = eclipse::lutRangeForDistances(system, moonDistanceM - 3e6, moonDistanceM + 3e6, true);
  eclipse::ShadowLutParams lp;
  lp.uMin = range.uMin, lp.uMax = range.uMax, lp.vMin = range.vMin, lp.vMax = range.vMax, lp.vLowFraction = range.vLowFraction;
  const eclipse::ShadowLut lut = eclipse::buildAirlessShadowLut(lp);
  const atmosphere::SunVisibility tabulated = [&](const glm::dvec3& p) {
    return eclipse::eclipseFactor(p, sunM, eclipse::kSunRadiusM, {moonM, kMoonRadiusM}, &lut).g;
  };
  const atmosphere::AtmosphereTables tables =
      atmosphere::precompute(atm, atmosphere::skyPrecomputeOptions(atm, 4, std::acos(std::clamp(sunDirection.z, -1.0, 1.0))));

  struct Level {
    const char* name;
    atmosphere::EclipsedSkyOptions o;
  };
  std::vector<Level> levels;
  levels.push_back({"draft: field 13x8x12, incoming 8x8x16, 3 orders, diffuse 6x6, view 32",
                    atmosphere::draftEclipsedSkyOptions()});
  atmosphere::EclipsedSkyOptions o;
  levels.push_back({"default: field 25x16x16, incoming 12x16x24, 4 orders, diffuse 8x8, view 48", atmosphere::EclipsedSkyOptions{}});
  o = {};
  o.fieldSamples = 32, o.incomingZenith = 24, o.incomingAzimuths = 24, o.incomingSamples = 32, o.viewSamples = 64,
  o.orders = 6, o.diffuseZenith = 16, o.diffuseAzimuths = 16;
  levels.push_back({"fine: field 25x16x32, incoming 24x24x32, 6 orders, diffuse 16x16, view 64", o});
  if (!knobs.empty()) levels.clear();
  for (const std::string& k : knobs) {
    o = {};
    if (std::sscanf(k.c_str(), "%d,%d,%d,%d,%d,%d,%d,%d,%d,%d", &o.fieldElevations, &o.fieldAzimuths, &o.fieldSamples,
                    &o.incomingZenith, &o.incomingAzimuths, &o.incomingSamples, &o.orders, &o.diffuseZenith,
                    &o.diffuseAzimuths, &o.viewSamples) != 10 || !o.validate().empty()) {
      std::fprintf(stderr, "--knobs: expected 10 valid numbers, got '%s' (%s)\n", k.c_str(), o.validate().c_str());
      return 2;
    }
    levels.push_back({k.c_str(), o});
  }

  for (int moon = 1; moon >= 0; --moon) {
    atmosphere::MonteCarloSkyOptions mc;
    mc.paths = moon ? referencePaths : referencePaths / 4;
    const atmosphere::MonteCarloSky reference =
        atmosphere::monteCarloSkyRadiance(atm, observer, views, sunDirection, moon ? exact : atmosphere::SunVisibility{}, mc);
    std::printf("%s: the quadrature against the Monte-Carlo (%lld paths, %.1f s), per cent\n\n",
                moon ? "With the Moon" : "Without the Moon", static_cast<long long>(mc.paths), reference.seconds);
    std::printf("| knobs | time [s] | nm |");
    for (const auto& n : names) std::printf(" %s |", n.c_str());
    std::printf("\n|---|---:|---:|");
    for (std::size_t k = 0; k < names.size(); ++k) std::printf("---:|");
    std::printf("\n");
    for (int w = 0; w < 3; ++w) {
      std::printf("| Monte-Carlo: standard error | | %.0f |", atm.wavelengthsNm[static_cast<std::size_t>(w)]);
      for (const auto& r : reference.directions)
        std::printf(" %.1f |", 100.0 * r.standardError[static_cast<std::size_t>(w)] / r.radiance[static_cast<std::size_t>(w)]);
      std::printf("\n");
    }
    for (const Level& level : levels) {
      if (!moon && knobs.empty() && std::string(level.name).rfind("default", 0) != 0) continue;
      const atmosphere::EclipsedSky sky = atmosphere::eclipsedSkyRadiance(
          tables, atm, observer, views, sunDirection, moon ? tabulated : atmosphere::SunVisibility{}, level.o);
      for (int w = 0; w < 3; ++w) {
        const std::size_t wi = static_cast<std::size_t>(w);
        std::printf("| %s | %.2f | %.0f |", w == 0 ? level.name : "", sky.seconds, atm.wavelengthsNm[wi]);
        for (std::size_t k = 0; k < views.size(); ++k)
          std::printf(" %+.1f |", 100.0 * (sky.radiance[k][wi] / reference.directions[k].radiance[wi] - 1.0));
        std::printf("\n");
      }
    }
    std::printf("\n");
  }

  if (imageW > 0) {
    std::vector<glm::dvec3> pixels;
    for (int y = 0; y < imageH; ++y)
      for (int x = 0; x < imageW; ++x) {
        const double elevation = (y + 0.5) / imageH * 50.0 * kDeg, azimuth = ((x + 0.5) / imageW - 0.5) * 90.0 * kDeg;
        pixels.push_back(dir(0.5 * kPi - elevation, azimuth));
      }
    const atmosphere::EclipsedSky sky = atmosphere::eclipsedSkyRadiance(tables, atm, observer, pixels, sunDirection, tabulated);
    const atmosphere::EclipsedSky field = atmosphere::eclipsedSkyRadiance(tables, atm, observer, {dir(0, 0)}, sunDirection, tabulated);
    std::printf("One %dx%d image by the quadrature (default knobs): %.1f s, of which the light field %.1f s\n", imageW,
                imageH, sky.seconds, field.seconds);
  }
  return 0;
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"The eclipsed sky by Monte-Carlo: radiance, statistical error and time"};
  std::string preset = "earth";
  double sunZenithDeg = 26.1, umbraKm = 114.7, offsetKm = 0.0, sunDistanceAu = 1.0105;
  std::int64_t paths = 100000;
  std::string image;
  int imagePaths = 64;
  bool fast = false;
  std::int64_t referencePaths = 400000;
  app.add_option("--preset", preset)->capture_default_str();
  app.add_option("--sun-zenith-deg", sunZenithDeg)->capture_default_str();
  app.add_option("--umbra-km", umbraKm, "The umbra's width through the observer, across the axis")->capture_default_str();
  app.add_option("--offset-km", offsetKm, "The Moon's offset from the observer-Sun line (a partial phase)")->capture_default_str();
  app.add_option("--sun-distance-au", sunDistanceAu)->capture_default_str();
  app.add_option("--paths", paths, "Paths per direction and wavelength")->capture_default_str();
  app.add_option("--image", image, "Also time one image of WxH directions (a 90 x 50 degree field towards the Sun's azimuth)");
  app.add_option("--image-paths", imagePaths, "Paths per pixel and wavelength of the image")->capture_default_str();
  app.add_flag("--fast", fast,
               "Instead: the quadrature (atmosphere/EclipsedSky.hpp) against the Monte-Carlo at the zenith, 2 deg "
               "and 30 deg up at 4 azimuths, with the Moon and without, error against time over its knobs (with --image: "
               "the time of that image by the quadrature)");
  std::vector<std::string> knobs;
  app.add_option("--knobs", knobs,
                 "With --fast, these configurations instead of draft/default/fine: field elevations, azimuths, samples, "
                 "incoming zenith, azimuths, samples, orders, diffuse zenith, azimuths, view samples (comma-separated)");
  app.add_option("--reference-paths", referencePaths, "Monte-Carlo paths of --fast's reference")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  const atmosphere::Atmosphere atm = atmosphere::loadAtmosphere(preset, {680.0, 550.0, 440.0});
  const double sunDistanceM = sunDistanceAu * 149597870700.0;
  const glm::dvec3 observer(0.0, 0.0, atm.bottomRadiusM), sunDirection = dir(sunZenithDeg * kDeg, 0.0);
  const glm::dvec3 sunM = observer + sunDistanceM * sunDirection;
  const double moonDistanceM =
      eclipse::occluderDistanceForUmbraM(sunDistanceM, eclipse::kSunRadiusM, kMoonRadiusM, 0.5 * umbraKm * 1e3);
  const glm::dvec3 across = dir(sunZenithDeg * kDeg - 0.5 * kPi, 0.0);
  const glm::dvec3 moonM = observer + moonDistanceM * sunDirection + offsetKm * 1e3 * across;
  const atmosphere::SunVisibility shadow = [&](const glm::dvec3& p) {
    return eclipse::eclipseFactor(p, sunM, eclipse::kSunRadiusM, {moonM, kMoonRadiusM}, nullptr).g;
  };
  std::printf("%s, 680 / 550 / 440 nm, %d threads; the Sun %.1f deg from the zenith, umbra %.1f km, Moon offset %.0f km "
              "(visible fraction at the observer %.4f)\n\n",
              preset.c_str(), omp_get_max_threads(), sunZenithDeg, umbraKm, offsetKm, shadow(observer));

  if (fast) {
    int w = 0, h = 0;
    if (!image.empty() && (std::sscanf(image.c_str(), "%dx%d", &w, &h) != 2 || w < 1 || h < 1)) {
      std::fprintf(stderr, "--image: expected WxH, got '%s'\n", image.c_str());
      return 2;
    }
    return fastAgainstReference(atm, observer, sunDirection, sunM, moonM, moonDistanceM, shadow, referencePaths, w, h, knobs);
  }

  // The vertical through the Sun: signed zenith angle, positive towards the Sun.
  std::vector<double> zenithDeg;
  for (double z = -88.0; z <= 88.0 + 1e-9; z += (std::abs(z) >= 70.0 ? 4.0 : 10.0)) zenithDeg.push_back(z);
  std::vector<glm::dvec3> views;
  for (double z : zenithDeg) views.push_back(dir(std::abs(z) * kDeg, z >= 0.0 ? 0.0 : kPi));
  atmosphere::MonteCarloSkyOptions o;
  o.paths = paths;
  const atmosphere::MonteCarloSky eclipsed = atmosphere::monteCarloSkyRadiance(atm, observer, views, sunDirection, shadow, o);
  const atmosphere::MonteCarloSky clear = atmosphere::monteCarloSkyRadiance(atm, observer, views, sunDirection, {}, o);
  std::printf("The vertical through the Sun (%lld paths a direction and wavelength: %.1f s eclipsed, %.1f s clear), "
              "radiance per unit solar irradiance [1/sr] +- its standard error:\n\n",
              static_cast<long long>(paths), eclipsed.seconds, clear.seconds);
  std::printf("| zenith angle (+: the Sun's side) | 680 nm | 550 nm | 440 nm | clear / eclipsed at 550 nm |\n|---|---|---|---|---|\n");
  for (std::size_t k = 0; k < views.size(); ++k) {
    const auto& e = eclipsed.directions[k];
    std::printf("| %+.0f |", zenithDeg[k]);
    for (int w = 0; w < 3; ++w) std::printf(" %.3e +- %.0f %% |", e.radiance[w], 100.0 * e.standardError[w] / e.radiance[w]);
    std::printf(" %.0f |\n", clear.directions[k].radiance[1] / e.radiance[1]);
  }

  // Error against time at the zenith.
  std::printf("\nThe zenith's standard error against the paths (550 nm):\n\n| paths | time [s] | radiance | standard error |\n|---|---|---|---|\n");
  for (std::int64_t n = 1000; n <= paths; n *= 4) {
    o.paths = n;
    const atmosphere::MonteCarloSky z = atmosphere::monteCarloSkyRadiance(atm, observer, {dir(0, 0)}, sunDirection, shadow, o);
    std::printf("| %lld | %.3f | %.3e | %.1f %% |\n", static_cast<long long>(n), z.seconds, z.directions[0].radiance[1],
                100.0 * z.directions[0].standardError[1] / z.directions[0].radiance[1]);
  }

  if (!image.empty()) {
    int w = 0, h = 0;
    if (std::sscanf(image.c_str(), "%dx%d", &w, &h) != 2 || w < 1 || h < 1) {
      std::fprintf(stderr, "--image: expected WxH, got '%s'\n", image.c_str());
      return 2;
    }
    std::vector<glm::dvec3> pixels;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double elevation = (y + 0.5) / h * 50.0 * kDeg, azimuth = ((x + 0.5) / w - 0.5) * 90.0 * kDeg;
        pixels.push_back(dir(0.5 * kPi - elevation, azimuth));
      }
    o.paths = imagePaths;
    const atmosphere::MonteCarloSky sky = atmosphere::monteCarloSkyRadiance(atm, observer, pixels, sunDirection, shadow, o);
    double meanRelative = 0.0;
    for (const auto& p : sky.directions)
      meanRelative += p.radiance[1] > 0.0 ? p.standardError[1] / p.radiance[1] : 1.0;
    std::printf("\nOne %dx%d image, %d paths a pixel and wavelength: %.1f s; mean standard error of a pixel at 550 nm %.0f %%\n",
                w, h, imagePaths, sky.seconds, 100.0 * meanRelative / static_cast<double>(pixels.size()));
  }
  return 0;
}
