// umbra atmosphere sky --preset NAME --sun-zenith-deg Z [--observer-altitude M] --csv FILE [--plot FILE.png]
// The sky's luminance and colour over a grid of view directions, from freshly precomputed
// (small) tables, lit by the top-of-atmosphere Sun at 1 au; optionally a fisheye picture of
// the dome. docs/sky-validation.md compares it with the CIE standard clear sky.
#include "AtmosphereCommon.hpp"
#include "Commands.hpp"
#include "OutputFile.hpp"
#include "ShadowCommon.hpp"  // lengthOption

#include "Atmosphere.hpp"
#include "Precompute.hpp"
#include "Sky.hpp"
#include "Spectrum.hpp"
#include "AtmosphereTablesBlocks.h"
#include "vtkAtmosphereTablesSource.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkPointData.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>

namespace umbra::cli {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

double srgbEncode(double linear) {
  const double c = std::clamp(linear, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

/// Equidistant fisheye of the dome, `size` x `size` pixels: the zenith at the centre, the
/// horizon on the inscribed circle, the Sun's azimuth up (azimuth increasing clockwise;
/// the sky is symmetric about the Sun's vertical); black outside the circle. Tone mapping:
/// 1 - exp(-k L) per linear sRGB channel with k = ln 2 / (the dome's mean luminance), then
/// the sRGB transfer function. The Sun (when above the horizon) is a white disc of 1 degree
/// radius.
void writeFisheye(const std::string& path, int size, const atmosphere::AtmosphereTables& tables,
                  const atmosphere::Atmosphere& atm, const atmosphere::WavelengthSet& wavelengths,
                  double sunZenithRad, double altitudeM) {
  std::vector<glm::dvec3> rgb(static_cast<std::size_t>(size) * size, glm::dvec3(0.0));
  std::vector<char> inside(rgb.size(), 0);
  std::vector<char> sun(rgb.size(), 0);
  double sumL = 0.0;
  int count = 0;
  const double half = 0.5 * size;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const double dx = (x + 0.5 - half) / half, dy = (y + 0.5 - half) / half;  // y up (VTK rows bottom first)
      const double rho = std::hypot(dx, dy);
      if (rho > 1.0) continue;
      const double zenith = rho * kPi / 2;
      const double azimuth = std::atan2(dx, dy);
      const std::size_t i = static_cast<std::size_t>(y) * size + x;
      const atmosphere::SkySample s =
          atmosphere::skyLuminanceAt(tables, atm, wavelengths, sunZenithRad, altitudeM, zenith, azimuth);
      rgb[i] = s.linearSrgb;
      inside[i] = 1;
      sumL += s.luminanceCdM2;
      ++count;
      const double cosChi = std::cos(zenith) * std::cos(sunZenithRad) +
                            std::sin(zenith) * std::sin(sunZenithRad) * std::cos(azimuth);
      sun[i] = sunZenithRad < kPi / 2 && std::acos(std::clamp(cosChi, -1.0, 1.0)) < 1.0 * kDeg;
    }
  const double mean = count > 0 ? sumL / count : 0.0;
  const double k = mean > 0.0 ? std::log(2.0) / mean : 0.0;

  vtkNew<vtkImageData> image;
  image->SetDimensions(size, size, 1);
  vtkNew<vtkUnsignedCharArray> pixels;
  pixels->SetName("rgb");
  pixels->SetNumberOfComponents(3);
  pixels->SetNumberOfTuples(static_cast<vtkIdType>(rgb.size()));
  for (std::size_t i = 0; i < rgb.size(); ++i) {
    unsigned char v[3] = {0, 0, 0};
    for (int c = 0; c < 3; ++c) {
      double value = 0.0;
      if (sun[i]) value = 1.0;
      else if (inside[i]) value = srgbEncode(1.0 - std::exp(-k * std::max(rgb[i][c], 0.0)));
      v[c] = static_cast<unsigned char>(std::lround(255.0 * value));
    }
    pixels->SetTypedTuple(static_cast<vtkIdType>(i), v);
  }
  image->GetPointData()->SetScalars(pixels);

  writePng(image, path);
}

} // namespace

void addAtmosphereSkyCommand(CLI::App& atmosphereCmd, Action& action) {
  CLI::App* sky = atmosphereCmd.add_subcommand(
      "sky", "Sky luminance (cd/m^2, for the top-of-atmosphere Sun at 1 au) and linear sRGB seen by an observer, "
             "over view zenith x azimuth from the Sun's azimuth (0-180 degrees: the sky is symmetric)");
  struct Options {
    std::string preset, config, altitude = "0", csv, plot;
    double sunZenithDeg = -1.0, zenithStep = 5.0, azimuthStep = 10.0, lowestSunZenithDeg = 102.0;
    int orders = 4, wavelengths = 15, plotSize = 256, densityDirections = 0;
    CacheOptions cache;
  };
  auto o = std::make_shared<Options>();
  addAtmosphereOptions(sky, o->preset, o->config);
  sky->add_option("--sun-zenith-deg", o->sunZenithDeg,
                  "Sun zenith angle in degrees (0-180; past 90 the twilight sky)")
      ->required();
  CLI::Option* lowestSun = sky->add_option("--lowest-sun-zenith-deg", o->lowestSunZenithDeg,
                  "The lowest Sun the tables hold, in degrees (102-170; below it the air is dark). Default: 102, or 20 "
                  "below a Sun lower than 82 (the light scattered into the shadowed air: second-order twilight)");
  CLI::Option* directions = sky->add_option("--density-directions", o->densityDirections,
                  "Polar directions of the multiple-scattering density (times twice as many azimuths; 4-64). Default: 12, "
                  "24 for a Sun below the horizon, or what a forward-peaked phase function asks for (Mars' dust: 56; "
                  "docs/accuracy-vs-speed/atmosphere-tables.md, \"Density directions\")");
  sky->add_option("--observer-altitude", o->altitude, "Observer altitude above the ground (units m, km)")
      ->capture_default_str();
  sky->add_option("--zenith-step", o->zenithStep, "View zenith step in degrees (0 to 90)")->capture_default_str();
  sky->add_option("--azimuth-step", o->azimuthStep, "Azimuth step in degrees (0 to 90)")->capture_default_str();
  sky->add_option("--orders", o->orders, "Scattering orders (1-10)")->capture_default_str();
  sky->add_option("--wavelengths", o->wavelengths, "Wavelengths: 3 (680, 550, 440 nm) or 4-47 uniform in 360-830 nm")
      ->capture_default_str();
  sky->add_option("--csv", o->csv, "CSV file to write (view_zenith_deg,view_azimuth_deg,luminance,r,g,b)")->required();
  sky->add_option("--plot", o->plot, "PNG file: a fisheye picture of the dome (zenith in the centre, Sun's azimuth up)");
  sky->add_option("--plot-size", o->plotSize, "Width and height of the picture in pixels (16-4096)")->capture_default_str();
  o->cache.addTo(sky);

  sky->callback([&action, o, lowestSun, directions] {
    const bool lowestSunGiven = lowestSun->count() > 0, directionsGiven = directions->count() > 0;
    action = [o, lowestSunGiven, directionsGiven] {
      output::checkWritable(o->csv, {".csv"});
      if (!o->plot.empty()) output::checkWritable(o->plot, {".png"});
      if (!(o->sunZenithDeg >= 0.0 && o->sunZenithDeg <= 180.0))
        throw CommandError("--sun-zenith-deg: expected 0 to 180 degrees, got " + std::to_string(o->sunZenithDeg));
      if (!(o->zenithStep > 0.0 && o->zenithStep <= 90.0))
        throw CommandError("--zenith-step: expected 0 < STEP <= 90 degrees");
      if (!(o->azimuthStep > 0.0 && o->azimuthStep <= 90.0))
        throw CommandError("--azimuth-step: expected 0 < STEP <= 90 degrees");
      const double directions = (std::floor(90.0 / o->zenithStep + 1e-9) + 1.0) * (std::floor(180.0 / o->azimuthStep + 1e-9) + 1.0);
      if (directions > atmosphere::kMaxSkyDirections)
        throw CommandError("--zenith-step, --azimuth-step: " + std::to_string(static_cast<long long>(directions)) +
                           " directions, more than " + std::to_string(atmosphere::kMaxSkyDirections));
      if (o->orders < 1 || o->orders > 10) throw CommandError("--orders: expected 1 to 10");
      if (o->wavelengths < 3 || o->wavelengths > 47) throw CommandError("--wavelengths: expected 3 to 47");
      if (o->plotSize < 16 || o->plotSize > 4096) throw CommandError("--plot-size: expected 16 to 4096");
      if (lowestSunGiven && !(o->lowestSunZenithDeg >= 102.0 && o->lowestSunZenithDeg <= 170.0))
        throw CommandError("--lowest-sun-zenith-deg: expected 102 to 170 degrees, got " +
                           std::to_string(o->lowestSunZenithDeg));
      if (directionsGiven && !(o->densityDirections >= 4 && o->densityDirections <= 64))
        throw CommandError("--density-directions: expected 4 to 64, got " + std::to_string(o->densityDirections));
      const double sunZenithRad = o->sunZenithDeg * kDeg;
      const double altitudeM = lengthOption("--observer-altitude", o->altitude);
      if (!(altitudeM >= 0.0)) throw CommandError("--observer-altitude: expected a length >= 0, got " + o->altitude);

      const atmosphere::WavelengthSet wavelengths =
          o->wavelengths == 3 ? atmosphere::WavelengthSet::rgb() : atmosphere::WavelengthSet::uniform(o->wavelengths);
      const atmosphere::AtmosphereModelPtr model = atmosphereOption(o->preset, o->config);
      const atmosphere::Atmosphere& atm = model->at(wavelengths.nm);
      if (!(altitudeM < 0.5 * atm.thicknessM()))
        throw CommandError("--observer-altitude: expected below half the atmosphere's thickness (" +
                           std::to_string(0.5 * atm.thicknessM()) + " m), got " + o->altitude);

      atmosphere::PrecomputeOptions options = atmosphere::skyPrecomputeOptions(atm, o->orders, sunZenithRad);
      if (lowestSunGiven) options.muSMin = std::cos(o->lowestSunZenithDeg * kDeg);
      if (directionsGiven) options.sphereSamples = o->densityDirections;
      // Fewer than a forward-peaked phase function asks for (docs/accuracy-vs-speed/atmosphere-tables.md,
      // "Density directions"): say so.
      const int asked = atmosphere::densityDirectionsFor(atm);
      if (asked > atmosphere::kMinDensityDirections && options.sphereSamples < asked && options.orders >= 2)
        std::cerr << "note: " << atm.name << "'s forward-peaked phase functions ask for " << asked << " density directions, "
                  << options.sphereSamples << " used (faster, the light scattered more than once less exact): "
                  << "--density-directions " << asked << " for that\n";
      // The tables through the filter (and so through the cache), at the sky's sizes.
      auto source = vtkSmartPointer<vtkAtmosphereTablesSource>::New();
      source->SetAtmosphereModel(model);
      source->SetTables(vtkAtmosphereTablesSource::Bruneton);
      source->SetWavelengths(o->wavelengths);
      source->SetOrders(options.orders);
      source->SetTransmittanceSize(options.transmittanceWidth, options.transmittanceHeight);
      source->SetScatteringSize(options.scatteringR, options.scatteringMu, options.scatteringMuS, options.scatteringNu);
      source->SetIrradianceSize(options.irradianceWidth, options.irradianceHeight);
      source->SetMuSMin(options.muSMin);
      source->SetDensityDirections(options.sphereSamples);
      source->SetQuadratureSamples(options.singleScatteringSamples, options.multipleScatteringSamples,
                                   options.irradianceSamples);
      updateTablesSource(source, o->cache, "sky tables (" + atm.name + ")");
      const atmosphere::AtmosphereTables tables = filters::tablesFromBlocks(source->GetOutput(), atm);
      const atmosphere::SkyGrid grid = atmosphere::skyLuminance(tables, atm, wavelengths, sunZenithRad, altitudeM,
                                                                o->zenithStep * kDeg, o->azimuthStep * kDeg);
      if (!o->plot.empty()) writeFisheye(o->plot, o->plotSize, tables, atm, wavelengths, sunZenithRad, altitudeM);

      output::OutputFile out(o->csv);
      {
        std::ofstream f(out.tempPath());
        f << "view_zenith_deg,view_azimuth_deg,luminance,r,g,b\n";
        char line[256];
        for (const atmosphere::SkySample& s : grid.samples) {
          std::snprintf(line, sizeof line, "%.6f,%.6f,%.9g,%.9g,%.9g,%.9g\n", s.viewZenithRad / kDeg,
                        s.azimuthRad / kDeg, s.luminanceCdM2, std::max(s.linearSrgb.r, 0.0),
                        std::max(s.linearSrgb.g, 0.0), std::max(s.linearSrgb.b, 0.0));
          f << line;
        }
        if (!f.flush()) throw CommandError(o->csv + ": cannot write");
      }
      out.commit();
      std::cout << "wrote " << o->csv << (o->plot.empty() ? "" : " and " + o->plot) << " (" << atm.name
                << ", Sun zenith " << o->sunZenithDeg << " deg, tables down to a Sun "
                << std::lround(std::acos(options.muSMin) / kDeg) << " deg from the zenith, " << options.sphereSamples
                << " x " << 2 * options.sphereSamples << " density directions, observer at " << altitudeM
                << " m; luminance for a solar illuminance of " << std::lround(grid.solarIlluminanceLux)
                << " lx, r,g,b linear sRGB in cd/m^2 clamped at 0)\n";
      return 0;
    };
  });
}

} // namespace umbra::cli
