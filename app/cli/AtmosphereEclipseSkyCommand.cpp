// umbra atmosphere eclipse-sky --time ISO8601 --observer LAT,LON[,ALT] --preset NAME --csv FILE
//     [--plot-vertical FILE] [--plot-almucantar FILE]
// The sky of a solar eclipse seen by an observer on the Earth: the Sun and the Moon from the
// ephemerides (scene::sunAndMoonInHorizon), the Moon's shadow as the Sun's visible fraction
// at every point of the air and the ground (eclipse::eclipseFactor: exact for the reference,
// from a shadow LuT over the scene's distances for the quadrature), the radiance by the
// Monte-Carlo reference (atmosphere::monteCarloSkyRadiance) or the quadrature
// (atmosphere::eclipsedSkyRadiance, --method fast) along the vertical through the Sun and
// the almucantar at its altitude, beside the same sky without the Moon.
#include "AtmosphereCommon.hpp"
#include "Commands.hpp"
#include "OutputFile.hpp"
#include "ProfileExport.hpp"
#include "ShadowCommon.hpp"  // parseObserver

#include "EclipsedSky.hpp"
#include "MonteCarloSky.hpp"
#include "ShadowLut.hpp"
#include "Sky.hpp"
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
  // The wavelengths' paths are drawn independently: their errors add in quadrature. No
  // errors (the quadrature): none.
  if (error.empty()) {
    c.luminanceError = NAN;
    return c;
  }
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
    std::string preset, config, time, observer, csv, plotVertical, plotAlmucantar, method = "reference";
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
                  "docs/accuracy-vs-speed/atmosphere-tables.md, \"The sky of a solar eclipse\")")
      ->capture_default_str();
  cmd->add_option("--method", o->method,
                  "reference: Monte-Carlo, every order, with its standard error; fast: the quadrature (single and "
                  "second order exact, higher orders from a light field around the observer; its error against the "
                  "reference in docs/accuracy-vs-speed/atmosphere-tables.md)")
      ->check(CLI::IsMember({"reference", "fast"}))
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "Random seed (the same seed, the same numbers)")->capture_default_str();
  cmd->add_option("--step-deg", o->stepDeg, "Step along both curves in degrees (0.1-30)")->capture_default_str();
  cmd->add_option("--csv", o->csv,
                  "CSV file to write: curve,position_deg,view_zenith_deg,view_azimuth_deg,luminance_cd_m2,"
                  "luminance_se_cd_m2,r,g,b,clear_luminance_cd_m2, then radiance_NNNnm,se_NNNnm per wavelength (the standard "
                  "errors empty with --method fast) "
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
      const atmosphere::AtmosphereModelPtr model = atmosphereOption(o->preset, o->config);
      const atmosphere::Atmosphere& atm = model->at(set.nm);
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

      const bool fast = o->method == "fast";
      // Per direction: radiance and standard error per unit solar irradiance (the quadrature
      // has no statistical error: empty).
      std::vector<atmosphere::MonteCarloRadiance> eclipsed, clear;
      double seconds = 0.0;
      if (!fast) {
        atmosphere::MonteCarloSkyOptions mc;
        mc.paths = o->paths;
        mc.seed = o->seed;
        ProgressLine progress("eclipsed sky (Monte-Carlo)");
        const atmosphere::MonteCarloSky e = atmosphere::monteCarloSkyRadiance(
            atm, eye, directions, toSun, shadow, mc, [&](double f) { progress.update(0.5 * f); return true; });
        const atmosphere::MonteCarloSky c = atmosphere::monteCarloSkyRadiance(
            atm, eye, directions, toSun, {}, mc, [&](double f) { progress.update(0.5 + 0.5 * f); return true; });
        progress.update(1.0);
        eclipsed = e.directions, clear = c.directions, seconds = e.seconds + c.seconds;
      } else {
        // The Sun's transmittance from the sky's tables (one order: the transmittance is all
        // the quadrature reads); the Moon's shadow from an airless LuT over the distances
        // from the Moon of the air within 3000 km of the observer.
        const atmosphere::AtmosphereTables tables =
            atmosphere::precompute(atm, atmosphere::skyPrecomputeOptions(atm, 1, 0.5 * kPi - sunAltitude));
        const double moonDistance = glm::length(sky.moonM);
        const eclipse::SunOccluderSystem system{sky.sunRadiusM, sky.moonRadiusM, glm::length(sunM - moonM)};
        const eclipse::LutRange range =
            eclipse::lutRangeForDistances(system, std::max(0.5 * moonDistance, moonDistance - 3e6), moonDistance + 3e6, true);
        eclipse::ShadowLutParams lp;
        lp.uMin = range.uMin, lp.uMax = range.uMax, lp.vMin = range.vMin, lp.vMax = range.vMax;
        lp.vLowFraction = range.vLowFraction;
        const eclipse::ShadowLut lut = eclipse::buildAirlessShadowLut(lp);
        const atmosphere::SunVisibility tabulated = [&](const glm::dvec3& p) {
          return eclipse::eclipseFactor(p, sunM, sky.sunRadiusM, {moonM, sky.moonRadiusM}, &lut).g;
        };
        ProgressLine progress("eclipsed sky (quadrature)");
        const atmosphere::EclipsedSky e = atmosphere::eclipsedSkyRadiance(
            tables, atm, eye, directions, toSun, tabulated, {}, [&](double f) { progress.update(0.5 * f); return true; });
        const atmosphere::EclipsedSky c = atmosphere::eclipsedSkyRadiance(
            tables, atm, eye, directions, toSun, {}, {}, [&](double f) { progress.update(0.5 + 0.5 * f); return true; });
        progress.update(1.0);
        for (std::size_t i = 0; i < directions.size(); ++i) {
          eclipsed.push_back({e.radiance[i], {}});
          clear.push_back({c.radiance[i], {}});
        }
        seconds = e.seconds + c.seconds;
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
        colours.push_back(colourOf(set, spectral(eclipsed[i].radiance), spectral(eclipsed[i].standardError)));
        clearColours.push_back(colourOf(set, spectral(clear[i].radiance), spectral(clear[i].standardError)));
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
          // (an empty standard error: the quadrature's, which has none)
          const auto error = [](double e) {
            char text[32] = "";
            if (std::isfinite(e)) std::snprintf(text, sizeof text, "%.3g", e);
            return std::string(text);
          };
          std::snprintf(line, sizeof line, "%s,%.4f,%.4f,%.4f,%.6g,%s,%.6g,%.6g,%.6g,%.6g", rows[i].curve.c_str(),
                        rows[i].positionDeg, std::acos(std::clamp(d.z, -1.0, 1.0)) / kDeg, azimuth, c.luminance,
                        error(c.luminanceError).c_str(), std::max(c.rgb.r, 0.0), std::max(c.rgb.g, 0.0),
                        std::max(c.rgb.b, 0.0), clearColours[i].luminance);
          f << line;
          const std::vector<double> L = spectral(eclipsed[i].radiance), se = spectral(eclipsed[i].standardError);
          for (std::size_t w = 0; w < L.size(); ++w) {
            std::snprintf(line, sizeof line, ",%.6g,%s", L[w], se.empty() ? "" : error(se[w]).c_str());
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
      const std::string method = fast ? std::string("quadrature")
                                      : "Monte-Carlo, " + std::to_string(o->paths) + " paths a direction and wavelength";
      std::snprintf(subtitle, sizeof subtitle, "%s; Sun %.1f deg up, %.4f of it visible; %s", atm.name.c_str(),
                    sunAltitude / kDeg, visible, method.c_str());
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
      if (fast)
        std::printf("zenith luminance %.4g cd/m^2 (without the Moon %.4g cd/m^2", z.luminance, zClear);
      else
        std::printf("zenith luminance %.4g +- %.2g cd/m^2 (without the Moon %.4g cd/m^2", z.luminance, z.luminanceError, zClear);
      if (z.luminance > 0.0) std::printf(": %.3g times brighter", zClear / z.luminance);
      std::printf(")\n");
      std::cout << "wrote " << o->csv << (o->plotVertical.empty() ? "" : ", " + o->plotVertical)
                << (o->plotAlmucantar.empty() ? "" : ", " + o->plotAlmucantar) << " (" << atm.name << ", "
                << rows.size() << " directions x " << set.size() << " wavelengths, "
                << (fast ? std::string("quadrature") : std::to_string(o->paths) + " paths") << ", twice: "
                << std::lround(seconds) << " s)\n";
      return 0;
    };
  });
}

}  // namespace umbra::cli
