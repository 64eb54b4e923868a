// umbra atmosphere eclipse-sky --time ISO8601 --observer LAT,LON[,ALT] --preset NAME --csv FILE
//     [--plot-vertical FILE] [--plot-almucantar FILE]
// The sky of a solar eclipse seen by an observer on the Earth: the Sun and the Moon from the
// ephemerides (scene::sunAndMoonInHorizon), the Moon's shadow as the Sun's visible fraction
// at every point of the air and the ground (eclipse::eclipseFactor, exact), the radiance by
// the Monte-Carlo reference (atmosphere::monteCarloSkyRadiance) along the vertical through
// the Sun and the almucantar at its altitude, beside the same sky without the Moon.
#include "AtmosphereCommon.hpp"
#include "Commands.hpp"
#include "OutputFile.hpp"
#include "ProfileExport.hpp"
#include "ShadowCommon.hpp"  // parseObserver

#include "MonteCarloSky.hpp"
#include "ShadowLut.hpp"
#include "Spectrum.hpp"
#include "scene/Moon.hpp"
#include "scene/Time.hpp"

#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkTable.h>

#include <glm/geometric.hpp>

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
constexpr double kAuM = 149597870700.0;

/// A direction in the horizon frame (x east, y north, z up) from azimuth (north through
/// east) and elevation.
glm::dvec3 horizonDirection(double azimuthRad, double elevationRad) {
  return {std::sin(azimuthRad) * std::cos(elevationRad), std::cos(azimuthRad) * std::cos(elevationRad),
          std::sin(elevationRad)};
}

struct Row {
  std::string curve;
  double positionDeg = 0.0;  ///< along the curve: the signed zenith angle (+: the Sun's side), or azimuth from the Sun
  glm::dvec3 direction{0.0};
};

/// The colour of one direction's spectral radiance.
struct Colour {
  double luminance = 0.0, luminanceError = 0.0;
  glm::dvec3 rgb{0.0};
};

Colour colourOf(const atmosphere::WavelengthSet& set, const std::vector<double>& radiance,
                const std::vector<double>& error) {
  Colour c;
  c.luminance = atmosphere::luminanceCdM2(set, radiance);
  c.rgb = atmosphere::spectralRadianceToLinearSrgb(set, radiance);
  // The wavelengths' paths are drawn independently: their errors add in quadrature.
  double variance = 0.0;
  for (std::size_t i = 0; i < set.size(); ++i) {
    std::vector<double> unit(set.size(), 0.0);
    unit[i] = error[i];
    const double y = atmosphere::luminanceCdM2(set, unit);
    variance += y * y;
  }
  c.luminanceError = std::sqrt(variance);
  return c;
}

void writePlot(const std::string& path, const std::vector<Row>& rows, const std::vector<Colour>& colours,
               const std::string& curve, const std::string& title, const std::string& subtitle,
               const std::string& xLabel) {
  vtkNew<vtkTable> table;
  const char* names[] = {"position_deg", "r", "g", "b", "luminance"};
  std::vector<vtkSmartPointer<vtkDoubleArray>> columns;
  for (int k = 0; k < 5; ++k) {
    columns.push_back(vtkSmartPointer<vtkDoubleArray>::New());
    columns[k]->SetName(names[k]);
    table->AddColumn(columns[k]);
  }
  double top = 0.0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].curve != curve) continue;
    const Colour& c = colours[i];
    const double values[] = {rows[i].positionDeg, std::max(c.rgb.r, 0.0), std::max(c.rgb.g, 0.0),
                             std::max(c.rgb.b, 0.0), c.luminance};
    for (int k = 0; k < 5; ++k) columns[k]->InsertNextValue(values[k]);
    top = std::max({top, c.luminance, c.rgb.r, c.rgb.g, c.rgb.b});
  }
  plot::ProfilePlotStyle style;
  style.logScale = true;
  style.xColumn = "position_deg";
  style.xLabel = xLabel;
  style.yLabel = "luminance, linear sRGB [cd/m^2]";
  style.yMax = std::max(1.5 * top, 1e-6);
  style.subtitle = subtitle;
  style.legendTop = true;
  try {
    plot::writeProfilePlot(table, path, title, style);
  } catch (const std::exception& e) {
    throw CommandError(e.what());
  }
}

}  // namespace

void addAtmosphereEclipseSkyCommand(CLI::App& atmosphereCmd, Action& action) {
  CLI::App* cmd = atmosphereCmd.add_subcommand(
      "eclipse-sky",
      "The sky of a solar eclipse seen from the Earth (Monte-Carlo reference, every order of scattering): radiance, "
      "luminance and colour along the vertical through the Sun and the almucantar at its altitude, with and without "
      "the Moon");
  struct Options {
    std::string preset, config, time, observer, csv, plotVertical, plotAlmucantar;
    int wavelengths = 3;
    std::int64_t paths = 20000;
    std::uint64_t seed = 1;
    double stepDeg = 2.0;
  };
  auto o = std::make_shared<Options>();
  addAtmosphereOptions(cmd, o->preset, o->config);
  cmd->add_option("--time", o->time, "The instant (ISO 8601 UTC), e.g. 2017-08-21T18:25:30Z")->required();
  cmd->add_option("--observer", o->observer,
                  "Where on the Earth: LAT,LON[,ALT] (geodetic degrees north and east; ALT in m or km above the "
                  "ellipsoid, at most half the atmosphere's thickness; default 0)")
      ->required();
  cmd->add_option("--wavelengths", o->wavelengths, "Wavelengths: 3 (680, 550, 440 nm) or 4-47 uniform in 360-830 nm")
      ->capture_default_str();
  cmd->add_option("--paths", o->paths,
                  "Monte-Carlo paths per direction and wavelength (the standard error falls as 1/sqrt: "
                  "docs/accuracy-vs-speed.md, \"The sky of a solar eclipse\")")
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "Random seed (the same seed, the same numbers)")->capture_default_str();
  cmd->add_option("--step-deg", o->stepDeg, "Step along both curves in degrees (0.1-30)")->capture_default_str();
  cmd->add_option("--csv", o->csv,
                  "CSV file to write: curve,position_deg,view_zenith_deg,view_azimuth_deg,luminance_cd_m2,"
                  "luminance_se_cd_m2,r,g,b,clear_luminance_cd_m2, then radiance_NNNnm,se_NNNnm per wavelength "
                  "[W m^-2 sr^-1 nm^-1]")
      ->required();
  cmd->add_option("--plot-vertical", o->plotVertical, "Plot of the vertical through the Sun (.png or .svg)");
  cmd->add_option("--plot-almucantar", o->plotAlmucantar, "Plot of the almucantar at the Sun's altitude (.png or .svg)");

  cmd->callback([&action, o] {
    action = [o] {
      output::checkWritable(o->csv, {".csv"});
      for (const std::string& p : {o->plotVertical, o->plotAlmucantar})
        if (!p.empty()) output::checkWritable(p, {".png", ".svg"});
      if (o->wavelengths < 3 || o->wavelengths > 47) throw CommandError("--wavelengths: expected 3 to 47");
      if (o->paths < 1 || o->paths > 100000000) throw CommandError("--paths: expected 1 to 100000000");
      if (!(o->stepDeg >= 0.1 && o->stepDeg <= 30.0)) throw CommandError("--step-deg: expected 0.1 to 30 degrees");
      scene::UtcTime time;
      try {
        time = scene::parseUtc(o->time);
      } catch (const std::exception& e) {
        throw CommandError(std::string("--time: ") + e.what());
      }
      const scene::Observer observer = parseObserver(o->observer);
      const atmosphere::WavelengthSet set =
          o->wavelengths == 3 ? atmosphere::WavelengthSet::rgb() : atmosphere::WavelengthSet::uniform(o->wavelengths);
      const atmosphere::Atmosphere atm = loadAtmosphereOption(o->preset, o->config, set.nm);
      if (!(observer.altM >= 0.0 && observer.altM <= 0.5 * atm.thicknessM()))
        throw CommandError("--observer: the altitude must be from 0 to half the atmosphere's thickness (" +
                           std::to_string(0.5 * atm.thicknessM()) + " m), got " + std::to_string(observer.altM) + " m");

      // The planet of the Monte-Carlo: a sphere of the atmosphere's bottom radius, the
      // observer on its north pole with the horizon frame's axes (x east, y north, z up).
      const scene::SunAndMoonInHorizon sky = scene::sunAndMoonInHorizon(time, observer);
      const glm::dvec3 eye(0.0, 0.0, atm.bottomRadiusM + observer.altM);
      const glm::dvec3 sunM = eye + sky.sunM, moonM = eye + sky.moonM, toSun = glm::normalize(sky.sunM);
      const atmosphere::SunVisibility shadow = [&](const glm::dvec3& p) {
        return eclipse::eclipseFactor(p, sunM, sky.sunRadiusM, {moonM, sky.moonRadiusM}, nullptr).g;
      };
      const double sunAltitude = std::asin(std::clamp(toSun.z, -1.0, 1.0));
      const double sunAzimuth = std::hypot(toSun.x, toSun.y) > 0.0 ? std::atan2(toSun.x, toSun.y) : 0.0;
      const double visible = shadow(eye);

      std::vector<Row> rows;
      const int half = static_cast<int>(std::floor(90.0 / o->stepDeg + 1e-9));
      for (int k = -half; k <= half; ++k) {
        const double z = k * o->stepDeg * kDeg;
        rows.push_back({"vertical", z / kDeg, horizonDirection(sunAzimuth + (z < 0.0 ? kPi : 0.0), 0.5 * kPi - std::abs(z))});
      }
      const double almucantar = std::clamp(sunAltitude, 0.0, 89.0 * kDeg);
      const int around = static_cast<int>(std::floor(360.0 / o->stepDeg - 1e-9));
      for (int k = 0; k <= around; ++k) {
        const double a = k * o->stepDeg * kDeg;
        rows.push_back({"almucantar", a / kDeg, horizonDirection(sunAzimuth + a, almucantar)});
      }
      std::vector<glm::dvec3> directions;
      for (const Row& r : rows) directions.push_back(r.direction);

      atmosphere::MonteCarloSkyOptions mc;
      mc.paths = o->paths;
      mc.seed = o->seed;
      atmosphere::MonteCarloSky eclipsed, clear;
      {
        ProgressLine progress("eclipsed sky (Monte-Carlo)");
        eclipsed = atmosphere::monteCarloSkyRadiance(atm, eye, directions, toSun, shadow, mc,
                                                     [&](double f) { progress.update(0.5 * f); return true; });
        clear = atmosphere::monteCarloSkyRadiance(atm, eye, directions, toSun, {}, mc,
                                                  [&](double f) { progress.update(0.5 + 0.5 * f); return true; });
        progress.update(1.0);
      }

      // Per unit solar irradiance to W m^-2 sr^-1 nm^-1: the Sun's spectrum at its distance.
      const double distanceFactor = (kAuM / glm::length(sky.sunM)) * (kAuM / glm::length(sky.sunM));
      std::vector<double> sunlight;
      for (double nm : set.nm) sunlight.push_back(atmosphere::solarIrradianceWm2PerNm(nm) * distanceFactor);
      const auto spectral = [&](const std::vector<double>& perUnit) {
        std::vector<double> out(perUnit.size());
        for (std::size_t i = 0; i < out.size(); ++i) out[i] = perUnit[i] * sunlight[i];
        return out;
      };
      std::vector<Colour> colours, clearColours;
      for (std::size_t i = 0; i < rows.size(); ++i) {
        colours.push_back(colourOf(set, spectral(eclipsed.directions[i].radiance), spectral(eclipsed.directions[i].standardError)));
        clearColours.push_back(colourOf(set, spectral(clear.directions[i].radiance), spectral(clear.directions[i].standardError)));
      }

      output::OutputFile out(o->csv);
      {
        std::ofstream f(out.tempPath());
        f << "curve,position_deg,view_zenith_deg,view_azimuth_deg,luminance_cd_m2,luminance_se_cd_m2,r,g,b,"
             "clear_luminance_cd_m2";
        for (double nm : set.nm) f << ",radiance_" << std::lround(nm) << "nm,se_" << std::lround(nm) << "nm";
        f << "\n";
        char line[256];
        for (std::size_t i = 0; i < rows.size(); ++i) {
          const glm::dvec3& d = rows[i].direction;
          double azimuth = std::atan2(d.x, d.y) / kDeg;
          if (azimuth < 0.0) azimuth += 360.0;
          const Colour& c = colours[i];
          std::snprintf(line, sizeof line, "%s,%.4f,%.4f,%.4f,%.6g,%.3g,%.6g,%.6g,%.6g,%.6g", rows[i].curve.c_str(),
                        rows[i].positionDeg, std::acos(std::clamp(d.z, -1.0, 1.0)) / kDeg, azimuth, c.luminance,
                        c.luminanceError, std::max(c.rgb.r, 0.0), std::max(c.rgb.g, 0.0), std::max(c.rgb.b, 0.0),
                        clearColours[i].luminance);
          f << line;
          const std::vector<double> L = spectral(eclipsed.directions[i].radiance),
                                    se = spectral(eclipsed.directions[i].standardError);
          for (std::size_t w = 0; w < L.size(); ++w) {
            std::snprintf(line, sizeof line, ",%.6g,%.3g", L[w], se[w]);
            f << line;
          }
          f << "\n";
        }
        if (!f.flush()) throw CommandError(o->csv + ": cannot write");
      }
      out.commit();

      char where[160];
      std::snprintf(where, sizeof where, "%s, %.4f %s %.4f %s", scene::formatUtc(time).c_str(), std::abs(observer.latDeg),
                    observer.latDeg >= 0 ? "N" : "S", std::abs(observer.lonDeg), observer.lonDeg >= 0 ? "E" : "W");
      char subtitle[200];
      std::snprintf(subtitle, sizeof subtitle,
                    "%s; Sun %.1f deg up, %.4f of it visible; Monte-Carlo, %lld paths a direction and wavelength",
                    atm.name.c_str(), sunAltitude / kDeg, visible, static_cast<long long>(o->paths));
      if (!o->plotVertical.empty())
        writePlot(o->plotVertical, rows, colours, "vertical", std::string("The vertical through the Sun: ") + where,
                  subtitle, "zenith angle [deg] (+: towards the Sun)");
      if (!o->plotAlmucantar.empty())
        writePlot(o->plotAlmucantar, rows, colours, "almucantar",
                  std::string("The almucantar at the Sun's altitude: ") + where, subtitle, "azimuth from the Sun [deg]");

      // The zenith: the vertical's middle row.
      const std::size_t zenith = static_cast<std::size_t>(half);
      std::printf("%s: Sun %.2f deg up at azimuth %.2f deg, %.4f of its disc's light visible\n", where,
                  sunAltitude / kDeg, (sunAzimuth < 0.0 ? sunAzimuth + 2.0 * kPi : sunAzimuth) / kDeg, visible);
      const Colour& z = colours[zenith];
      const double zClear = clearColours[zenith].luminance;
      std::printf("zenith luminance %.4g +- %.2g cd/m^2 (without the Moon %.4g cd/m^2", z.luminance, z.luminanceError, zClear);
      if (z.luminance > 0.0) std::printf(": %.3g times brighter", zClear / z.luminance);
      std::printf(")\n");
      std::cout << "wrote " << o->csv << (o->plotVertical.empty() ? "" : ", " + o->plotVertical)
                << (o->plotAlmucantar.empty() ? "" : ", " + o->plotAlmucantar) << " (" << atm.name << ", "
                << rows.size() << " directions x " << set.size() << " wavelengths x " << o->paths << " paths, twice: "
                << std::lround(eclipsed.seconds + clear.seconds) << " s)\n";
      return 0;
    };
  });
}

}  // namespace umbra::cli
