// umbra moon [--time ISO8601 | --from ISO8601 --to ISO8601 --step DURATION] [--observer LAT,LON[,ALT]] [--csv FILE]
//   The Moon's numbers (scene::moonNumbers): position, distance, size, phase, bright limb,
//   V magnitude, optical libration and earthshine; a table over time with --from/--to/--step.
#include "Commands.hpp"
#include "OutputFile.hpp"
#include "ShadowCommon.hpp"  // lengthOption

#include "scene/Moon.hpp"
#include "scene/Time.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>

namespace umbra::cli {
namespace {

constexpr const char* kCsvHeader =
    "time_utc,ra_deg,dec_deg,altitude_deg,azimuth_deg,distance_km,angular_diameter_arcmin,phase_angle_deg,"
    "illuminated_fraction,bright_limb_position_angle_deg,magnitude_v,libration_longitude_deg,libration_latitude_deg,"
    "earthshine_w_m2,ecliptic_longitude_deg,ecliptic_latitude_deg";

std::string csvRow(const scene::MoonNumbers& m) {
  const double values[] = {m.rightAscensionDeg, m.declinationDeg, m.altitudeDeg.value_or(0.0), m.azimuthDeg.value_or(0.0),
                           m.distanceKm, m.angularDiameterArcmin, m.phaseAngleDeg, m.illuminatedFraction,
                           m.brightLimbPositionAngleDeg, m.magnitudeV, m.librationLongitudeDeg,
                           m.librationLatitudeDeg, m.earthshineWm2, m.eclipticLongitudeDeg, m.eclipticLatitudeDeg};
  for (double v : values)
    if (!std::isfinite(v))
      throw CommandError("the Moon's numbers at " + scene::formatUtc(m.time) + " are not finite (new Moon's magnitude?)");
  char line[512];
  std::snprintf(line, sizeof line, "%s,%.6f,%.6f,%s,%s,%.3f,%.4f,%.4f,%.5f,%.3f,%.3f,%.4f,%.4f,%.6g,%.6f,%.6f",
                scene::formatUtc(m.time).c_str(), values[0], values[1],
                m.altitudeDeg ? std::to_string(*m.altitudeDeg).c_str() : "", m.azimuthDeg ? std::to_string(*m.azimuthDeg).c_str() : "",
                m.distanceKm, m.angularDiameterArcmin, m.phaseAngleDeg, m.illuminatedFraction,
                m.brightLimbPositionAngleDeg, m.magnitudeV, m.librationLongitudeDeg, m.librationLatitudeDeg,
                m.earthshineWm2, m.eclipticLongitudeDeg, m.eclipticLatitudeDeg);
  return line;
}

void printBlock(const scene::MoonNumbers& m) {
  std::printf("The Moon at %s, seen from %s\n", scene::formatUtc(m.time).c_str(),
              m.topocentric ? "the observer" : "the Earth's centre");
  std::printf("  right ascension     %10.4f deg   (true equator and equinox of date)\n", m.rightAscensionDeg);
  std::printf("  declination         %+10.4f deg\n", m.declinationDeg);
  if (m.altitudeDeg) {
    std::printf("  altitude            %+10.4f deg   (geometric, no refraction)\n", *m.altitudeDeg);
    std::printf("  azimuth             %10.4f deg   (from north through east)\n", *m.azimuthDeg);
  }
  std::printf("  distance            %10.1f km\n", m.distanceKm);
  std::printf("  angular diameter    %10.3f arcmin\n", m.angularDiameterArcmin);
  std::printf("  phase angle         %10.4f deg\n", m.phaseAngleDeg);
  std::printf("  illuminated         %10.4f\n", m.illuminatedFraction);
  std::printf("  bright limb at      %10.2f deg   (position angle, from north through east)\n",
              m.brightLimbPositionAngleDeg);
  std::printf("  magnitude V         %+10.2f       (outside eclipses)\n", m.magnitudeV);
  std::printf("  libration           %+10.3f deg in longitude, %+.3f deg in latitude (optical)\n",
              m.librationLongitudeDeg, m.librationLatitudeDeg);
  std::printf("  earthshine          %10.4g W m^-2 on the Moon\n", m.earthshineWm2);
}

}  // namespace

void addMoonCommand(CLI::App& app, Action& action) {
  CLI::App* moon = app.add_subcommand(
      "moon", "The Moon's numbers: position (RA/Dec, altitude/azimuth), distance, angular diameter, phase angle, "
              "illuminated fraction, bright limb, V magnitude, optical libration and earthshine; a table over time "
              "with --from/--to/--step");
  struct Options {
    std::string time, observer, csv, from, to, step;
  };
  auto o = std::make_shared<Options>();
  moon->add_option("--time", o->time, "UTC time, ISO 8601 (default: now)");
  moon->add_option("--observer", o->observer,
                   "An observer on the Earth: LAT,LON[,ALT] (geodetic degrees north and east; ALT in m, km; default "
                   "0): topocentric numbers and altitude/azimuth (default: the Earth's centre)");
  moon->add_option("--from", o->from, "A table over time: the first UTC time, ISO 8601");
  moon->add_option("--to", o->to, "A table over time: the last UTC time at most, ISO 8601");
  moon->add_option("--step", o->step, "A table over time: the step, e.g. 1h or 1d (units s, min, h, d)");
  moon->add_option("--csv", o->csv, "Also write the numbers as CSV (one row per time)");

  moon->callback([&action, o] {
    action = [o] {
      const bool series = !o->from.empty() || !o->to.empty() || !o->step.empty();
      if (series && !o->time.empty()) throw CommandError("--time: not with --from/--to/--step");
      if (!o->csv.empty()) output::checkWritable(o->csv, {".csv"});
      std::optional<scene::Observer> observer;
      if (!o->observer.empty()) observer = parseObserver(o->observer);
      std::vector<scene::UtcTime> times;
      if (series) {
        times = timeSteps(o->from, o->to, o->step);
      } else {
        times.push_back(timeOption(o->time));
      }
      noteTimesBeyondEphemeris(times);
      std::vector<std::string> rows;
      std::vector<scene::MoonNumbers> numbers;
      for (const scene::UtcTime& t : times) {
        numbers.push_back(scene::moonNumbers(t, observer));
        rows.push_back(csvRow(numbers.back()));  // checks every value is finite
      }
      if (!o->csv.empty()) {
        output::OutputFile out(o->csv);
        {
          std::ofstream f(out.tempPath());
          f << kCsvHeader << "\n";
          for (const std::string& r : rows) f << r << "\n";
          if (!f.flush()) throw CommandError(o->csv + ": cannot write");
        }
        out.commit();
      }
      if (!series) {
        printBlock(numbers.front());
      } else {
        std::printf("%-20s %9s %9s %8s %9s %7s %6s %7s %6s %7s %7s\n", "time (UTC)", "alt deg", "az deg", "dist km",
                    "diam '", "phase", "lit", "V", "lib l", "lib b", "ES W/m2");
        for (const scene::MoonNumbers& m : numbers) {
          char alt[16] = "-", az[16] = "-";
          if (m.altitudeDeg) std::snprintf(alt, sizeof alt, "%+.2f", *m.altitudeDeg);
          if (m.azimuthDeg) std::snprintf(az, sizeof az, "%.2f", *m.azimuthDeg);
          std::printf("%-20s %9s %9s %8.0f %9.3f %7.2f %6.3f %+7.2f %+6.2f %+7.2f %7.3g\n",
                      scene::formatUtc(m.time).c_str(), alt, az, m.distanceKm, m.angularDiameterArcmin,
                      m.phaseAngleDeg, m.illuminatedFraction, m.magnitudeV, m.librationLongitudeDeg,
                      m.librationLatitudeDeg, m.earthshineWm2);
        }
      }
      if (!o->csv.empty()) std::printf("wrote %s (%zu rows)\n", o->csv.c_str(), rows.size());
      return 0;
    };
  });
}

}  // namespace umbra::cli
