// umbra eclipses --from DATE --to DATE [--kind solar|lunar|both] [--csv FILE]
//   Every solar and lunar eclipse whose greatest eclipse falls in the span (scene::Eclipses):
//   type, greatest eclipse in UT and TT with the Delta T used, gamma, magnitudes, contacts,
//   Saros series; for solar eclipses the point of greatest eclipse, and the duration and
//   path width there for central ones.
#include "Commands.hpp"
#include "EclipsedMoon.hpp"
#include "OutputFile.hpp"
#include "ShadowCommon.hpp"

#include "scene/DeltaT.hpp"
#include "scene/Eclipses.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

namespace umbra::cli {
namespace {


/// A contact's UT, or "" when the eclipse has none.
std::string ut(const scene::Contact& tt, double deltaTSeconds, int decimals = 1) {
  return tt ? scene::formatJulianDate(scene::ut1FromTt(*tt, deltaTSeconds), decimals) : "";
}

std::string number(const std::optional<double>& v, const char* format) {
  if (!v) return "";
  char b[32];
  std::snprintf(b, sizeof b, format, *v);
  return b;
}

/// One eclipse as a row: the solar and lunar ones share the columns.
struct Row {
  std::string kind, type, greatestUt, greatestTt, deltaTSource;
  double deltaT = 0.0, gamma = 0.0, magnitude = 0.0;
  std::optional<double> penumbralMagnitude, latitude, longitude, sunAltitude, duration, width;
  std::vector<std::string> contacts;  // P1 P2 U1 U2 U3 U4 P3 P4, UT
  int saros = 0;
  double sortKey = 0.0;
};

Row row(const scene::SolarEclipse& e) {
  Row r;
  r.kind = "solar";
  r.type = scene::typeName(e.type);
  if (!e.central && e.type != scene::SolarEclipseType::Partial) r.type += " (non-central)";
  r.greatestUt = ut(e.greatestTt, e.deltaTSeconds);
  r.greatestTt = scene::formatJulianDate(e.greatestTt);
  r.deltaT = e.deltaTSeconds, r.deltaTSource = e.deltaTSource;
  r.gamma = e.gamma, r.magnitude = e.magnitude;
  r.latitude = e.latitudeDeg, r.longitude = e.longitudeDeg, r.sunAltitude = e.sunAltitudeDeg;
  r.duration = e.centralDurationS, r.width = e.pathWidthKm;
  for (const auto* c : {&e.p1, &e.p2, &e.u1, &e.u2, &e.u3, &e.u4, &e.p3, &e.p4}) r.contacts.push_back(ut(*c, e.deltaTSeconds));
  r.saros = e.saros;
  r.sortKey = e.greatestTt;
  return r;
}

Row row(const scene::LunarEclipse& e) {
  Row r;
  r.kind = "lunar";
  r.type = scene::typeName(e.type);
  r.greatestUt = ut(e.greatestTt, e.deltaTSeconds);
  r.greatestTt = scene::formatJulianDate(e.greatestTt);
  r.deltaT = e.deltaTSeconds, r.deltaTSource = e.deltaTSource;
  r.gamma = e.gamma, r.magnitude = e.umbralMagnitude, r.penumbralMagnitude = e.penumbralMagnitude;
  for (const auto* c : {&e.p1, static_cast<const scene::Contact*>(nullptr), &e.u1, &e.u2, &e.u3, &e.u4,
                        static_cast<const scene::Contact*>(nullptr), &e.p4})
    r.contacts.push_back(c ? ut(*c, e.deltaTSeconds) : "");
  r.saros = e.saros;
  r.sortKey = e.greatestTt;
  return r;
}

}  // namespace

void addEclipsesCommand(CLI::App& app, Action& action) {
  CLI::App* cmd = app.add_subcommand(
      "eclipses", "Every solar and lunar eclipse between two dates: type, greatest eclipse (UT and TT, with Delta T), "
                  "gamma, magnitudes, contacts and Saros series (positions: ELP 2000-82B and ERFA; NASA's constants)");
  struct Options {
    std::string from, to, kind = "both", csv, lunarShadow = "danjon", atmosphere = "earth";
    std::optional<double> deltaT;
    bool oblate = false;
  };
  auto o = std::make_shared<Options>();
  cmd->add_option("--from", o->from, "First date, UT: YYYY-MM-DD[THH:MM[:SS]] (proleptic Gregorian; -0584-05-28 for 585 BC)")
      ->required();
  cmd->add_option("--to", o->to, "Last date, UT (inclusive), as --from")->required();
  cmd->add_option("--kind", o->kind, "solar, lunar or both")->check(CLI::IsMember({"solar", "lunar", "both"}))
      ->capture_default_str();
  cmd->add_option("--csv", o->csv,
                  "Also write CSV: kind,type,greatest_ut,greatest_tt,delta_t_s,delta_t_source,gamma,magnitude,"
                  "penumbral_magnitude,saros,latitude_deg,longitude_deg,sun_altitude_deg,central_duration_s,"
                  "path_width_km,p1_ut,p2_ut,u1_ut,u2_ut,u3_ut,u4_ut,p3_ut,p4_ut");
  cmd->add_option("--delta-t", o->deltaT,
                  "Delta T = TT - UT1 in seconds for every eclipse (default: from the leap seconds 1972-2026, "
                  "Espenak & Meeus 2006 outside)")
      ->check(CLI::Range(-1e6, 1e6));
  cmd->add_option("--lunar-shadow", o->lunarShadow,
                  "How the atmosphere enlarges the Earth's shadow: danjon (the Earth's radius + 1/85, as NASA's "
                  "canon), chauvenet (the shadow + 1/50, as the Astronomical Almanac) or physical (the umbra's edge "
                  "where --atmosphere's shadow profile is steepest)")
      ->check(CLI::IsMember({"danjon", "chauvenet", "physical"}))
      ->capture_default_str();
  cmd->add_option("--atmosphere", o->atmosphere, "With --lunar-shadow physical: the atmosphere preset or file")
      ->capture_default_str();
  cmd->add_flag("--oblate-shadow", o->oblate,
                "The Earth's outline an ellipse (flattening 1/298.257) as the Moon sees it, in the lunar contacts and "
                "magnitudes (default: a sphere, as the rules are published)");

  cmd->callback([&action, o] {
    action = [o] {
      if (!o->csv.empty()) output::checkWritable(o->csv, {".csv"});
      scene::EclipseSearch search;
      try {
        const auto toTt = [&](const std::string& text) { return scene::ttFromUt1(scene::parseUtDate(text), o->deltaT); };
        search.fromTt = toTt(o->from);
        search.toTt = toTt(o->to);
      } catch (const std::invalid_argument& e) {
        throw CommandError(std::string("--from/--to: ") + e.what());
      }
      if (search.toTt < search.fromTt) throw CommandError("--to (" + o->to + ") is before --from (" + o->from + ")");
      search.deltaTSeconds = o->deltaT;
      search.lunarRule = o->lunarShadow == "chauvenet" ? scene::LunarShadowRule::Chauvenet
                         : o->lunarShadow == "physical" ? scene::LunarShadowRule::Physical
                                                        : scene::LunarShadowRule::Danjon;
      search.oblateShadow = o->oblate;
      if (search.lunarRule == scene::LunarShadowRule::Physical && o->kind != "solar") {
        // The edge of the shadow through the atmosphere at the Moon's mean distance, 1 au from the Sun.
        EclipseAtmosphereChoice atmosphere;
        atmosphere.atmosphere = o->atmosphere;
        atmosphere.bottomRadiusM();  // one line naming --atmosphere when it is bad
        const OccluderChoice earth = chooseOccluder("Earth", "", "1au");
        const double distanceM = 384400e3;
        std::vector<eclipse::ProfileSample> profile =
            atmosphericProfileSamples(atmosphere, earth, distanceM, 0.0, 2001, eclipse::kDefaultLimbDarkening);
        for (auto& p : profile) p.luminance = std::max(p.luminance, 1e-300);
        search.physicalEnlargementM =
            eclipse::umbraEdgeEnlargementM(profile, {eclipse::kSunRadiusM, earth.radiusM, earth.sunDistanceM}, distanceM);
        std::fprintf(stderr, "umbra: note: the umbra's edge through %s: the Earth's radius enlarged by %.1f km (1/%.0f)\n",
                     o->atmosphere.c_str(), search.physicalEnlargementM / 1000.0, earth.radiusM / search.physicalEnlargementM);
      }
      std::vector<Row> rows;
      try {
        if (o->kind != "lunar") {
          ProgressLine progress("solar eclipses");
          search.progress = [&](double f) { progress.update(f); };
          for (const auto& e : scene::findSolarEclipses(search)) rows.push_back(row(e));
        }
        if (o->kind != "solar") {
          ProgressLine progress("lunar eclipses");
          search.progress = [&](double f) { progress.update(f); };
          for (const auto& e : scene::findLunarEclipses(search)) rows.push_back(row(e));
        }
      } catch (const std::invalid_argument& e) {
        throw CommandError(e.what());
      }
      std::stable_sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.sortKey < b.sortKey; });
      for (const Row& r : rows)
        for (double v : {r.gamma, r.magnitude, r.deltaT})
          if (!std::isfinite(v)) throw CommandError("the " + r.kind + " eclipse of " + r.greatestUt + " has a number that is not finite");

      if (!o->csv.empty()) {
        output::OutputFile out(o->csv);
        {
          std::ofstream f(out.tempPath());
          f << "kind,type,greatest_ut,greatest_tt,delta_t_s,delta_t_source,gamma,magnitude,penumbral_magnitude,saros,"
               "latitude_deg,longitude_deg,sun_altitude_deg,central_duration_s,path_width_km,p1_ut,p2_ut,u1_ut,u2_ut,"
               "u3_ut,u4_ut,p3_ut,p4_ut\n";
          for (const Row& r : rows) {
            char head[160];
            std::snprintf(head, sizeof head, "%.1f,%s,%.4f,%.4f,", r.deltaT, r.deltaTSource.c_str(), r.gamma, r.magnitude);
            f << r.kind << ',' << r.type << ',' << r.greatestUt << ',' << r.greatestTt << ',' << head
              << number(r.penumbralMagnitude, "%.4f") << ',' << r.saros << ',' << number(r.latitude, "%.3f") << ','
              << number(r.longitude, "%.3f") << ',' << number(r.sunAltitude, "%.1f") << ','
              << number(r.duration, "%.1f") << ',' << number(r.width, "%.1f");
            for (const std::string& c : r.contacts) f << ',' << c;
            f << '\n';
          }
          if (!f.flush()) throw CommandError(o->csv + ": cannot write");
        }
        out.commit();
      }

      std::printf("%-5s %-22s %-21s %6s %8s %7s %7s %5s %s\n", "kind", "type", "greatest (UT)", "dT s", "gamma",
                  "mag", "pen.mag", "saros", "central: place, duration, width / Sun's altitude");
      bool uncertain = false;
      for (const Row& r : rows) {
        std::string where;
        if (r.latitude) {
          char b[96];
          std::snprintf(b, sizeof b, "%6.2f %7.2f  alt %4.1f", *r.latitude, *r.longitude, *r.sunAltitude);
          where = b;
          if (r.duration) {
            const int s = static_cast<int>(std::lround(*r.duration));
            std::snprintf(b, sizeof b, "  %dm%02ds", s / 60, s % 60);
            where += b;
          }
          if (r.width) where += "  " + number(r.width, "%.1f") + " km";
        }
        std::printf("%-5s %-22s %-21s %6.1f %+8.4f %7.4f %7s %5d %s\n", r.kind.c_str(), r.type.c_str(),
                    r.greatestUt.c_str(), r.deltaT, r.gamma, r.magnitude, number(r.penumbralMagnitude, "%.4f").c_str(),
                    r.saros, where.c_str());
        const double year = scene::decimalYear(r.sortKey);
        uncertain = uncertain || !scene::deltaTAtYear(year).wellKnown;
      }
      if (uncertain && !o->deltaT)
        std::fprintf(stderr,
                     "umbra: note: some eclipses fall outside 1600-2200, where Delta T is uncertain (minutes, hours "
                     "in antiquity): so are their UT times and, for the Sun, their places on the Earth\n");
      std::printf("%zu eclipse%s", rows.size(), rows.size() == 1 ? "" : "s");
      if (!o->csv.empty()) std::printf("; wrote %s", o->csv.c_str());
      std::printf("\n");
      return 0;
    };
  });
}

}  // namespace umbra::cli
