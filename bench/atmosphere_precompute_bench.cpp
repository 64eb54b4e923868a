// Speed against accuracy of the atmosphere tables (Bruneton 2017 scheme, issue #3):
// time per stage and in total for table sizes, scattering orders and refraction, and the
// error of the sky radiance looked up in each against a reference configuration.
// Prints Markdown for docs/accuracy-vs-speed.md.
//
//   build/bench/umbra-bench-atmosphere [--preset earth] [--wavelengths 3] [--skip-reference]
#include "Atmosphere.hpp"
#include "Precompute.hpp"
#include "Spectrum.hpp"

#include <CLI/CLI.hpp>

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

using namespace umbra::atmosphere;

namespace {

struct Config {
  const char* name;
  PrecomputeOptions options;
};

PrecomputeOptions scaled(double f, int orders, bool refraction) {
  PrecomputeOptions o;
  o.transmittanceWidth = static_cast<int>(256 * f);
  o.transmittanceHeight = static_cast<int>(64 * f);
  o.scatteringR = static_cast<int>(32 * f);
  o.scatteringMu = 2 * static_cast<int>(64 * f);
  o.scatteringMuS = static_cast<int>(32 * f);
  o.scatteringNu = std::max(2, static_cast<int>(8 * f));
  o.irradianceWidth = static_cast<int>(64 * f);
  o.irradianceHeight = static_cast<int>(16 * f);
  o.orders = orders;
  o.refraction = refraction;
  return o;
}

struct Probe {
  double r, mu, muS, nu;
};

} // namespace

int main(int argc, char** argv) {
  CLI::App app{"Atmosphere tables: time and error per configuration"};
  std::string preset = "earth";
  int wavelengths = 3, probes = 3000;
  app.add_option("--preset", preset)->capture_default_str();
  app.add_option("--wavelengths", wavelengths, "3 (680/550/440 nm) or N between 360 and 830 nm")->capture_default_str();
  app.add_option("--probes", probes, "Random view/sun geometries compared")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  const WavelengthSet set = wavelengths == 3 ? WavelengthSet::rgb() : WavelengthSet::uniform(wavelengths);
  const Atmosphere atm = loadAtmosphere(preset, set.nm);

  // Observers from the ground to 60 km, every view direction, the Sun above -10 degrees.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Probe> geometry(probes);
  for (auto& p : geometry) {
    p.r = atm.bottomRadiusM + 60e3 * unit(rng) * unit(rng);
    p.mu = 2.0 * unit(rng) - 1.0;
    p.muS = -0.17 + 1.17 * unit(rng);
    const double phi = M_PI * unit(rng);
    p.nu = p.mu * p.muS + std::cos(phi) * std::sqrt((1 - p.mu * p.mu) * (1 - p.muS * p.muS));
  }

  const Config reference{"reference: 1.5x sizes, 6 orders", scaled(1.5, 6, false)};
  const Config configs[] = {{"0.5x sizes, 4 orders", scaled(0.5, 4, false)},
                            {"default sizes, 2 orders", scaled(1.0, 2, false)},
                            {"default sizes, 4 orders", scaled(1.0, 4, false)},
                            {"default sizes, 4 orders, refraction (10 km)", scaled(1.0, 4, true)}};

  auto sky = [&](const AtmosphereTables& t) {
    std::vector<std::vector<double>> out(probes);
    for (int k = 0; k < probes; ++k) out[k] = skyRadiance(t, atm, geometry[k].r, geometry[k].mu, geometry[k].muS, geometry[k].nu);
    return out;
  };
  auto timeIt = [&](const PrecomputeOptions& o, double& seconds, AtmosphereTables& t) {
    const auto t0 = std::chrono::steady_clock::now();
    t = precompute(atm, o);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };

  double refSeconds = 0.0;
  AtmosphereTables refTables;
  timeIt(reference.options, refSeconds, refTables);
  const auto refSky = sky(refTables);
  std::printf("%s, %zu wavelengths, %d threads; reference (%s) took %.1f s\n\n", preset.c_str(), set.nm.size(),
              omp_get_max_threads(), reference.name, refSeconds);
  std::printf("| configuration | total [s] | transmittance | single | density | multiple | memory [MiB] "
              "| sky radiance error vs reference: median | 95th pct |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const Config& c : configs) {
    double seconds = 0.0;
    AtmosphereTables t;
    timeIt(c.options, seconds, t);
    const auto s = sky(t);
    std::vector<double> errors;
    for (int k = 0; k < probes; ++k)
      for (std::size_t i = 0; i < s[k].size(); ++i)
        if (refSky[k][i] > 1e-12) errors.push_back(std::abs(s[k][i] / refSky[k][i] - 1.0));
    std::sort(errors.begin(), errors.end());
    auto stage = [&](const char* name) {
      double sum = 0.0;
      for (const auto& st : t.timings)
        if (st.stage.find(name) != std::string::npos) sum += st.seconds;
      return sum;
    };
    std::printf("| %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f | %.2f %% | %.2f %% |\n", c.name, seconds,
                stage("transmittance"), stage("single"), stage("density"), stage("multiple"),
                t.bytes() / 1048576.0, 100.0 * errors[errors.size() / 2], 100.0 * errors[errors.size() * 95 / 100]);
  }
  return 0;
}
