// umbra planets [--time ISO8601] [--observer LAT,LON[,ALT]] [--csv FILE]
//   Mercury, Venus, Mars, Jupiter and Saturn seen from the Earth's centre or an observer on it
//   (scene::planetsSeenFrom): right ascension and declination (ICRS, astrometric), altitude
//   and azimuth, distance, phase angle, illuminated fraction, V magnitude and Saturn's ring tilt.
#include "Commands.hpp"
#include "OutputFile.hpp"
#include "ShadowCommon.hpp"  // parseObserver

#include "scene/Bodies.hpp"
#include "scene/Planets.hpp"
#include "scene/Scene.hpp"
#include "scene/Time.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>

namespace umbra::cli {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

struct PlanetRow {
  scene::PlanetSeen p;
  double raDeg = 0.0, decDeg = 0.0;
  std::optional<double> altitudeDeg, azimuthDeg;
};

}  // namespace

void addPlanetsCommand(CLI::App& app, Action& action) {
  CLI::App* cmd = app.add_subcommand(
      "planets", "Mercury, Venus, Mars, Jupiter and Saturn: right ascension and declination (ICRS), altitude and "
                 "azimuth, distance, phase angle, illuminated fraction, V magnitude (Mallama & Hilton 2018) and "
                 "Saturn's ring tilt");
  struct Options {
    std::string time, observer, csv;
  };
  auto o = std::make_shared<Options>();
  cmd->add_option("--time", o->time, "UTC time, ISO 8601 (default: now)");
  cmd->add_option("--observer", o->observer,
                  "An observer on the Earth: LAT,LON[,ALT] (geodetic degrees north and east; ALT in m, km; default "
                  "0): altitude and azimuth too (default: the Earth's centre)");
  cmd->add_option("--csv", o->csv,
                  "Also write CSV: planet,ra_deg,dec_deg,altitude_deg,azimuth_deg,distance_au,sun_distance_au,"
                  "phase_angle_deg,illuminated_fraction,magnitude_v,ring_tilt_deg (Saturn's: the observer's latitude "
                  "over its rings, north positive; empty for the others)");

  cmd->callback([&action, o] {
    action = [o] {
      if (!o->csv.empty()) output::checkWritable(o->csv, {".csv"});
      const scene::UtcTime time = timeOption(o->time);
      noteTimesBeyondEphemeris({time});
      const scene::Body earth = scene::presetBody("Earth", time);
      glm::dvec3 eye = earth.positionM, east(0.0), north(0.0), up(0.0);
      std::optional<scene::Observer> observer;
      if (!o->observer.empty()) {
        observer = parseObserver(o->observer);
        eye = scene::observerPositionM(earth, *observer, time);
        east = scene::horizontalDirection(earth, *observer, {90.0, 0.0}, time);
        north = scene::horizontalDirection(earth, *observer, {0.0, 0.0}, time);
        up = scene::horizontalDirection(earth, *observer, {0.0, 90.0}, time);
      }
      std::vector<PlanetRow> rows;
      for (const scene::PlanetSeen& p : scene::planetsSeenFrom(eye, time)) {
        PlanetRow r;
        r.p = p;
        const glm::dvec3& d = p.directionIcrs;
        r.raDeg = std::fmod(std::atan2(d.y, d.x) / kDeg + 360.0, 360.0);
        r.decDeg = std::asin(std::clamp(d.z, -1.0, 1.0)) / kDeg;
        if (observer) {
          r.altitudeDeg = std::asin(std::clamp(glm::dot(d, up), -1.0, 1.0)) / kDeg;
          r.azimuthDeg = std::fmod(std::atan2(glm::dot(d, east), glm::dot(d, north)) / kDeg + 360.0, 360.0);
        }
        for (double v : {r.raDeg, r.decDeg, p.distanceAu, p.phaseAngleDeg, p.magnitudeV})
          if (!std::isfinite(v)) throw CommandError(p.name + "'s numbers at " + scene::formatUtc(time) + " are not finite");
        rows.push_back(r);
      }
      const auto lit = [](const scene::PlanetSeen& p) { return 0.5 * (1.0 + std::cos(p.phaseAngleDeg * kDeg)); };
      if (!o->csv.empty()) {
        output::OutputFile out(o->csv);
        {
          std::ofstream f(out.tempPath());
          f << "planet,ra_deg,dec_deg,altitude_deg,azimuth_deg,distance_au,sun_distance_au,phase_angle_deg,"
               "illuminated_fraction,magnitude_v,ring_tilt_deg\n";
          char line[256];
          for (const PlanetRow& r : rows) {
            char alt[24] = "", az[24] = "", tilt[24] = "";
            if (r.altitudeDeg) std::snprintf(alt, sizeof alt, "%.4f", *r.altitudeDeg);
            if (r.azimuthDeg) std::snprintf(az, sizeof az, "%.4f", *r.azimuthDeg);
            if (r.p.name == "Saturn") std::snprintf(tilt, sizeof tilt, "%.3f", r.p.ringTiltDeg);
            std::snprintf(line, sizeof line, "%s,%.6f,%.6f,%s,%s,%.7f,%.7f,%.4f,%.5f,%.3f,%s\n", r.p.name.c_str(),
                          r.raDeg, r.decDeg, alt, az, r.p.distanceAu, r.p.sunDistanceAu, r.p.phaseAngleDeg, lit(r.p),
                          r.p.magnitudeV, tilt);
            f << line;
          }
          if (!f.flush()) throw CommandError(o->csv + ": cannot write");
        }
        out.commit();
      }
      std::printf("The planets at %s, seen from %s (RA/Dec: ICRS, astrometric; altitude: geometric)\n",
                  scene::formatUtc(time).c_str(), observer ? "the observer" : "the Earth's centre");
      std::printf("%-8s %9s %9s %8s %8s %10s %8s %6s %6s\n", "planet", "RA deg", "Dec deg", "alt deg", "az deg",
                  "dist au", "phase", "lit", "V");
      for (const PlanetRow& r : rows) {
        char alt[16] = "-", az[16] = "-";
        if (r.altitudeDeg) std::snprintf(alt, sizeof alt, "%+.2f", *r.altitudeDeg);
        if (r.azimuthDeg) std::snprintf(az, sizeof az, "%.2f", *r.azimuthDeg);
        std::printf("%-8s %9.4f %+9.4f %8s %8s %10.6f %8.2f %6.3f %+6.2f\n", r.p.name.c_str(), r.raDeg, r.decDeg, alt, az,
                    r.p.distanceAu, r.p.phaseAngleDeg, lit(r.p), r.p.magnitudeV);
      }
      if (!o->csv.empty()) std::printf("wrote %s (%zu rows)\n", o->csv.c_str(), rows.size());
      return 0;
    };
  });
}

}  // namespace umbra::cli
