// Speed against accuracy of the airless eclipse-shadow LuT.
// For each size, the build time (best of --repeats runs) and the error of the bilinearly
// sampled LuT against a 1024x1024 reference LuT and against the exact shadow function.
// Prints a Markdown table for docs/accuracy-vs-speed/eclipse-luts.md.
//
//   build/bench/umbra-bench-shadow-lut [--sizes 64,128,256,512] [--reference 1024] [--repeats 3]
#include "ShadowLut.hpp"

#include <CLI/CLI.hpp>

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

using namespace umbra::eclipse;

namespace {
double seconds(const std::chrono::steady_clock::time_point& t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
} // namespace

int main(int argc, char** argv) {
  CLI::App app{"Build time and error of the airless shadow LuT at several sizes"};
  std::vector<int> sizes{64, 128, 256, 512};
  int referenceSize = 1024, repeats = 3, exactSamples = 20000;
  double farU = 0.1;
  std::vector<double> tolerances{1e-3, 1e-4, 1e-6, 1e-8, 1e-10};
  int toleranceSize = 256;
  app.add_option("--sizes", sizes, "LuT sizes to measure")->delimiter(',');
  app.add_option("--reference", referenceSize, "Size of the reference LuT")->capture_default_str();
  app.add_option("--repeats", repeats, "Builds per size (the fastest counts)")->capture_default_str();
  app.add_option("--exact-samples", exactSamples, "Random (u, v) points compared with the exact function")->capture_default_str();
  app.add_option("--far-u", farU, "Errors are also given for u >= this (away from the occluder)")->capture_default_str();
  app.add_option("--tolerances", tolerances, "Quadrature tolerances to measure")->delimiter(',');
  app.add_option("--tolerance-size", toleranceSize, "LuT size for the tolerance table")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  auto t0 = std::chrono::steady_clock::now();
  const ShadowLut reference = buildAirlessShadowLut({referenceSize, referenceSize});
  const double referenceTime = seconds(t0);

  // Random points over the LuT for the comparison with the exact function.
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<LutCoords> points(exactSamples);
  std::vector<double> exact(exactSamples);
  for (auto& p : points) p = {uniform(rng), uniform(rng)};
#pragma omp parallel for
  for (int k = 0; k < exactSamples; ++k) exact[k] = airlessShadow(points[k]);

  std::printf("threads: %d; reference %dx%d built in %.3f s\n\n", omp_get_max_threads(), referenceSize,
              referenceSize, referenceTime);
  std::printf("| size | build time [s] | max error vs %d² (all u) | max error vs %d² (u ≥ %.2g) | mean error vs %d² "
              "| max error vs exact (u ≥ %.2g) | mean error vs exact |\n",
              referenceSize, referenceSize, farU, referenceSize, farU);
  std::printf("|---:|---:|---:|---:|---:|---:|---:|\n");
  for (int n : sizes) {
    double best = 1e300;
    ShadowLut lut;
    for (int r = 0; r < repeats; ++r) {
      t0 = std::chrono::steady_clock::now();
      lut = buildAirlessShadowLut({n, n});
      best = std::min(best, seconds(t0));
    }
    // Against the reference: both sampled at the reference's texel centres.
    double maxAll = 0.0, maxFar = 0.0, sumAll = 0.0;
#pragma omp parallel for reduction(max : maxAll, maxFar) reduction(+ : sumAll)
    for (int j = 0; j < referenceSize; ++j) {
      for (int i = 0; i < referenceSize; ++i) {
        const LutCoords c{(i + 0.5) / referenceSize, (j + 0.5) / referenceSize};
        const double e = std::abs(lut.sample(c).r - reference.texel(i, j).r);
        maxAll = std::max(maxAll, e);
        if (c.u >= farU) maxFar = std::max(maxFar, e);
        sumAll += e;
      }
    }
    double maxExact = 0.0, sumExact = 0.0;
    for (int k = 0; k < exactSamples; ++k) {
      const double e = std::abs(lut.sample(points[k]).r - exact[k]);
      if (points[k].u >= farU) maxExact = std::max(maxExact, e);
      sumExact += e;
    }
    std::printf("| %d | %.4f | %.2e | %.2e | %.2e | %.2e | %.2e |\n", n, best, maxAll, maxFar,
                sumAll / (double(referenceSize) * referenceSize), maxExact, sumExact / exactSamples);
  }

  // The quadrature knob: tolerance of the per-texel integral, against a 1e-13 build.
  std::printf("\nPer-texel quadrature tolerance at %dx%d, against a build with tolerance 1e-13:\n\n", toleranceSize,
              toleranceSize);
  std::printf("| relative tolerance | build time [s] | max error |\n|---:|---:|---:|\n");
  const ShadowLut tight = buildAirlessShadowLut({toleranceSize, toleranceSize, kDefaultLimbDarkening, 1e-13});
  for (double tol : tolerances) {
    double best = 1e300;
    ShadowLut lut;
    for (int r = 0; r < repeats; ++r) {
      t0 = std::chrono::steady_clock::now();
      lut = buildAirlessShadowLut({toleranceSize, toleranceSize, kDefaultLimbDarkening, tol});
      best = std::min(best, seconds(t0));
    }
    double maxErr = 0.0;
    for (std::size_t k = 0; k < lut.rgb.size(); ++k) maxErr = std::max(maxErr, double(std::abs(lut.rgb[k] - tight.rgb[k])));
    std::printf("| %.0e | %.4f | %.2e |\n", tol, best, maxErr);
  }
  return 0;
}
