// Shadow tables (terrain/ShadowTable.hpp) against the per-pixel DP search they replace:
// the visible fraction looked up between samples in a table made for the Sun rounded to a
// step, against the DP search at the same point for the exact Sun (what the renderer's
// reference path computes per pixel), on the synthetic crater field.
//
// For each of --suns random Suns (elevation within --sun-spread-deg of --sun-elevation-deg,
// any azimuth) and each step, the errors |table - DP| at --points random points of the
// patch (fractional grid coordinates, on the bilinear surface): the mean over all points,
// the mean over those the DP puts in the penumbra, the 99th percentile and the largest;
// "exact Sun" is the table made for the exact Sun (what interpolation alone costs). And
// the time to make one table on every thread (what a frame pays when the Sun has moved a
// step and the table is not cached).
//
//   build/bench/umbra-bench-terrain-table [--size 512] [--seed 7] [--sun-elevation-deg 0.94]
#include "CraterField.hpp"
#include "MaximumMipmap.hpp"
#include "ShadowTable.hpp"
#include "SoftShadow.hpp"

#include <CLI/CLI.hpp>

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

using namespace umbra::terrain;

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;

struct Errors {
  std::vector<double> all, penumbra;
  void add(double value, double reference) {
    const double e = std::abs(value - reference);
    all.push_back(e);
    if (reference > 1e-3 && reference < 1.0 - 1e-3) penumbra.push_back(e);
  }
  static double mean(const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v) s += x;
    return v.empty() ? 0.0 : s / v.size();
  }
  double percentile(double p) {
    std::sort(all.begin(), all.end());
    return all[static_cast<std::size_t>(p * (all.size() - 1))];
  }
};
} // namespace

int main(int argc, char** argv) {
  CLI::App app{"Shadow tables against the per-pixel DP search"};
  int size = 512, points = 20000, suns = 8;
  long long seed = 7;
  double elevationDeg = 0.94, spreadDeg = 0.5;
  std::vector<double> stepsDeg{0.002, 0.01, 0.05};
  std::vector<double> nearTexels{0, 2, 4, 8, 16};
  app.add_option("--size", size, "Crater field samples a side")->capture_default_str();
  app.add_option("--seed", seed, "Crater field seed")->capture_default_str();
  app.add_option("--points", points, "Random points compared per Sun")->capture_default_str();
  app.add_option("--suns", suns, "Random Suns")->capture_default_str();
  app.add_option("--sun-elevation-deg", elevationDeg, "Mean Sun elevation at the patch centre")->capture_default_str();
  app.add_option("--sun-spread-deg", spreadDeg, "Sun elevations within this of the mean")->capture_default_str();
  app.add_option("--steps-deg", stepsDeg, "Rounding steps of the Sun's direction [deg]")->delimiter(',');
  app.add_option("--near-texels", nearTexels, "Stretches each point searches itself [texels]")->delimiter(',');
  CLI11_PARSE(app, argc, argv);

  CraterFieldOptions co;
  co.seed = static_cast<std::uint64_t>(seed);
  co.size = size;
  const HeightField field = makeCraterField(co);
  const MaximumMipmap mip(field);
  const ShadowOptions dp;
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> unit(0.0, 1.0);

  // Rows: for each near stretch, the exact Sun and then each rounding step.
  const std::size_t perNear = stepsDeg.size() + 1;
  std::vector<Errors> errors(nearTexels.size() * perNear), facing(errors.size());
  std::vector<double> tableSeconds(nearTexels.size(), 0.0);
  // Whether the bilinear surface at g faces the Sun (its normal by central differences
  // over a sample, as the renderer's): elsewhere the shading is dark whatever the fraction.
  auto facesSun = [&](glm::dvec2 g, glm::dvec3 sunDirection) {
    auto point = [&](glm::dvec2 q) { return (field.bodyRadiusM + field.bilinear(q.x, q.y)) * field.direction(q.x, q.y); };
    const glm::dvec3 n = glm::cross(point(g + glm::dvec2(0.5, 0.0)) - point(g - glm::dvec2(0.5, 0.0)),
                                    point(g + glm::dvec2(0.0, 0.5)) - point(g - glm::dvec2(0.0, 0.5)));
    return glm::dot(n, sunDirection) > 0.0;
  };
  for (int k = 0; k < suns; ++k) {
    SunDisc sun;
    sun.direction = sunDirectionFromElevationAzimuth((elevationDeg + spreadDeg * (2.0 * unit(rng) - 1.0)) * kDeg,
                                                     360.0 * unit(rng) * kDeg);
    std::vector<glm::dvec2> at(static_cast<std::size_t>(points));
    for (glm::dvec2& g : at) g = {unit(rng) * (size - 1), unit(rng) * (size - 1)};
    std::vector<double> reference(at.size());
    std::vector<char> faces(at.size());
#pragma omp parallel for schedule(dynamic, 64)
    for (int p = 0; p < points; ++p) {
      const glm::dvec2 g = at[static_cast<std::size_t>(p)];
      reference[static_cast<std::size_t>(p)] =
          discFractionAboveHorizon(horizonTowardsSunAt(field, mip, g, field.bilinear(g.x, g.y), sun, dp), sun);
      faces[static_cast<std::size_t>(p)] = facesSun(g, sun.direction);
    }
    for (std::size_t n = 0; n < nearTexels.size(); ++n)
      for (std::size_t s = 0; s < perNear; ++s) {
        const SunDisc rounded = s == 0 ? sun : roundedSun(sun, stepsDeg[s - 1] * kDeg);
        const auto t0 = std::chrono::steady_clock::now();
        const ShadowTable table = makeShadowTable(field, mip, rounded, dp, nearTexels[n]);
        tableSeconds[n] += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::vector<double> value(at.size());
#pragma omp parallel for schedule(dynamic, 64)
        for (int p = 0; p < points; ++p)
          value[static_cast<std::size_t>(p)] = table.fractionAt(field, mip, at[static_cast<std::size_t>(p)]);
        for (std::size_t p = 0; p < at.size(); ++p) {
          errors[n * perNear + s].add(value[p], reference[p]);
          if (faces[p]) facing[n * perNear + s].add(value[p], reference[p]);
        }
      }
  }
  std::printf("crater field seed %lld, %d x %d at 30 m (%.1f km); %d Suns %.2f +- %.2f deg up, any azimuth; "
              "%d points each; %d threads\n\n",
              seed, size, size, size * 0.03, suns, elevationDeg, spreadDeg, points, omp_get_max_threads());
  std::printf("| near stretch | Sun rounded to | mean \\|table - DP\\| | mean in the penumbra | 99th pct | max | "
              "points in the penumbra | mean where the ground faces the Sun (points) | a table takes |\n");
  std::printf("|---:|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (std::size_t n = 0; n < nearTexels.size(); ++n)
    for (std::size_t s = 0; s < perNear; ++s) {
      Errors& e = errors[n * perNear + s];
      const double p99 = e.percentile(0.99);
      char label[64];
      if (s == 0) std::snprintf(label, sizeof label, "exact Sun");
      else std::snprintf(label, sizeof label, "%g deg", stepsDeg[s - 1]);
      std::printf("| %g texels | %s | %.5f | %.4f | %.4f | %.3f | %zu | %.5f (%zu) | %.2f s |\n", nearTexels[n], label,
                  Errors::mean(e.all), Errors::mean(e.penumbra), p99, e.all.back(), e.penumbra.size(),
                  Errors::mean(facing[n * perNear + s].all), facing[n * perNear + s].all.size(),
                  tableSeconds[n] / (suns * perNear));
    }
  return 0;
}
