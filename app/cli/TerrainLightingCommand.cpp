// umbra terrain lighting: the lighting of a DEM over a time range (maps of the share of the
// time lit, the longest shadow and the mean visible fraction; the Sun and the Earth at
// chosen points), eclipses included; its time steps shared by MPI ranks.
#include "Commands.hpp"
#include "OutputFile.hpp"
#include "ProfileExport.hpp"
#include "Ranks.hpp"
#include "TerrainSite.hpp"

#include "EclipsedDisc.hpp"
#include "HorizonSweep.hpp"
#include "LightingStatistics.hpp"
#include "MaximumMipmap.hpp"
#include "SoftShadow.hpp"
#include "TerrainImageData.h"
#include "scene/Ephemeris.hpp"
#include "scene/Time.hpp"
#include "scene/Units.hpp"
#include "umbra/tables/Exr.h"

#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkTable.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

namespace umbra::cli {
namespace {

struct LightingOptions {
  SiteOptions site;
  std::string output, method = "sweep", from, to, step, csv, plot;
  std::vector<std::string> points;  // "I,J"
};

/// Another body seen from the site's (direction in the tangent frame, angular radius) at
/// `time`; none where either has no ephemeris or the site's no rotation.
std::optional<terrain::SunDisc> bodySeenFrom(const Site& site, const std::string& other, scene::UtcTime time) {
  const std::string& body = site.body->name;
  if (!scene::hasEphemeris(body) || !scene::hasEphemeris(other) || !scene::hasRotationModel(body)) return std::nullopt;
  const glm::dvec3 towards = scene::heliocentricPositionM(other, time) - scene::heliocentricPositionM(body, time);
  const glm::dvec3 bodyFixed = glm::transpose(scene::bodyFixedToInertial(body, time)) * glm::normalize(towards);
  terrain::SunDisc seen;
  seen.direction = inTangentFrame(site, bodyFixed);
  seen.angularRadiusRad = std::asin(std::min(1.0, scene::findPreset(other)->meanRadiusM / glm::length(towards)));
  return seen;
}

/// The Earth from the site (for communications); none from the Earth itself.
std::optional<terrain::SunDisc> earthFrom(const Site& site, scene::UtcTime time) {
  return site.body->name == "Earth" ? std::nullopt : bodySeenFrom(site, "Earth", time);
}

/// The body that can stand in front of the Sun seen from the site's (the Earth from the
/// Moon, the Moon from the Earth), on the Sun's disc as the grid's centre sees it; none
/// when it does not touch the disc.
std::optional<terrain::OccluderOnDisc> occluderOfSun(const Site& site, scene::UtcTime time, const terrain::SunDisc& sun) {
  const std::string& body = site.body->name;
  const char* other = body == "Moon" ? "Earth" : body == "Earth" ? "Moon" : nullptr;
  const std::optional<terrain::SunDisc> seen = other ? bodySeenFrom(site, other, time) : std::nullopt;
  if (!seen) return std::nullopt;
  const terrain::OccluderOnDisc o = terrain::occluderOnDisc(sun.direction, sun.angularRadiusRad, seen->direction,
                                                            seen->angularRadiusRad, glm::dvec3(0.0, 0.0, 1.0));
  return terrain::overlaps(o) ? std::optional(o) : std::nullopt;
}

double elevationDegOf(const glm::dvec3& d) { return std::asin(std::clamp(glm::normalize(d).z, -1.0, 1.0)) / kTerrainDeg; }
double azimuthDegOf(const glm::dvec3& d) {
  const double a = std::atan2(d.x, d.y) / kTerrainDeg;
  return a < 0.0 ? a + 360.0 : a;
}

std::string timeLabel(scene::UtcTime t) { return scene::formatUtc(t); }

void writeLightingExr(const std::string& path, const terrain::LightingMaps& m, std::map<std::string, std::string> parameters) {
  tables::Table t;
  t.width = m.width;
  t.height = m.height;
  t.channels = {"lit_time_fraction", "longest_shadow_s", "mean_visible_fraction"};
  t.data.resize(static_cast<std::size_t>(m.width) * m.height * 3);
  for (int j = 0; j < m.height; ++j)  // the top row is the DEM's last (+y, north)
    for (int i = 0; i < m.width; ++i) {
      const std::size_t from = static_cast<std::size_t>(j) * m.width + i;
      float* to = &t.data[3 * (static_cast<std::size_t>(m.height - 1 - j) * m.width + i)];
      to[0] = m.litTimeFraction[from], to[1] = m.longestShadowS[from], to[2] = m.meanVisibleFraction[from];
    }
  parameters["rows"] = "top row = last DEM row (+y, north)";
  t.parameters = std::move(parameters);
  tables::writeExr(path, t);
}

void writeLightingVti(const std::string& path, const terrain::HeightField& field, const terrain::LightingMaps& m) {
  auto image = filters::imageFromHeightField(field);
  const std::pair<const char*, const std::vector<float>*> arrays[] = {{"lit_time_fraction", &m.litTimeFraction},
                                                                      {"longest_shadow_s", &m.longestShadowS},
                                                                      {"mean_visible_fraction", &m.meanVisibleFraction}};
  for (const auto& [name, values] : arrays) {
    vtkNew<vtkFloatArray> a;
    a->SetName(name);
    a->SetNumberOfTuples(static_cast<vtkIdType>(values->size()));
    for (std::size_t k = 0; k < values->size(); ++k) a->SetValue(static_cast<vtkIdType>(k), (*values)[k]);
    image->GetPointData()->AddArray(a);
  }
  writeVti(path, image);
}

struct Point {
  int i = 0, j = 0;
};

std::vector<Point> lightingPoints(const LightingOptions& o, const terrain::HeightField& f) {
  std::vector<Point> points;
  for (const std::string& text : o.points) {
    Point p;
    char comma = 0, extra = 0;
    std::istringstream in(text);
    if (!(in >> p.i >> comma >> p.j) || comma != ',' || (in >> extra))
      throw CommandError("--point: expected I,J (grid column and row), got '" + text + "'");
    if (p.i < 0 || p.j < 0 || p.i >= f.width || p.j >= f.height)
      throw CommandError("--point: " + text + " lies outside the " + std::to_string(f.width) + " x " +
                         std::to_string(f.height) + " grid");
    points.push_back(p);
  }
  if (points.empty()) points.push_back({f.width / 2, f.height / 2});  // the centre
  return points;
}

/// The points' visible fraction over time, one line each.
void writeLightingPlot(const std::string& path, const std::vector<Point>& points, const std::vector<double>& hours,
                       const std::vector<std::vector<double>>& fractions, const std::string& from, const std::string& source) {
  vtkNew<vtkTable> table;
  vtkNew<vtkDoubleArray> x;
  x->SetName("hours");
  for (double h : hours) x->InsertNextValue(h);
  table->AddColumn(x);
  plot::ProfilePlotStyle style;
  style.xColumn = "hours";
  style.xLabel = "hours from " + from;
  style.yLabel = "visible fraction of the solar disc";
  style.subtitle = source;
  style.legendTop = true;
  static const unsigned char palette[][3] = {{220, 50, 47}, {40, 100, 220}, {60, 160, 60}, {200, 130, 0}, {120, 60, 170}, {30, 30, 30}};
  for (std::size_t p = 0; p < points.size(); ++p) {
    vtkNew<vtkDoubleArray> y;
    const std::string name = "point" + std::to_string(p + 1);
    y->SetName(name.c_str());
    for (double v : fractions[p]) y->InsertNextValue(v);
    table->AddColumn(y);
    const unsigned char* c = palette[p % 6];
    style.lines.push_back({name, "point " + std::to_string(p + 1) + " (" + std::to_string(points[p].i) + ", " +
                                     std::to_string(points[p].j) + ")",
                           c[0], c[1], c[2], 1.5f});
  }
  try {
    plot::writeProfilePlot(table, path, "The Sun at the points", style);
  } catch (const std::exception& e) {
    throw CommandError(e.what());
  }
}

/// What one rank makes of its share of the steps: the statistics, the CSV's rows, and for
/// the plot each step's hours and the points' fractions (1 + points numbers a step).
struct LightingShare {
  terrain::LightingAccumulator stats;
  std::string csv;
  std::vector<double> series;
};

/// Steps [begin, end) of `times` on the site: each step's map, the statistics, the points.
LightingShare lightSteps(const LightingOptions& o, const Site& site, const std::vector<Point>& points,
                         const std::vector<scene::UtcTime>& times, std::size_t begin, std::size_t end, bool showProgress) {
  const terrain::HeightField& field = site.dem.field;
  // Each step stands for the time nearer to it than to the others, within the range: half
  // a step on each side, the first and the last clipped at --from and --to.
  const double stepS = scene::parseDurationS(o.step);
  const double spanS = scene::secondsBetween(times.front(), scene::parseUtc(o.to));
  const terrain::MaximumMipmap mip(field);  // the DP's, and the Earth's horizon at the points
  LightingShare share{terrain::LightingAccumulator(field.width, field.height), {}, {}};
  std::ostringstream csv;
  std::optional<ProgressLine> progress;
  if (showProgress) progress.emplace("terrain lighting");
  for (std::size_t k = begin; k < end; ++k) {
    terrain::SunDisc sun;
    try {
      const scene::SunFromBody s = scene::sunFromBody(site.body->name, times[k]);
      sun.direction = inTangentFrame(site, s.directionBodyFixed);
      sun.angularRadiusRad = s.angularRadiusRad;
    } catch (const std::invalid_argument& e) {
      throw CommandError(std::string("--body: ") + e.what());
    }
    // An eclipse: the part of the disc above each sample's horizon and outside the occluder.
    const std::optional<terrain::OccluderOnDisc> occluder = occluderOfSun(site, times[k], sun);
    const double eclipseFraction =
        occluder ? terrain::visibleFractionAboveHorizonOutside(2.0, *occluder, sun.limbDarkening) : 1.0;
    std::vector<float> fraction;
    if (o.method == "sweep") {
      fraction = terrain::sweepVisibleFractionMap(field, sun, occluder ? &*occluder : nullptr);
    } else if (!occluder) {
      const std::vector<double> map = terrain::visibleFractionMap(field, mip, sun, terrain::ShadowOptions{});
      fraction.assign(map.begin(), map.end());
    } else {
      for (const terrain::Horizon& h : terrain::horizonMap(field, mip, sun, terrain::ShadowOptions{}))
        fraction.push_back(static_cast<float>(
            h.degenerate ? (h.sunElevationRad > 0.0 ? eclipseFraction : 0.0)
                         : terrain::visibleFractionAboveHorizonOutside(
                               (h.sunElevationRad - h.horizonElevationRad) / sun.angularRadiusRad, *occluder,
                               sun.limbDarkening)));
    }
    const double at = k * stepS;
    share.stats.add(fraction, std::min(at + 0.5 * stepS, spanS) - std::max(at - 0.5 * stepS, 0.0));
    share.series.push_back(at / 3600.0);
    const std::optional<terrain::SunDisc> earth = earthFrom(site, times[k]);
    for (std::size_t p = 0; p < points.size(); ++p) {
      const Point& q = points[p];
      const double v = fraction[static_cast<std::size_t>(q.j) * field.width + q.i];
      share.series.push_back(v);
      csv << timeLabel(times[k]) << ',' << p + 1 << ',' << q.i << ',' << q.j << ',' << terrainNumber(elevationDegOf(sun.direction))
          << ',' << terrainNumber(azimuthDegOf(sun.direction)) << ',' << terrainNumber(eclipseFraction) << ',' << terrainNumber(v);
      if (earth)
        csv << ',' << terrainNumber(elevationDegOf(earth->direction)) << ','
            << terrainNumber(terrain::visibleFraction(field, mip, q.i, q.j, *earth, terrain::ShadowOptions{}));
      else
        csv << ",,";
      csv << '\n';
    }
    if (progress) progress->update(double(k + 1 - begin) / double(end - begin));
  }
  share.csv = csv.str();
  return share;
}

/// The maps, the CSV and the plot of the whole range (on rank 0).
void writeLighting(const LightingOptions& o, const Site& site, const std::vector<Point>& points, std::size_t steps,
                   const terrain::LightingMaps& maps, const std::string& csvRows, const std::vector<double>& series) {
  const terrain::HeightField& field = site.dem.field;
  if (output::extensionOf(o.output) == ".vti") {
    writeLightingVti(o.output, field, maps);
  } else {
    writeLightingExr(o.output, maps,
                     {{"source", site.source}, {"method", o.method}, {"from", o.from}, {"to", o.to}, {"step", o.step},
                      {"steps", std::to_string(steps)}, {"body", site.body->name},
                      {"latDeg", terrainNumber(site.latDeg)}, {"lonDeg", terrainNumber(site.lonDeg)}, {"spacingM", terrainNumber(field.spacingM)},
                      {"bodyRadiusM", terrainNumber(field.bodyRadiusM)}, {"totalS", terrainNumber(maps.totalS)}});
  }
  if (!o.csv.empty()) {
    output::OutputFile out(o.csv);
    {
      std::ofstream file(out.tempPath());
      file << "time_utc,point,i,j,sun_elevation_deg,sun_azimuth_deg,eclipse_visible_fraction,visible_solar_fraction,"
              "earth_elevation_deg,earth_visible_fraction\n"
           << csvRows;
      if (!file) throw CommandError(o.csv + ": cannot write");
    }
    out.commit();
  }
  if (!o.plot.empty()) {
    std::vector<double> hours;
    std::vector<std::vector<double>> fractions(points.size());
    for (std::size_t k = 0; k + points.size() < series.size(); k += 1 + points.size()) {
      hours.push_back(series[k]);
      for (std::size_t p = 0; p < points.size(); ++p) fractions[p].push_back(series[k + 1 + p]);
    }
    writeLightingPlot(o.plot, points, hours, fractions, o.from, site.source);
  }
}

int runLighting(const LightingOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  output::checkWritable(o.output, {".exr", ".vti"});
  if (!o.csv.empty()) output::checkWritable(o.csv, {".csv"});
  if (!o.plot.empty()) output::checkWritable(o.plot, {".png", ".svg"});
  if (o.method != "sweep" && o.method != "dp") throw CommandError("--method: expected sweep or dp, got '" + o.method + "'");
  const std::vector<scene::UtcTime> times = timeSteps(o.from, o.to, o.step);
  const Site site = loadSite(o.site);
  const terrain::HeightField& field = site.dem.field;
  const std::vector<Point> points = lightingPoints(o, field);

  // Under mpirun the steps are shared by the ranks; rank 0 joins their statistics in time order.
  parallel::Ranks& ranks = parallel::Ranks::world();
  if (ranks.root()) noteTimesBeyondEphemeris(times);
  const auto [begin, end] = parallel::share(times.size(), ranks.rank(), ranks.size());
  std::optional<LightingShare> mine;
  std::string error;
  try {
    mine.emplace(lightSteps(o, site, points, times, begin, end, ranks.root()));
  } catch (const std::exception& e) {
    error = e.what();
  }
  if (const std::string errors = ranks.finish(error); !errors.empty()) throw CommandError(errors);
  const std::vector<double> states = ranks.gather(mine->stats.state());
  const std::vector<std::string> csvs = ranks.gather(mine->csv);
  const std::vector<double> series = ranks.gather(mine->series);
  if (!ranks.root()) return 0;
  const std::size_t stateSize = mine->stats.state().size();
  terrain::LightingAccumulator stats =
      terrain::LightingAccumulator::fromState(field.width, field.height, states.data(), stateSize);
  for (std::size_t r = 1; r * stateSize < states.size(); ++r)
    stats.append(terrain::LightingAccumulator::fromState(field.width, field.height, states.data() + r * stateSize, stateSize));
  std::string csvRows;
  for (const std::string& rows : csvs) csvRows += rows;
  const terrain::LightingMaps maps = stats.maps();
  writeLighting(o, site, points, times.size(), maps, csvRows, series);

  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string others = (o.csv.empty() ? "" : ", " + o.csv) + (o.plot.empty() ? "" : ", " + o.plot);
  std::printf("wrote %s%s: %d x %d at %.6g m (%s), %zu steps of %s from %s, method %s, %.2f s%s\n", o.output.c_str(),
              others.c_str(), field.width, field.height, field.spacingM, site.source.c_str(), times.size(),
              o.step.c_str(), timeLabel(times.front()).c_str(), o.method.c_str(), seconds, ranksNote(start).c_str());
  for (std::size_t p = 0; p < points.size(); ++p) {
    const std::size_t at = static_cast<std::size_t>(points[p].j) * field.width + points[p].i;
    std::printf("point %zu (%d, %d): lit %.1f %% of the time, longest shadow %.1f h, mean visible fraction %.4f\n", p + 1,
                points[p].i, points[p].j, 100.0 * maps.litTimeFraction[at], maps.longestShadowS[at] / 3600.0,
                maps.meanVisibleFraction[at]);
  }
  return 0;
}

} // namespace

void addTerrainLightingCommand(CLI::App* terrainCmd, Action& action) {
  CLI::App* lighting = terrainCmd->add_subcommand(
      "lighting",
      "Lighting over time at every sample of a DEM: the fraction of the time lit, the longest continuous shadow "
      "and the mean visible fraction of the solar disc (maps), and at chosen points the Sun's and the Earth's "
      "visibility at each step (CSV)");
  auto o = std::make_shared<LightingOptions>();
  const auto checkSite = addSiteOptions(lighting, o->site, "");
  lighting->add_option("--from", o->from, "UTC time of the first step, ISO 8601")->required();
  lighting->add_option("--to", o->to, "UTC time of the last step at most, ISO 8601")->required();
  lighting->add_option("--step", o->step, "Time between steps, e.g. 1h (units s, min, h, d); each step stands for the time nearer to it than to the others, within the range")
      ->required();
  lighting->add_option("--method", o->method,
                       "sweep (every sample at once along the Sun's azimuth: the fast path) or dp (the DP search at "
                       "every sample: the reference; docs/accuracy-vs-speed/terrain.md)")
      ->capture_default_str();
  lighting->add_option("--point", o->points, "A point for the CSV: I,J (grid column, row; repeat the option for more; "
                                             "default: the centre)");
  lighting->add_option("--csv", o->csv, "The points' time series: the Sun's elevation and azimuth, the fraction of "
                                        "its disc an eclipse leaves (the Earth from the Moon, the Moon from the Earth), "
                                        "the fraction visible at the point (horizon and eclipse together), the Earth's "
                                        "elevation and visible fraction (bodies other than Earth)");
  lighting->add_option("--plot", o->plot, "The points' visible fraction of the Sun over time: .png or .svg");
  lighting->add_option("--output", o->output, "The maps: .exr (three float channels) or .vti (with the heights)")->required();
  lighting->callback([&action, o, checkSite] {
    action = [o, checkSite] {
      checkSite();
      return runLighting(*o);
    };
  });
}

} // namespace umbra::cli
