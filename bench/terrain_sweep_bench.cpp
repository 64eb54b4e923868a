// The sweep (terrain/HorizonSweep.hpp), the fast path of `umbra terrain lighting`, against
// the DP search at every sample (`--method dp`, the reference): |sweep - DP| over all
// samples of the synthetic crater field (the mean, the mean over the samples the DP puts in
// the penumbra, the 99th percentile) and the time of one map on every thread, for --suns
// random Suns (elevation within --sun-spread-deg of --sun-elevation-deg, any azimuth).
//
//   build/bench/umbra-bench-terrain-sweep [--sizes 256,512,1024] [--suns 4]
#include "CraterField.hpp"
#include "HorizonSweep.hpp"
#include "MaximumMipmap.hpp"
#include "SoftShadow.hpp"

#include <CLI/CLI.hpp>

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

using namespace umbra::terrain;

int main(int argc, char** argv) {
  CLI::App app{"The lighting sweep against the DP search at every sample"};
  std::vector<int> sizes{256, 512, 1024};
  int suns = 4;
  long long seed = 7;
  double elevationDeg = 0.94, spreadDeg = 0.5;
  app.add_option("--sizes", sizes, "Crater field sizes (samples a side)")->delimiter(',');
  app.add_option("--suns", suns, "Random Suns")->capture_default_str();
  app.add_option("--seed", seed, "Crater field seed")->capture_default_str();
  app.add_option("--sun-elevation-deg", elevationDeg, "Mean Sun elevation at the patch centre")->capture_default_str();
  app.add_option("--sun-spread-deg", spreadDeg, "Sun elevations within this of the mean")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  auto seconds = [](auto t0) { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };

  std::printf("crater field seed %lld at 30 m; %d Suns %.2f +- %.2f deg up, any azimuth; %d threads\n\n", seed, suns,
              elevationDeg, spreadDeg, omp_get_max_threads());
  std::printf("| DEM | DP map | sweep map | DP / sweep | mean \\|sweep - DP\\| | mean in the penumbra | 99th pct | "
              "samples in the penumbra |\n|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (int size : sizes) {
    CraterFieldOptions co;
    co.seed = static_cast<std::uint64_t>(seed);
    co.size = size;
    const HeightField f = makeCraterField(co);
    const MaximumMipmap mip(f);
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double dpS = 0.0, sweepS = 0.0, sum = 0.0, penumbraSum = 0.0;
    std::size_t penumbra = 0, n = 0;
    std::vector<double> errors;
    for (int k = 0; k < suns; ++k) {
      SunDisc sun;
      sun.direction = sunDirectionFromElevationAzimuth((elevationDeg + spreadDeg * (2.0 * unit(rng) - 1.0)) * kDeg,
                                                       360.0 * unit(rng) * kDeg);
      auto t0 = std::chrono::steady_clock::now();
      const std::vector<double> dp = visibleFractionMap(f, mip, sun, ShadowOptions{});
      dpS += seconds(t0);
      t0 = std::chrono::steady_clock::now();
      const std::vector<float> sweep = sweepVisibleFractionMap(f, sun);
      sweepS += seconds(t0);
      for (std::size_t s = 0; s < dp.size(); s += 7) {  // (every 7th sample for the percentile)
        const double e = std::abs(sweep[s] - dp[s]);
        errors.push_back(e);
        sum += e, ++n;
        if (dp[s] > 1e-3 && dp[s] < 1.0 - 1e-3) penumbraSum += e, ++penumbra;
      }
    }
    std::sort(errors.begin(), errors.end());
    std::printf("| %d² | %.3f s | %.4f s | %.0fx | %.4f | %.3f | %.3f | %zu |\n", size, dpS / suns, sweepS / suns,
                dpS / sweepS, sum / n, penumbra ? penumbraSum / penumbra : 0.0,
                errors[static_cast<std::size_t>(0.99 * (errors.size() - 1))], penumbra);
  }
  return 0;
}
