// umbra's spectral sky against the CPU reference of Bruneton's precomputed_atmospheric_scattering
// (double precision, 47 wavelengths 360, 370, ..., 820 nm, 4 orders): reads the reference's
// sky radiances per unit solar irradiance (the CSV of bench/peer/bruneton_reference_driver.cc),
// precomputes umbra's tables of the same atmosphere (bench/peer/bruneton-reference.json) at
// those wavelengths with the default sizes, and prints the relative error of skyRadiance at
// every probe and wavelength as Markdown, by group (view and Sun above or below the horizon)
// and by band. bench/peer_reference_accuracy.sh runs both sides.
//
//   build/bench/umbra-bench-peer-reference --reference ref.csv [--config bench/peer/bruneton-reference.json]
#include "Atmosphere.hpp"
#include "Precompute.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace umbra::atmosphere;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Probe {
  double altitudeM, viewZenithDeg, sunZenithDeg, azimuthDeg;
  std::vector<double> L;  ///< per wavelength, 1/sr
};

std::vector<Probe> readReference(const std::string& path, int wavelengths) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read");
  std::string line;
  std::getline(in, line);  // header
  std::vector<Probe> probes;
  int row = 1;
  while (std::getline(in, line)) {
    ++row;
    if (line.empty()) continue;
    std::stringstream s(line);
    std::vector<double> v;
    for (std::string cell; std::getline(s, cell, ',');) v.push_back(std::stod(cell));
    if (static_cast<int>(v.size()) != 4 + wavelengths)
      throw std::runtime_error(path + ": row " + std::to_string(row) + ": expected " + std::to_string(4 + wavelengths) +
                               " values, got " + std::to_string(v.size()));
    probes.push_back({v[0], v[1], v[2], v[3], std::vector<double>(v.begin() + 4, v.end())});
  }
  if (probes.empty()) throw std::runtime_error(path + ": no rows");
  return probes;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * (v.size() - 1) + 0.5))];
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("umbra's spectral sky against the CPU reference of Bruneton's precomputation");
  std::string reference, config = std::string(UMBRA_SOURCE_DIR) + "/bench/peer/bruneton-reference.json";
  app.add_option("--reference", reference, "CSV of the reference (bench/peer/bruneton_reference_driver.cc)")->required();
  app.add_option("--config", config, "The reference's atmosphere for umbra")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    std::vector<double> nm;
    for (int l = 0; l < 47; ++l) nm.push_back(360.0 + 10.0 * l);
    const std::vector<Probe> probes = readReference(reference, static_cast<int>(nm.size()));
    const Atmosphere atm = loadAtmosphere(config, nm);
    PrecomputeOptions o;                      // Bruneton's sizes and 4 orders
    o.sunAngularRadiusRad = 0.2678 * kPi / 180.0;  // the reference's Sun
    const auto t0 = std::chrono::steady_clock::now();
    const AtmosphereTables tables = precompute(atm, o);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    double scale = 0.0;  // the brightest reference value: errors below 1e-4 of it are not counted
    for (const Probe& p : probes)
      for (double v : p.L) scale = std::max(scale, v);
    std::map<std::string, std::vector<double>> errors, bias;
    std::vector<double> all;
    for (const Probe& p : probes) {
      const double vz = p.viewZenithDeg * kPi / 180.0, sz = p.sunZenithDeg * kPi / 180.0;
      const double az = p.azimuthDeg * kPi / 180.0;
      const double mu = std::cos(vz), muS = std::cos(sz);
      const double nu = std::sin(vz) * std::cos(az) * std::sin(sz) + mu * muS;
      const std::vector<double> L = skyRadiance(tables, atm, tables.bottomRadiusM + p.altitudeM, mu, muS, nu);
      const std::string group = std::string(p.viewZenithDeg <= 90.0 ? "view above the horizon" : "view below the horizon") +
                                (p.sunZenithDeg < 90.0 ? ", Sun up" : ", Sun 5 deg down");
      for (std::size_t l = 0; l < nm.size(); ++l) {
        if (!(p.L[l] > 1e-4 * scale)) continue;
        const double e = (L[l] - p.L[l]) / p.L[l];
        const std::string band = nm[l] < 450.0 ? "360-440 nm" : nm[l] < 600.0 ? "450-590 nm" : "600-820 nm";
        for (const std::string& key : {group, "band " + band}) {
          errors[key].push_back(std::abs(e));
          bias[key].push_back(e);
        }
        all.push_back(std::abs(e));
      }
    }
    std::printf("umbra tables of %s, 47 wavelengths, default sizes, 4 orders: %.1f s (2 threads); %zu probes, values "
                "above 1e-4 of the brightest\n\n",
                atm.name.c_str(), seconds, probes.size());
    std::printf("| probes | values | median |rel. error| | 95th percentile | largest | mean signed error |\n"
                "|---|---:|---:|---:|---:|---:|\n");
    auto row = [&](const std::string& name, const std::vector<double>& e, const std::vector<double>& b) {
      double mean = 0.0;
      for (double x : b) mean += x;
      std::printf("| %s | %zu | %.2f %% | %.2f %% | %.2f %% | %+.2f %% |\n", name.c_str(), e.size(),
                  100.0 * percentile(e, 0.5), 100.0 * percentile(e, 0.95), 100.0 * percentile(e, 1.0),
                  b.empty() ? 0.0 : 100.0 * mean / b.size());
    };
    for (const auto& [key, e] : errors) row(key, e, bias[key]);
    std::vector<double> signedAll;
    for (const auto& [key, b] : bias)
      if (key.rfind("band ", 0) == 0) signedAll.insert(signedAll.end(), b.begin(), b.end());
    row("all", all, signedAll);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "umbra-bench-peer-reference: %s\n", e.what());
    return 1;
  }
  return 0;
}
