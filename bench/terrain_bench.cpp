// Soft terrain shadows: the dynamic-programming search (DP) against uniform
// stepping, both against the reference, on the synthetic crater field, at several DEM sizes.
//
// Error: |fraction - reference| at --receivers random receivers (mean, sigma, 99th
// percentile). Speed: the same --timed random receivers (one thread, the methods
// interleaved, best of --repeats), as microseconds per receiver. For each size the speed
// ratio is taken against the cheapest uniform step count whose mean error is not below DP's.
// Prints Markdown tables for docs/accuracy-vs-speed/terrain.md.
//
//   build/bench/umbra-bench-terrain [--sizes 512,1024,2048,4096] [--sun-elevation-deg 1.5]
#include "CraterField.hpp"
#include "MaximumMipmap.hpp"
#include "SoftShadow.hpp"

#include <CLI/CLI.hpp>

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <random>
#include <string>
#include <vector>

using namespace umbra::terrain;

namespace {

double seconds(const std::chrono::steady_clock::time_point& t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

struct Stats {
  double mean = 0.0, sigma = 0.0, p99 = 0.0, max = 0.0, penumbraMean = 0.0;
};

/// Errors over all receivers, and the mean over those the reference puts in the penumbra.
Stats errorStats(const std::vector<double>& values, const std::vector<double>& reference) {
  std::vector<double> e(values.size());
  double penumbraSum = 0.0;
  int penumbra = 0;
  for (std::size_t k = 0; k < e.size(); ++k) {
    e[k] = std::abs(values[k] - reference[k]);
    if (reference[k] > 1e-3 && reference[k] < 1.0 - 1e-3) penumbraSum += e[k], ++penumbra;
  }
  Stats s;
  s.penumbraMean = penumbra ? penumbraSum / penumbra : 0.0;
  s.mean = std::accumulate(e.begin(), e.end(), 0.0) / e.size();
  for (double x : e) s.sigma += (x - s.mean) * (x - s.mean);
  s.sigma = std::sqrt(s.sigma / e.size());
  std::sort(e.begin(), e.end());
  s.p99 = e[static_cast<std::size_t>(0.99 * (e.size() - 1))];
  s.max = e.back();
  return s;
}

struct Config {
  std::string label;
  ShadowOptions options;
  double timeUs = 1e300;  ///< per receiver, best of the repeats
  double samples = 0.0;   ///< heights / texels looked at per receiver
  Stats error;
};

} // namespace

int main(int argc, char** argv) {
  CLI::App app{"Soft terrain shadows: DP vs uniform stepping vs the reference"};
  std::vector<int> sizes{512, 1024, 2048, 4096};
  std::vector<int> levels{4, 6, 8};
  std::vector<int> steps{32, 64, 128, 256, 512, 1024, 2048};
  int receivers = 400, timed = 20000, repeats = 3, strips = 32;
  double elevationDeg = 1.5, azimuthDeg = 140.0, referenceStep = 0.125;
  std::uint64_t seed = 1;
  app.add_option("--sizes", sizes, "DEM sizes (samples per side)")->delimiter(',');
  app.add_option("--levels", levels, "N' values for DP")->delimiter(',');
  app.add_option("--steps", steps, "Step counts for uniform stepping")->delimiter(',');
  app.add_option("--receivers", receivers, "Random receivers compared with the reference")->capture_default_str();
  app.add_option("--timed", timed, "Random receivers timed per method")->capture_default_str();
  app.add_option("--repeats", repeats, "Timing runs per method (the fastest counts)")->capture_default_str();
  app.add_option("--strips", strips, "Reference: vertical strips of the disc")->capture_default_str();
  app.add_option("--reference-step", referenceStep, "Reference: step along each strip [texels]")->capture_default_str();
  app.add_option("--sun-elevation-deg", elevationDeg, "Sun elevation at the DEM centre")->capture_default_str();
  app.add_option("--sun-azimuth-deg", azimuthDeg, "Sun azimuth (from north towards east)")->capture_default_str();
  app.add_option("--seed", seed, "Crater field seed")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  constexpr double deg = 3.14159265358979323846 / 180.0;
  SunDisc sun;
  sun.direction = sunDirectionFromElevationAzimuth(elevationDeg * deg, azimuthDeg * deg);
  std::printf("crater field seed %llu, 30 m/texel, Moon (R = 1737.4 km); Sun at %.2f deg elevation, %.0f deg "
              "azimuth, uniform disc; %d reference receivers (%d strips, %.3g-texel steps); %d timed receivers, "
              "1 thread, best of %d; %d threads for the rest\n\n",
              static_cast<unsigned long long>(seed), elevationDeg, azimuthDeg, receivers, strips, referenceStep, timed,
              repeats, omp_get_max_threads());

  struct Summary {
    int size;
    Config dp, uniform;
    bool matched;
  };
  std::vector<Summary> summaries;

  for (int size : sizes) {
    auto t0 = std::chrono::steady_clock::now();
    CraterFieldOptions co;
    co.seed = seed;
    co.size = size;
    const HeightField field = makeCraterField(co);
    const double generateS = seconds(t0);
    t0 = std::chrono::steady_clock::now();
    const MaximumMipmap mip(field);
    const double mipS = seconds(t0);

    std::mt19937_64 rng(1234 + size);
    std::uniform_int_distribution<int> pick(0, size - 1);
    auto randomReceivers = [&](int n) {
      std::vector<std::pair<int, int>> r(n);
      for (auto& p : r) p = {pick(rng), pick(rng)};
      return r;
    };
    const auto errorSet = randomReceivers(receivers), timeSet = randomReceivers(timed);

    ShadowOptions refOptions;
    refOptions.method = ShadowMethod::Reference;
    refOptions.referenceStrips = strips;
    refOptions.referenceStepTexels = referenceStep;
    std::vector<double> reference(receivers);
    t0 = std::chrono::steady_clock::now();
#pragma omp parallel for schedule(dynamic, 1)
    for (int k = 0; k < receivers; ++k)
      reference[k] = visibleFraction(field, mip, errorSet[k].first, errorSet[k].second, sun, refOptions);
    const double referenceS = seconds(t0);
    int penumbra = 0;
    for (double v : reference) penumbra += v > 1e-3 && v < 1.0 - 1e-3;

    std::vector<Config> configs;
    for (int n : levels) {
      Config c;
      c.label = "DP, N' = " + std::to_string(n);
      c.options.levels = n;
      configs.push_back(c);
    }
    for (int n : steps) {
      Config c;
      c.label = "uniform, " + std::to_string(n) + " steps";
      c.options.method = ShadowMethod::Uniform;
      c.options.uniformSteps = n;
      configs.push_back(c);
    }
    for (Config& c : configs) {
      std::vector<double> values(receivers);
#pragma omp parallel for schedule(dynamic, 16)
      for (int k = 0; k < receivers; ++k)
        values[k] = visibleFraction(field, mip, errorSet[k].first, errorSet[k].second, sun, c.options);
      c.error = errorStats(values, reference);
    }
    // Timing: one thread, methods interleaved, best of the repeats.
    double sink = 0.0;
    for (int rep = 0; rep < repeats; ++rep)
      for (Config& c : configs) {
        long long samples = 0;
        const auto t = std::chrono::steady_clock::now();
        for (const auto& [i, j] : timeSet) {
          long long n = 0;
          sink += visibleFraction(field, mip, i, j, sun, c.options, &n);
          samples += n;
        }
        c.timeUs = std::min(c.timeUs, seconds(t) * 1e6 / timed);
        c.samples = double(samples) / timed;
      }

    std::printf("### %d x %d (%.1f km); crater field %.2f s, mipmap %.3f s, reference %.1f s; %d of %d receivers in "
                "the penumbra (checksum %.3f)\n\n",
                size, size, size * 0.03, generateS, mipS, referenceS, penumbra, receivers, sink / repeats);
    std::printf("| method | samples / receiver | time / receiver [µs] | mean error | σ | 99th pct | max | mean error in "
                "the penumbra |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const Config& c : configs)
      std::printf("| %s | %.1f | %.2f | %.5f | %.5f | %.5f | %.4f | %.4f |\n", c.label.c_str(), c.samples, c.timeUs,
                  c.error.mean, c.error.sigma, c.error.p99, c.error.max, c.error.penumbraMean);
    std::printf("\n");

    // DP at the default N' against the cheapest uniform stepping at equal or lower mean error.
    const Config* dp = nullptr;
    for (const Config& c : configs)
      if (c.options.method == ShadowMethod::DynamicProgramming && c.options.levels == ShadowOptions{}.levels) dp = &c;
    if (!dp) dp = &configs.front();
    const Config* match = nullptr;
    for (const Config& c : configs)
      if (c.options.method == ShadowMethod::Uniform && c.error.mean <= dp->error.mean &&
          (!match || c.timeUs < match->timeUs))
        match = &c;
    bool matched = match != nullptr;
    if (!match)  // none as accurate: the most accurate uniform stepping tried
      for (const Config& c : configs)
        if (c.options.method == ShadowMethod::Uniform && (!match || c.error.mean < match->error.mean)) match = &c;
    summaries.push_back({size, *dp, *match, matched});
  }

  std::printf("### DP against uniform stepping at equal or lower error\n\n");
  std::printf("| DEM | DP | µs | mean error | uniform | µs | mean error | uniform / DP time |\n");
  std::printf("|---|---|---:|---:|---|---:|---:|---:|\n");
  for (const Summary& s : summaries)
    std::printf("| %d² | %s | %.2f | %.5f | %s%s | %.2f | %.5f | %.2f× |\n", s.size, s.dp.label.c_str(), s.dp.timeUs,
                s.dp.error.mean, s.uniform.label.c_str(), s.matched ? "" : " (most accurate tried, still worse)",
                s.uniform.timeUs, s.uniform.error.mean, s.uniform.timeUs / s.dp.timeUs);
  return 0;
}
