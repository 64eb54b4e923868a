// Speed against accuracy of the atmosphere tables (Bruneton 2017 scheme):
// time per stage and in total against table sizes, scattering orders, the refraction step
// and the number of wavelengths, with the error of the sky radiance looked up in each
// against a reference configuration, and the peak memory. Prints Markdown for
// docs/accuracy-vs-speed/atmosphere-tables.md.
//
//   build/bench/umbra-bench-atmosphere [--preset earth] [--wavelengths 3] [--probes 2000]
//       [--sections sizes,orders,refraction,wavelengths,stages,directions] [--reference-cache FILE]
//       [--wavelength-counts 3,15,47] [--batches 0,8]
//
// --reference-cache keeps the reference's sky radiances in FILE (written when missing, read
// when present), so that a changed precomputation is compared with the same reference.
#include "Atmosphere.hpp"
#include "Precompute.hpp"
#include "Spectrum.hpp"

#include <CLI/CLI.hpp>

#include <omp.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>

using namespace umbra::atmosphere;

namespace {

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
using Sky = std::vector<std::vector<double>>;

/// Resident-memory high-water mark of this process [bytes]; reset() starts a new one
/// (Linux: /proc/self/clear_refs "5"); where that is refused the peak stays process-wide.
struct PeakMemory {
  static void reset() { std::ofstream("/proc/self/clear_refs") << "5"; }
  static double bytes() {
    std::ifstream f("/proc/self/status");
    std::string line;
    while (std::getline(f, line))
      if (line.rfind("VmHWM:", 0) == 0) return 1024.0 * std::stod(line.substr(6));
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return 1024.0 * static_cast<double>(u.ru_maxrss);
  }
};

double cpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct Run {
  double seconds = 0.0, cpu = 0.0, peakBytes = 0.0;
  AtmosphereTables tables;
};

Run timed(const Atmosphere& atm, const PrecomputeOptions& o) {
  Run r;
  PeakMemory::reset();
  const double c0 = cpuSeconds();
  const auto t0 = std::chrono::steady_clock::now();
  r.tables = precompute(atm, o);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.cpu = cpuSeconds() - c0;
  r.peakBytes = PeakMemory::bytes();
  return r;
}

double stage(const AtmosphereTables& t, const char* name) {
  double sum = 0.0;
  for (const auto& st : t.timings)
    if (st.stage.find(name) != std::string::npos) sum += st.seconds;
  return sum;
}

/// Median and 95th percentile of |s / ref - 1| over probes and wavelengths.
std::pair<double, double> errorOf(const Sky& s, const Sky& ref) {
  std::vector<double> e;
  for (std::size_t k = 0; k < s.size(); ++k)
    for (std::size_t i = 0; i < s[k].size(); ++i)
      if (ref[k][i] > 1e-12) e.push_back(std::abs(s[k][i] / ref[k][i] - 1.0));
  if (e.empty()) return {NAN, NAN};
  std::sort(e.begin(), e.end());
  return {e[e.size() / 2], e[e.size() * 95 / 100]};
}

bool readSky(const std::string& path, std::size_t probes, std::size_t channels, Sky& out) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return false;
  out.assign(probes, std::vector<double>(channels));
  for (auto& v : out) f.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(channels * sizeof(double)));
  return static_cast<bool>(f) && f.peek() == std::char_traits<char>::eof();
}

void writeSky(const std::string& path, const Sky& s) {
  std::ofstream f(path, std::ios::binary);
  for (const auto& v : s) f.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(double)));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Atmosphere tables: time and error per configuration"};
  std::string preset = "earth", sectionList = "sizes,orders,refraction,wavelengths", referenceCache;
  int wavelengths = 3, probes = 2000, referenceOrders = 6;
  double referenceScale = 1.5;
  std::vector<int> wavelengthCounts{3, 15, 47}, batches{0, 8}, directionCounts{0, 24, 32};
  int referenceDirections = 64;
  app.add_option("--preset", preset)->capture_default_str();
  app.add_option("--wavelengths", wavelengths, "3 (680/550/440 nm) or N between 360 and 830 nm")->capture_default_str();
  app.add_option("--probes", probes, "Random view/sun geometries compared")->capture_default_str();
  app.add_option("--sections", sectionList,
                 "Comma-separated: default (default sizes, 4 orders only), sizes, orders, refraction, wavelengths, stages (every stage's time at each of --wavelength-counts), directions (density directions against a reference)")
      ->capture_default_str();
  app.add_option("--wavelength-counts", wavelengthCounts, "The wavelengths section's numbers of wavelengths")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--directions", directionCounts, "The directions section's polar directions (0: the atmosphere's own)")
      ->capture_default_str();
  app.add_option("--reference-directions", referenceDirections, "The directions section's reference")
      ->capture_default_str();
  app.add_option("--batches", batches, "The wavelengths section's batches (0: all at once)")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--reference-cache", referenceCache, "File of the reference's sky radiances (read, else written)");
  app.add_option("--reference-scale", referenceScale, "Reference table sizes relative to the defaults")->capture_default_str();
  app.add_option("--reference-orders", referenceOrders, "Reference scattering orders")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  auto want = [&](const std::string& s) { return ("," + sectionList + ",").find("," + s + ",") != std::string::npos; };

  const auto wavelengthSet = [](int n) { return n == 3 ? WavelengthSet::rgb() : WavelengthSet::uniform(n); };
  const Atmosphere atm = loadAtmosphere(preset, wavelengthSet(wavelengths).nm);
  const std::size_t nl = atm.wavelengthsNm.size();

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
  auto sky = [&](const AtmosphereTables& t) {
    Sky out(probes);
    for (int k = 0; k < probes; ++k) out[k] = skyRadiance(t, atm, geometry[k].r, geometry[k].mu, geometry[k].muS, geometry[k].nu);
    return out;
  };

  std::printf("%s, %zu wavelengths, %d threads\n\n", preset.c_str(), nl, omp_get_max_threads());
  const bool errorsWanted = want("default") || want("sizes") || want("orders");
  Sky refSky;
  if (errorsWanted) {
    std::ostringstream name;
    name << "reference: " << referenceScale << "x sizes, " << referenceOrders << " orders";
    if (!referenceCache.empty() && readSky(referenceCache, probes, nl, refSky)) {
      std::printf("%s, read from %s\n\n", name.str().c_str(), referenceCache.c_str());
    } else {
      const Run ref = timed(atm, scaled(referenceScale, referenceOrders, false));
      refSky = sky(ref.tables);
      if (!referenceCache.empty()) writeSky(referenceCache, refSky);
      std::printf("%s took %.1f s\n\n", name.str().c_str(), ref.seconds);
    }
  }

  const char* header =
      "| total [s] | CPU [s] | transmittance | single | density | multiple | tables [MiB] | peak memory [MiB] ";
  const char* rule = "|---|---:|---:|---:|---:|---:|---:|---:|---:";
  auto row = [&](const std::string& name, const Run& r) {
    std::printf("| %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f | %.0f ", name.c_str(), r.seconds, r.cpu,
                stage(r.tables, "transmittance"), stage(r.tables, "single"), stage(r.tables, "density"),
                stage(r.tables, "multiple"), r.tables.bytes() / 1048576.0, r.peakBytes / 1048576.0);
  };
  auto errorCells = [&](const Sky& s, const Sky& ref) {
    const auto [median, p95] = errorOf(s, ref);
    std::printf("| %.2f %% | %.2f %% |\n", 100.0 * median, 100.0 * p95);
  };

  // Sizes and orders against the reference.
  std::vector<std::pair<std::string, PrecomputeOptions>> configs;
  if (want("default") && !want("sizes") && !want("orders")) configs.push_back({"default sizes, 4 orders", scaled(1.0, 4, false)});
  if (want("sizes"))
    for (double f : {0.5, 0.75, 1.0}) {
      std::ostringstream n;
      n << f << "x sizes, 4 orders";
      configs.push_back({n.str(), scaled(f, 4, false)});
    }
  if (want("orders"))
    for (int k : {1, 2, 3, 5}) configs.push_back({"default sizes, " + std::to_string(k) + " orders", scaled(1.0, k, false)});
  if (!configs.empty()) {
    std::printf("| configuration %s| sky radiance error: median | 95th pct |\n%s|---:|---:|\n", header, rule);
    for (const auto& [name, o] : configs) {
      const Run r = timed(atm, o);
      row(name, r);
      errorCells(sky(r.tables), refSky);
    }
    std::printf("\n");
  }

  // Refraction: default sizes and 4 orders; the error is against the finest step.
  if (want("refraction")) {
    const double finestM = 1250.0;
    PrecomputeOptions fine = scaled(1.0, 4, true);
    fine.refractionStepM = finestM;
    std::printf("| refraction step %s| error vs %.2f km step: median | 95th pct |\n%s|---:|---:|\n", header,
                finestM / 1e3, rule);
    Sky fineSky;
    {
      const Run ref = timed(atm, fine);
      fineSky = sky(ref.tables);
      row("1.25 km (the reference)", ref);
      std::printf("| - | - |\n");
    }
    {
      const Run off = timed(atm, scaled(1.0, 4, false));
      row("no refraction", off);
      errorCells(sky(off.tables), fineSky);
    }
    for (double km : {40.0, 20.0, 10.0, 5.0}) {
      PrecomputeOptions o = scaled(1.0, 4, true);
      o.refractionStepM = km * 1e3;
      const Run r = timed(atm, o);
      std::ostringstream n;
      n << km << " km";
      row(n.str(), r);
      errorCells(sky(r.tables), fineSky);
    }
    std::printf("\n");
  }

  // Wavelengths: default sizes, 4 orders.
  if (want("wavelengths")) {
    std::printf("| wavelengths %s|\n%s|\n", header, rule);
    for (int n : wavelengthCounts) {
      const Atmosphere a = loadAtmosphere(preset, wavelengthSet(n).nm);
      for (int batch : batches) {
        if (batch >= n) continue;
        PrecomputeOptions o = scaled(1.0, 4, false);
        o.wavelengthBatch = batch;
        row(std::to_string(n) + (batch > 0 ? ", " + std::to_string(batch) + " at a time" : ""), timed(a, o));
        std::printf("|\n");
      }
    }
    std::printf("\n");
  }

  // Density directions: the multiple scattering with n x 2n directions against
  // --reference-directions (default sizes, 4 orders).
  if (want("directions")) {
    PrecomputeOptions o = scaled(1.0, 4, false);
    o.sphereSamples = referenceDirections;
    const Run ref = timed(atm, o);
    const auto& r = ref.tables.multipleScattering.values;
    double top = 0.0;
    for (float v : r) top = std::max(top, static_cast<double>(v));
    std::printf("multiple scattering against %d x %d directions (%.1f s)\n\n", referenceDirections, 2 * referenceDirections,
                ref.seconds);
    std::printf("| directions | total [s] | largest error / largest value | relative error, values over 1e-3 of the largest: median | 95th pct | largest |\n");
    std::printf("|---|---:|---:|---:|---:|---:|\n");
    for (int n : directionCounts) {
      o.sphereSamples = n;
      const Run run = timed(atm, o);
      const auto& v = run.tables.multipleScattering.values;
      double worst = 0.0;
      std::vector<double> relative;
      for (std::size_t i = 0; i < v.size(); ++i) {
        const double d = std::abs(static_cast<double>(v[i]) - r[i]);
        worst = std::max(worst, d);
        if (r[i] > 1e-3 * top) relative.push_back(d / r[i]);
      }
      std::sort(relative.begin(), relative.end());
      std::printf("| %d x %d%s | %.2f | %.4f | %.2f %% | %.2f %% | %.1f %% |\n", run.tables.options.sphereSamples,
                  2 * run.tables.options.sphereSamples, n == 0 ? " (default)" : "", run.seconds, worst / top,
                  100.0 * relative[relative.size() / 2], 100.0 * relative[relative.size() * 95 / 100],
                  100.0 * relative.back());
    }
    std::printf("\n");
  }

  // Every stage's time, default sizes and 4 orders, all wavelengths at once.
  if (want("stages")) {
    std::vector<AtmosphereTables> runs;
    for (int n : wavelengthCounts) runs.push_back(timed(loadAtmosphere(preset, wavelengthSet(n).nm), scaled(1.0, 4, false)).tables);
    std::printf("| stage [s] |");
    for (int n : wavelengthCounts) std::printf(" %d wavelengths |", n);
    std::printf("\n|---|");
    for (std::size_t i = 0; i < wavelengthCounts.size(); ++i) std::printf("---:|");
    std::printf("\n");
    for (const auto& st : runs.front().timings) {
      std::printf("| %s |", st.stage.c_str());
      for (const AtmosphereTables& t : runs)
        for (const auto& other : t.timings)
          if (other.stage == st.stage) std::printf(" %.3f |", other.seconds);
      std::printf("\n");
    }
    std::printf("\n");
  }
  return 0;
}
