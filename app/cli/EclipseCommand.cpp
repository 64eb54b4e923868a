// umbra eclipse local --date DATE --observer LAT,LON[,ALT] [--csv FILE]
//   A solar eclipse seen from one place: C1, C2, greatest, C3, C4 in UT with the Sun's
//   altitude and azimuth at each, magnitude, obscuration, duration of totality.
// umbra eclipse path --date DATE --geojson FILE [--png FILE] [--step SECONDS]
//   A central solar eclipse's path: the central line with the duration along it, the
//   limits of the umbra (antumbra) and of the penumbra, as GeoJSON and drawn on the Blue
//   Marble map.
#include "Commands.hpp"
#include "OutputFile.hpp"
#include "ShadowCommon.hpp"  // parseObserver

#include "EclipsedMoon.hpp"
#include "Photometry.hpp"
#include "ShadowLut.hpp"
#include "ShadowMapping.hpp"
#include "scene/Bodies.hpp"
#include "scene/DeltaT.hpp"
#include "scene/Eclipses.hpp"
#include "scene/Scene.hpp"

#include <vtkImageData.h>
#include <vtkImageReader2.h>
#include <vtkImageReader2Factory.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

namespace umbra::cli {
namespace {

struct DateOptions {
  std::string date;
  std::optional<double> deltaT;
  void addTo(CLI::App* cmd) {
    cmd->add_option("--date", date, "The eclipse's date, UT: YYYY-MM-DD")->required();
    cmd->add_option("--delta-t", deltaT, "Delta T = TT - UT1 in seconds (default: docs/eclipse-predictions.md)")
        ->check(CLI::Range(-1e6, 1e6));
  }
};

std::string utOf(double tt, double deltaTSeconds) { return scene::formatJulianDate(scene::ut1FromTt(tt, deltaTSeconds)); }

/// The eclipse (`find`: scene::findSolarEclipses or findLunarEclipses) whose greatest eclipse
/// falls on --date (UT). Throws CommandError naming the next one when there is none.
template <class Find>
auto eclipseOn(const DateOptions& o, const char* kind, Find find) -> typename decltype(find(scene::EclipseSearch{}))::value_type {
  double day = 0.0;
  try {
    day = scene::parseUtDate(o.date);
  } catch (const std::invalid_argument& e) {
    throw CommandError(std::string("--date: ") + e.what());
  }
  day = std::floor(day - 0.5) + 0.5;  // 0h UT
  scene::EclipseSearch search;
  search.deltaTSeconds = o.deltaT;
  search.fromTt = scene::ttFromUt1(day, o.deltaT);
  search.toTt = scene::ttFromUt1(day + 1.0, o.deltaT);
  try {
    const auto found = find(search);
    if (!found.empty()) return found.front();
    search.toTt = search.fromTt + 200.0;
    const auto later = find(search);
    std::string next;
    if (!later.empty())
      next = "; the next is the " + std::string(scene::typeName(later.front().type)) + " eclipse of " +
             utOf(later.front().greatestTt, later.front().deltaTSeconds).substr(0, 10);
    throw CommandError("--date: no " + std::string(kind) + " eclipse on " + o.date + next);
  } catch (const std::invalid_argument& e) {
    throw CommandError(std::string("--date: ") + e.what());
  }
}

scene::SolarEclipse solarEclipseOn(const DateOptions& o) { return eclipseOn(o, "solar", scene::findSolarEclipses); }
scene::LunarEclipse lunarEclipseOn(const DateOptions& o) { return eclipseOn(o, "lunar", scene::findLunarEclipses); }

/// GeoJSON's [lon, lat] pairs of a line, split where it crosses the antimeridian (RFC 7946,
/// 3.1.9): a MultiLineString's lines.
std::vector<std::vector<scene::GeoPlace>> splitAtAntimeridian(const std::vector<scene::GeoPlace>& line) {
  std::vector<std::vector<scene::GeoPlace>> parts(1);
  for (size_t i = 0; i < line.size(); ++i) {
    if (i > 0 && std::abs(line[i].longitudeDeg - line[i - 1].longitudeDeg) > 180.0) parts.emplace_back();
    parts.back().push_back(line[i]);
  }
  return parts;
}

/// A feature of one or more lines (each split at the antimeridian) as a MultiLineString.
void writeLinesFeature(std::ostream& f, const std::string& name, const std::vector<std::vector<scene::GeoPlace>>& lines,
                       bool& first) {
  std::vector<std::vector<scene::GeoPlace>> parts;
  for (const auto& line : lines)
    for (auto& part : splitAtAntimeridian(line))
      if (part.size() >= 2) parts.push_back(std::move(part));
  if (parts.empty()) return;
  f << (first ? "" : ",\n") << R"(  {"type": "Feature", "properties": {"name": ")" << name
    << R"("}, "geometry": {"type": "MultiLineString", "coordinates": [)";
  first = false;
  bool firstPart = true;
  for (const auto& part : parts) {
    f << (firstPart ? "" : ", ") << "[";
    firstPart = false;
    char b[64];
    for (size_t i = 0; i < part.size(); ++i) {
      std::snprintf(b, sizeof b, "%s[%.5f, %.5f]", i ? ", " : "", part[i].longitudeDeg, part[i].latitudeDeg);
      f << b;
    }
    f << "]";
  }
  f << "]}}";
}

void writeLineFeature(std::ostream& f, const std::string& name, const std::vector<scene::GeoPlace>& line, bool& first) {
  writeLinesFeature(f, name, {line}, first);
}

void writeGeoJson(const std::string& path, const scene::SolarEclipse& e, const scene::SolarEclipsePath& p,
                  const std::vector<std::vector<scene::GeoPlace>>& outline) {
  output::OutputFile out(path);
  {
    std::ofstream f(out.tempPath());
    f << "{\"type\": \"FeatureCollection\", \"features\": [\n";
    bool first = true;
    std::vector<scene::GeoPlace> central;
    for (const auto& c : p.centralLine) central.push_back(c.place);
    writeLineFeature(f, "central line", central, first);
    writeLineFeature(f, "northern limit", p.northernLimit, first);
    writeLineFeature(f, "southern limit", p.southernLimit, first);
    writeLineFeature(f, "northern limit of the partial eclipse", p.northernPenumbralLimit, first);
    writeLineFeature(f, "southern limit of the partial eclipse", p.southernPenumbralLimit, first);
    writeLinesFeature(f, "outline of the partial eclipse", outline, first);
    char b[320];
    for (const auto& c : p.centralLine) {
      std::snprintf(b, sizeof b,
                    R"(%s  {"type": "Feature", "properties": {"name": "central line point", "time_ut": "%s", )"
                    R"("duration_s": %.1f, "width_km": %s, "sun_altitude_deg": %.2f}, )"
                    R"("geometry": {"type": "Point", "coordinates": [%.5f, %.5f]}})",
                    first ? "" : ",\n", utOf(c.tt, e.deltaTSeconds).c_str(), c.durationS,
                    c.widthKm ? std::to_string(*c.widthKm).c_str() : "null", c.sunAltitudeDeg, c.place.longitudeDeg,
                    c.place.latitudeDeg);
      first = false;
      f << b;
    }
    f << "\n]}\n";
    if (!f.flush()) throw CommandError(path + ": cannot write");
  }
  out.commit();
}

/// The path drawn on the Blue Marble (equirectangular, from marble-qt-data).
void writeMapPng(const std::string& path, const scene::SolarEclipsePath& p,
                 const std::vector<std::vector<scene::GeoPlace>>& outline) {
  const auto map = scene::findNamedAlbedoMap("bluemarble");
  vtkSmartPointer<vtkImageReader2> reader;
  if (map) reader.TakeReference(vtkImageReader2Factory::CreateImageReader2(map->file.c_str()));
  if (!reader)
    throw CommandError("--png: cannot read the Blue Marble map " + (map ? map->file : std::string("")) +
                       " (install marble-qt-data)");
  reader->SetFileName(map->file.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  if (dims[0] < 2 || dims[1] < 2 || image->GetNumberOfScalarComponents() < 3)
    throw CommandError("--png: " + map->file + " is not a colour map");
  const int w = dims[0], h = dims[1];
  const auto plot = [&](const scene::GeoPlace& g, const unsigned char rgb[3]) {
    // VTK's rows run from the bottom: latitude -90 at row 0.
    const int x = std::clamp(static_cast<int>((g.longitudeDeg + 180.0) / 360.0 * w), 0, w - 1);
    const int y = std::clamp(static_cast<int>((g.latitudeDeg + 90.0) / 180.0 * h), 0, h - 1);
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int xx = std::clamp(x + dx, 0, w - 1), yy = std::clamp(y + dy, 0, h - 1);
        auto* px = static_cast<unsigned char*>(image->GetScalarPointer(xx, yy, 0));
        std::copy(rgb, rgb + 3, px);
      }
  };
  const auto line = [&](const std::vector<scene::GeoPlace>& l, const unsigned char rgb[3]) {
    for (size_t i = 0; i < l.size(); ++i) {
      plot(l[i], rgb);
      if (i == 0 || std::abs(l[i].longitudeDeg - l[i - 1].longitudeDeg) > 180.0) continue;
      const int steps = 16;  // fill between samples
      for (int s = 1; s < steps; ++s) {
        const double f = static_cast<double>(s) / steps;
        plot({l[i - 1].latitudeDeg + f * (l[i].latitudeDeg - l[i - 1].latitudeDeg),
              l[i - 1].longitudeDeg + f * (l[i].longitudeDeg - l[i - 1].longitudeDeg), 0.0},
             rgb);
      }
    }
  };
  const unsigned char red[3] = {255, 40, 40}, yellow[3] = {255, 220, 0}, white[3] = {235, 235, 235};
  for (const auto& piece : outline) line(piece, white);
  line(p.northernLimit, yellow);
  line(p.southernLimit, yellow);
  std::vector<scene::GeoPlace> central;
  for (const auto& c : p.centralLine) central.push_back(c.place);
  line(central, red);
  writePng(image, path);
}

std::string hms(double seconds) {
  const long s = std::lround(seconds);
  char b[32];
  std::snprintf(b, sizeof b, "%ldm%02lds", s / 60, s % 60);
  return b;
}

}  // namespace

void addEclipseCommand(CLI::App& app, Action& action) {
  CLI::App* eclipse = app.add_subcommand("eclipse", "One solar eclipse: as seen from a place (local), or its path on the Earth (path)");
  eclipse->require_subcommand(1);

  CLI::App* local = eclipse->add_subcommand(
      "local", "The solar eclipse of --date seen from --observer: contacts C1-C4 and greatest eclipse in UT with the "
               "Sun's altitude and azimuth, magnitude, obscuration, duration of totality or annularity");
  auto lo = std::make_shared<DateOptions>();
  auto observer = std::make_shared<std::string>();
  auto localCsv = std::make_shared<std::string>();
  lo->addTo(local);
  local->add_option("--observer", *observer, "LAT,LON[,ALT]: geodetic degrees north and east; ALT in m, km (default 0)")
      ->required();
  local->add_option("--csv", *localCsv, "Also write CSV: event,time_ut,sun_altitude_deg,sun_azimuth_deg");
  local->callback([&action, lo, observer, localCsv] {
    action = [lo, observer, localCsv] {
      if (!localCsv->empty()) output::checkWritable(*localCsv, {".csv"});
      const scene::Observer o = parseObserver(*observer);
      const scene::SolarEclipse e = solarEclipseOn(*lo);
      const scene::LocalSolarEclipse l = scene::localSolarEclipse(e, {o.latDeg, o.lonDeg, o.altM});
      std::printf("The %s solar eclipse of %s seen from %.4f, %.4f (%.0f m); Delta T %.1f s (%s)\n",
                  scene::typeName(e.type), lo->date.c_str(), o.latDeg, o.lonDeg, o.altM, e.deltaTSeconds,
                  e.deltaTSource.c_str());
      struct Event {
        const char* name;
        std::optional<scene::LocalInstant> at;
      };
      const std::vector<Event> events{{"C1", l.c1}, {"C2", l.c2}, {"greatest", l.eclipsed ? std::optional(l.greatest) : std::nullopt},
                                      {"C3", l.c3}, {"C4", l.c4}};
      if (!l.eclipsed) {
        std::printf("not eclipsed there: the penumbra passes by; the Moon's centre comes nearest the Sun's at %s UT\n",
                    utOf(l.greatest.tt, e.deltaTSeconds).c_str());
      } else {
        std::printf("%-9s %-23s %9s %9s\n", "event", "time (UT)", "Sun alt", "Sun az");
        for (const Event& ev : events)
          if (ev.at)
            std::printf("%-9s %-23s %+9.2f %9.2f%s\n", ev.name, utOf(ev.at->tt, e.deltaTSeconds).c_str(),
                        ev.at->sunAltitudeDeg, ev.at->sunAzimuthDeg, ev.at->sunAltitudeDeg < 0.0 ? "  (Sun below the horizon)" : "");
        std::printf("magnitude %.4f, obscuration %.4f, %s", l.magnitude, l.obscuration, scene::typeName(l.phase));
        if (l.centralDurationS) std::printf(" for %s", hms(*l.centralDurationS).c_str());
        std::printf("\n");
      }
      if (!localCsv->empty()) {
        output::OutputFile out(*localCsv);
        {
          std::ofstream f(out.tempPath());
          f << "event,time_ut,sun_altitude_deg,sun_azimuth_deg\n";
          char b[160];
          for (const Event& ev : events)
            if (ev.at) {
              std::snprintf(b, sizeof b, "%s,%s,%.3f,%.3f\n", ev.name, utOf(ev.at->tt, e.deltaTSeconds).c_str(),
                            ev.at->sunAltitudeDeg, ev.at->sunAzimuthDeg);
              f << b;
            }
          std::snprintf(b, sizeof b, "magnitude,%.5f,,\nobscuration,%.5f,,\n", l.magnitude, l.obscuration);
          f << b;
          if (l.centralDurationS) {
            std::snprintf(b, sizeof b, "%s_duration_s,%.2f,,\n", scene::typeName(l.phase), *l.centralDurationS);
            f << b;
          }
          if (!f.flush()) throw CommandError(*localCsv + ": cannot write");
        }
        out.commit();
        std::printf("wrote %s\n", localCsv->c_str());
      }
      return 0;
    };
  });

  CLI::App* brightness = eclipse->add_subcommand(
      "brightness", "How dark the lunar eclipse of --date is at greatest eclipse through --atmosphere: the Moon's "
                    "integrated V, its surface brightness at the centre and the limbs, and the Danjon L");
  struct BrightnessOptions {
    DateOptions date;
    EclipseAtmosphereChoice atmosphere;
    std::string csv;
    int samples = 801;
    bool spherical = false;
    std::string cloudTop = "10km";
  };
  auto bo = std::make_shared<BrightnessOptions>();
  bo->date.addTo(brightness);
  bo->atmosphere.addTo(brightness);
  brightness->get_option("--atmosphere")->required();
  brightness->add_option("--samples", bo->samples, "Samples of the shadow's cross-section, axis to past the penumbra")
      ->check(CLI::Range(16, 100000))
      ->capture_default_str();
  brightness->add_flag("--spherical", bo->spherical, "A spherical Earth (default: its oblate outline as seen from the Moon)");
  brightness->add_option("--cloud-cover", bo->atmosphere.cloudCover,
                         "The fraction of the Earth's limb under opaque clouds (default 0: a clear sky)")
      ->check(CLI::Range(0.0, 1.0));
  brightness->add_option("--cloud-top", bo->cloudTop, "Their tops' altitude (m, km): rays passing lower are stopped")
      ->capture_default_str();
  brightness->add_option("--csv", bo->csv, "Also write CSV: quantity,value,unit");
  brightness->callback([&action, bo] {
    action = [bo] {
      if (!bo->csv.empty()) output::checkWritable(bo->csv, {".csv"});
      bo->atmosphere.cloudTopM = lengthOption("--cloud-top", bo->cloudTop, 0.0, 30e3);
      const scene::LunarEclipse e = lunarEclipseOn(bo->date);
      const scene::LunarShadowGeometry g = scene::lunarShadowGeometry(e.greatestTt);
      bo->atmosphere.bottomRadiusM();  // a one-line error for a bad atmosphere
      OccluderChoice earth = chooseOccluder("Earth", "", "");
      earth.sunDistanceM = g.sunDistanceM;
      const scene::Body moonBody = scene::presetBody("Moon", scene::fromTt(e.greatestTt, 0.0));
      const double moonRadiusM = moonBody.radiusM;
      // From the axis to past the penumbra's edge on the far side of the Moon.
      const double reachM = std::hypot(g.moonOffsetXM, g.moonOffsetYM) + moonRadiusM;
      const double maxOffsetM = std::max(reachM, 1.05 * eclipse::shadowConeRadii(
          {eclipse::kSunRadiusM, earth.radiusM, earth.sunDistanceM}, g.moonDistanceM).penumbraRadiusM) + 100e3;
      const std::vector<eclipse::ProfileSample> profile = atmosphericProfileSamples(
          bo->atmosphere, earth, g.moonDistanceM, maxOffsetM, bo->samples, eclipse::kDefaultLimbDarkening);
      const scene::EclipseConstants k;
      const eclipse::EarthOutline outline =
          bo->spherical ? eclipse::EarthOutline{earth.radiusM, earth.radiusM, earth.radiusM}
                        : eclipse::earthOutline(k.earthEquatorialRadiusM, k.earthFlattening, g.axisDeclinationRad, earth.radiusM);
      const eclipse::EclipsedMoonLight light =
          eclipse::eclipsedMoonLight(profile, {g.moonOffsetXM, g.moonOffsetYM}, moonRadiusM, outline);
      // The Moon outside the shadow, lit from the Earth's limb as the shadow's light comes:
      // the phase angle is the limb's angular radius seen from the Moon (its opposition surge).
      const double phaseRad = std::asin(k.earthEquatorialRadiusM / g.moonDistanceM);
      const double fullV = sky::apparentMagnitudeV(moonBody.albedo, moonBody.photometry.hapke, phaseRad, moonRadiusM,
                                                   g.sunDistanceM, g.moonDistanceM);
      const eclipse::EclipsedMoonMagnitudes m =
          eclipse::eclipsedMoonMagnitudes(fullV, eclipse::angularRadiusRad(moonRadiusM, g.moonDistanceM), light);
      for (double x : {m.v, m.centreSurface, m.nearLimbSurface, m.farLimbSurface})
        if (!std::isfinite(x)) throw CommandError("the eclipse's brightness is not finite (the shadow profile has no value there)");
      std::string clouds;
      if (bo->atmosphere.cloudCover > 0.0) {
        char b[96];
        std::snprintf(b, sizeof b, ", clouds to %.1f km over %.0f %% of the limb", bo->atmosphere.cloudTopM / 1000.0,
                      100.0 * bo->atmosphere.cloudCover);
        clouds = b;
      }
      std::printf("The %s lunar eclipse of %s, greatest at %s UT (gamma %+.4f, umbral magnitude %.4f), through %s%s%s\n",
                  scene::typeName(e.type), bo->date.date.c_str(), utOf(e.greatestTt, e.deltaTSeconds).c_str(), e.gamma,
                  e.umbralMagnitude, bo->atmosphere.atmosphere.c_str(), clouds.c_str(),
                  bo->spherical ? " (a spherical Earth)" : "");
      std::printf("the Moon %.0f km away, its centre %.0f km from the shadow's axis\n", g.moonDistanceM / 1000.0,
                  std::hypot(g.moonOffsetXM, g.moonOffsetYM) / 1000.0);
      std::printf("V outside the shadow %.2f; in it %.2f (%.2f magnitudes dimmer), Danjon L %.1f\n", fullV, m.v, m.v - fullV,
                  m.danjonL);
      std::printf("surface brightness, mag/arcsec^2: centre %.2f, limb nearest the axis %.2f, farthest %.2f (full Moon %.2f)\n",
                  m.centreSurface, m.nearLimbSurface, m.farLimbSurface, m.fullSurface);
      if (!bo->csv.empty()) {
        output::OutputFile out(bo->csv);
        {
          std::ofstream f(out.tempPath());
          char b[512];
          std::snprintf(b, sizeof b,
                        "quantity,value,unit\ngreatest_ut,%s,\nmoon_distance,%.1f,km\naxis_offset,%.1f,km\n"
                        "v_outside_shadow,%.3f,mag\nv,%.3f,mag\nshadow_factor_mean,%.6g,\ndanjon_l,%.2f,\n"
                        "surface_brightness_centre,%.3f,mag/arcsec2\nsurface_brightness_near_limb,%.3f,mag/arcsec2\n"
                        "surface_brightness_far_limb,%.3f,mag/arcsec2\n",
                        utOf(e.greatestTt, e.deltaTSeconds).c_str(), g.moonDistanceM / 1000.0,
                        std::hypot(g.moonOffsetXM, g.moonOffsetYM) / 1000.0, fullV, m.v, light.mean, m.danjonL,
                        m.centreSurface, m.nearLimbSurface, m.farLimbSurface);
          f << b;
          if (!f.flush()) throw CommandError(bo->csv + ": cannot write");
        }
        out.commit();
        std::printf("wrote %s\n", bo->csv.c_str());
      }
      return 0;
    };
  });

  CLI::App* path = eclipse->add_subcommand(
      "path", "The solar eclipse of --date on the map: the outline of where the partial eclipse is seen; for a central "
              "one the central line (with the duration along it) and the limits of the umbra or antumbra, as GeoJSON "
              "and on a map");
  struct PathOptions {
    DateOptions date;
    std::string geojson, png;
    double stepSeconds = 60.0;
  };
  auto po = std::make_shared<PathOptions>();
  po->date.addTo(path);
  path->add_option("--geojson", po->geojson, "GeoJSON file (opens in QGIS)")->required();
  path->add_option("--png", po->png, "Also draw the path on the Blue Marble map (marble-qt-data)");
  path->add_option("--step", po->stepSeconds, "Seconds between points of the central line")
      ->check(CLI::Range(1.0, 3600.0))
      ->capture_default_str();
  path->callback([&action, po] {
    action = [po] {
      output::checkWritable(po->geojson, {".geojson", ".json"});
      if (!po->png.empty()) output::checkWritable(po->png, {".png"});
      const scene::SolarEclipse e = solarEclipseOn(po->date);
      const auto outline = scene::partialEclipseOutline(e);
      scene::SolarEclipsePath p;
      if (e.central) p = scene::solarEclipsePath(e, po->stepSeconds);
      if (e.central && p.centralLine.empty()) throw CommandError("--date: the central line has no point on the ground");
      writeGeoJson(po->geojson, e, p, outline);
      if (!po->png.empty()) writeMapPng(po->png, p, outline);
      if (!e.central) {
        std::printf("The %s solar eclipse of %s: no central line; the outline of the partial eclipse in %zu line%s\n",
                    scene::typeName(e.type), po->date.date.c_str(), outline.size(), outline.size() == 1 ? "" : "s");
        std::printf("wrote %s%s%s\n", po->geojson.c_str(), po->png.empty() ? "" : " and ", po->png.c_str());
        return 0;
      }
      const auto longest = std::max_element(p.centralLine.begin(), p.centralLine.end(),
                                            [](const auto& a, const auto& b) { return a.durationS < b.durationS; });
      std::printf("The %s solar eclipse of %s: the central line from %s to %s UT, %zu points; the longest %s at "
                  "%.2f, %.2f (%s UT)\n",
                  scene::typeName(e.type), po->date.date.c_str(), utOf(p.centralLine.front().tt, e.deltaTSeconds).c_str(),
                  utOf(p.centralLine.back().tt, e.deltaTSeconds).c_str(), p.centralLine.size(),
                  hms(longest->durationS).c_str(), longest->place.latitudeDeg, longest->place.longitudeDeg,
                  utOf(longest->tt, e.deltaTSeconds).c_str());
      std::printf("wrote %s", po->geojson.c_str());
      if (!po->png.empty()) std::printf(" and %s", po->png.c_str());
      std::printf("\n");
      return 0;
    };
  });
}

}  // namespace umbra::cli
