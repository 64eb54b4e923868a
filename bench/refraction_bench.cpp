// Speed against accuracy of the refraction table (deviation and contact altitude, eclipse
// paper section 4.1) for the Earth preset: build time per table size and RK4 step, and the
// error of the table lookup against rays traced directly with a 1 km step.
// Prints Markdown for docs/accuracy-vs-speed/atmosphere-tables.md.
//
//   build/bench/umbra-bench-refraction [--preset earth] [--samples 4000]
#include "Atmosphere.hpp"
#include "Refraction.hpp"
#include "SightLines.hpp"
#include "TextureCoords.hpp"

#include <CLI/CLI.hpp>

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

using namespace umbra::atmosphere;

int main(int argc, char** argv) {
  CLI::App app{"Refraction table: build time and error against directly traced rays"};
  std::string preset = "earth";
  int samples = 4000;
  app.add_option("--preset", preset)->capture_default_str();
  app.add_option("--samples", samples, "Random rays (r, mu) in the table's domain")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  const Atmosphere atm = loadAtmosphere(preset, {550.0});
  const RefractiveMedium medium = refractiveMedium(atm, 550.0);
  const ShellRadii shell{atm.bottomRadiusM, atm.topRadiusM};

  // Reference: random rays from the ground to the top, zenith to horizon, traced at 1 km.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<RadiusMu> rays(samples);
  std::vector<double> reference(samples), referenceContact(samples);
  for (auto& ray : rays) ray = rMuFromTransmittanceCoords(shell, TransmittanceCoords{unit(rng), unit(rng)});
#pragma omp parallel for schedule(dynamic, 16)
  for (int k = 0; k < samples; ++k) {
    const RayPath path = traceRay(medium, rays[k].radiusM, rays[k].mu, 1e3);
    reference[k] = path.deviationRad;
    referenceContact[k] = path.contactAltitudeM;
  }

  std::printf("threads: %d; %s at 550 nm; error = |lookup - ray traced at 1 km| over %d random rays\n\n",
              omp_get_max_threads(), preset.c_str(), samples);
  std::printf("| table | RK4 step | build time [s] | max error [arcsec] | max error, contact > 1 km [arcsec] | mean error [arcsec] |\n"
              "|---|---:|---:|---:|---:|---:|\n");
  const struct { int w, h; } sizes[] = {{128, 64}, {256, 128}, {512, 256}};
  for (const auto& size : sizes) {
    for (double stepKm : {40.0, 20.0, 10.0, 5.0}) {
      const auto t0 = std::chrono::steady_clock::now();
      const RefractionTable table = buildRefractionTable(medium, size.w, size.h, stepKm * 1e3);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      double maxErr = 0.0, maxAbove = 0.0, sumErr = 0.0;
      for (int k = 0; k < samples; ++k) {
        const double e = std::abs(table.sample(rays[k].radiusM, rays[k].mu).deviationRad - reference[k]);
        maxErr = std::max(maxErr, e);
        if (referenceContact[k] > 1e3) maxAbove = std::max(maxAbove, e);
        sumErr += e;
      }
      const double arcsec = 180.0 / M_PI * 3600.0;
      std::printf("| %dx%d | %.0f km | %.3f | %.3f | %.3f | %.4f |\n", size.w, size.h, stepKm, seconds, maxErr * arcsec,
                  maxAbove * arcsec, sumErr / samples * arcsec);
    }
  }
  return 0;
}
