// umbra terrain shadow: the visible fraction of the solar disc over a DEM (terrain paper).
#include "Commands.hpp"
#include "OutputFile.hpp"
#include "ProfileExport.hpp"
#include "Ranks.hpp"
#include "ShadowCommon.hpp"  // lengthOption
#include "TerrainDem.hpp"

#include "CraterField.hpp"
#include "HorizonSweep.hpp"
#include "LightingStatistics.hpp"
#include "SoftShadow.hpp"
#include "SolarDisc.hpp"
#include "TerrainImageData.h"
#include "scene/Bodies.hpp"
#include "scene/Ephemeris.hpp"
#include "scene/Time.hpp"
#include "umbra/tables/Exr.h"
#include "vtkTerrainHorizonShadowFilter.h"

#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkTable.h>
#include <vtkUnsignedShortArray.h>
#include <vtkXMLImageDataWriter.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <sstream>

namespace umbra::cli {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

struct Options {
  std::string dem, output, method = "dp", time, body = "Moon", bodyRadius, spacing = "30m";
  std::string from, to, step, csv, plot;  // lighting
  std::vector<std::string> points;   // lighting: "I,J"
  long long seed = -1;
  int size = 512, levels = 6, uniformSteps = 128;
  double elevationDeg = NAN, azimuthDeg = NAN, latitudeDeg = NAN, longitudeDeg = NAN, limbDarkening = 0.0;
};

/// The Sun in the DEM's tangent frame and its angular radius.
struct SunSetting {
  glm::dvec3 direction;
  double angularRadiusRad;
};

SunSetting sunFromTime(const Options& o, const scene::BodyPreset& body, double latDeg, double lonDeg) {
  try {
    const scene::SunFromBody sun = scene::sunFromBody(body.name, scene::parseUtc(o.time));
    return {terrain::bodyFixedToTangent(latDeg, lonDeg) * sun.directionBodyFixed, sun.angularRadiusRad};
  } catch (const std::invalid_argument& e) {
    throw CommandError(std::string("--time: ") + e.what());
  }
}

void writePng(const std::string& path, vtkImageData* result) {
  vtkDataArray* fraction = result->GetPointData()->GetArray("visible_solar_fraction");
  vtkNew<vtkImageData> image;
  image->SetDimensions(result->GetDimensions());
  vtkNew<vtkUnsignedShortArray> gray;  // linear, 0 = umbra, 65535 = fully lit
  gray->SetNumberOfTuples(fraction->GetNumberOfTuples());
  for (vtkIdType k = 0; k < fraction->GetNumberOfTuples(); ++k)
    gray->SetValue(k, static_cast<unsigned short>(std::lround(65535.0 * fraction->GetTuple1(k))));
  image->GetPointData()->SetScalars(gray);
  // VTK's first row is the bottom of the picture: north up
  umbra::cli::writePng(image, path);
}

void writeVti(const std::string& path, vtkImageData* result) {
  output::OutputFile out(path);
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(result);
  writer->SetFileName(out.tempPath().c_str());
  if (writer->Write() != 1 || writer->GetErrorCode() != 0) throw CommandError(path + ": cannot write");
  out.commit();
}

void writeExr(const std::string& path, vtkImageData* result, std::map<std::string, std::string> parameters) {
  vtkDataArray* fraction = result->GetPointData()->GetArray("visible_solar_fraction");
  int dims[3];
  result->GetDimensions(dims);
  tables::Table t;
  t.width = dims[0];
  t.height = dims[1];
  t.channels = {"visible_solar_fraction"};
  t.data.resize(static_cast<std::size_t>(dims[0]) * dims[1]);
  for (int j = 0; j < dims[1]; ++j)  // the top row is the DEM's last (+y, north)
    for (int i = 0; i < dims[0]; ++i)
      t.data[static_cast<std::size_t>(dims[1] - 1 - j) * dims[0] + i] =
          static_cast<float>(fraction->GetTuple1(static_cast<vtkIdType>(j) * dims[0] + i));
  parameters["rows"] = "top row = last DEM row (+y, north)";
  t.parameters = std::move(parameters);
  tables::writeExr(path, t);
}

std::string fmt(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.10g", v);
  return b;
}

/// The terrain of `o` (a DEM or a synthetic crater field), its body and its centre.
struct Site {
  Dem dem;
  std::string source;
  const scene::BodyPreset* body = nullptr;
  double latDeg = 0.0, lonDeg = 0.0;
};

Site loadSite(const Options& o) {
  Site site;
  site.body = scene::findPreset(o.body);
  if (!site.body) throw CommandError("--body: unknown body '" + o.body + "' (known: " + scene::presetNameList() + ")");
  const scene::BodyPreset* body = site.body;
  const double radiusOverride = o.bodyRadius.empty() ? 0.0 : lengthOption("--body-radius", o.bodyRadius, 1.0, kMaxRadiusM);
  const double spacingM = lengthOption("--spacing", o.spacing);
  if (!(spacingM > 0.0)) throw CommandError("--spacing: expected a positive length, got " + o.spacing);
  Dem& dem = site.dem;
  if (!o.dem.empty()) {
    dem = readDem(o.dem, spacingM, radiusOverride > 0.0 ? radiusOverride : (body->name == "Moon" ? 0.0 : body->meanRadiusM));
    site.source = o.dem;
  } else {
    terrain::CraterFieldOptions c;
    c.seed = static_cast<std::uint64_t>(o.seed);
    c.size = o.size;
    c.spacingM = spacingM;
    c.bodyRadiusM = radiusOverride > 0.0 ? radiusOverride : body->meanRadiusM;
    try {
      dem.field = terrain::makeCraterField(c);
      dem.field.validate();
    } catch (const std::exception& e) {
      throw CommandError(std::string("--synthetic with --size and --spacing: ") + e.what());
    }
    site.source = "synthetic crater field, seed " + std::to_string(o.seed);
  }
  site.latDeg = !std::isnan(o.latitudeDeg) ? o.latitudeDeg : dem.centreLatitudeDeg.value_or(-90.0);
  site.lonDeg = !std::isnan(o.longitudeDeg) ? o.longitudeDeg : dem.centreLongitudeDeg.value_or(0.0);
  if (!(site.latDeg >= -90.0 && site.latDeg <= 90.0)) throw CommandError("--lat-deg: expected -90..90");
  return site;
}

int runShadow(const Options& o) {
  output::checkWritable(o.output, {".exr", ".png", ".vti"});
  const terrain::ShadowMethod method = [&] {
    try {
      return terrain::parseShadowMethod(o.method);
    } catch (const std::exception& e) {
      throw CommandError(std::string("--method: ") + e.what());
    }
  }();
  const Site site = loadSite(o);
  const Dem& dem = site.dem;
  const std::string& source = site.source;
  const scene::BodyPreset* body = site.body;
  const double latDeg = site.latDeg, lonDeg = site.lonDeg;

  // The Sun.
  SunSetting sun;
  const bool angles = !std::isnan(o.elevationDeg) || !std::isnan(o.azimuthDeg);
  if (angles == !o.time.empty())
    throw CommandError("give either --sun-elevation-deg and --sun-azimuth-deg, or --time");
  if (angles) {
    if (std::isnan(o.elevationDeg) || std::isnan(o.azimuthDeg))
      throw CommandError("give both --sun-elevation-deg and --sun-azimuth-deg");
    if (!(o.elevationDeg >= -90.0 && o.elevationDeg <= 90.0)) throw CommandError("--sun-elevation-deg: expected -90..90");
    if (!std::isfinite(o.azimuthDeg)) throw CommandError("--sun-azimuth-deg: expected a finite angle");
    const double distance = scene::meanDistanceFromSunM(*body);
    sun = {terrain::sunDirectionFromElevationAzimuth(o.elevationDeg * kDeg, o.azimuthDeg * kDeg),
           distance > 0.0 ? std::asin(eclipse::kSunRadiusM / distance) : terrain::kSunAngularRadiusAt1AuRad};
  } else {
    sun = sunFromTime(o, *body, latDeg, lonDeg);
  }
  const double elevationDeg = std::asin(std::clamp(sun.direction.z, -1.0, 1.0)) / kDeg;
  double azimuthDeg = std::atan2(sun.direction.x, sun.direction.y) / kDeg;
  if (azimuthDeg < 0.0) azimuthDeg += 360.0;

  // The shadow, through the filter.
  auto image = filters::imageFromHeightField(dem.field);
  vtkNew<vtkTerrainHorizonShadowFilter> filter;
  filter->SetInputData(image);
  filter->SetSunDirection(sun.direction.x, sun.direction.y, sun.direction.z);
  filter->SetSunAngularRadiusRad(sun.angularRadiusRad);
  filter->SetLimbDarkening(o.limbDarkening);
  filter->SetBodyRadiusM(dem.field.bodyRadiusM);
  filter->SetMethod(static_cast<int>(method));
  filter->SetLevels(o.levels);
  filter->SetUniformSteps(o.uniformSteps);
  ProgressLine progress("terrain shadow", filter);
  const auto t0 = std::chrono::steady_clock::now();
  filter->Update();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  vtkImageData* result = filter->GetOutput();
  vtkDataArray* fraction = result->GetPointData()->GetArray("visible_solar_fraction");
  if (!fraction) throw CommandError("the shadow computation failed");

  const std::string ext = output::extensionOf(o.output);
  if (ext == ".png") writePng(o.output, result);
  else if (ext == ".vti") writeVti(o.output, result);
  else
    writeExr(o.output, result,
             {{"source", source}, {"method", o.method}, {"levels", std::to_string(o.levels)},
              {"uniformSteps", std::to_string(o.uniformSteps)}, {"spacingM", fmt(dem.field.spacingM)},
              {"bodyRadiusM", fmt(dem.field.bodyRadiusM)}, {"sunElevationDeg", fmt(elevationDeg)},
              {"sunAzimuthDeg", fmt(azimuthDeg)}, {"sunAngularRadiusRad", fmt(sun.angularRadiusRad)},
              {"limbDarkening", fmt(o.limbDarkening)}, {"time", o.time}});

  double sum = 0.0;
  long long umbra = 0, lit = 0;
  const vtkIdType n = fraction->GetNumberOfTuples();
  for (vtkIdType k = 0; k < n; ++k) {
    const double v = fraction->GetTuple1(k);
    sum += v, umbra += v == 0.0, lit += v == 1.0;
  }
  std::printf("wrote %s: %d x %d at %.6g m (%s), method %s, %.2f s\n", o.output.c_str(), dem.field.width,
              dem.field.height, dem.field.spacingM, source.c_str(), o.method.c_str(), seconds);
  std::printf("sun elevation %.9f deg, azimuth %.9f deg at the centre (lat %.6f, lon %.6f), radius %.6f deg\n",
              elevationDeg, azimuthDeg, latDeg, lonDeg, sun.angularRadiusRad / kDeg);
  std::printf("mean visible fraction %.4f; umbra %.1f %%, penumbra %.1f %%, fully lit %.1f %%\n", sum / n,
              100.0 * umbra / n, 100.0 * (n - umbra - lit) / n, 100.0 * lit / n);
  return 0;
}

/// A direction in the site's tangent frame from the body-fixed one.
glm::dvec3 inTangentFrame(const Site& site, const glm::dvec3& bodyFixed) {
  return terrain::bodyFixedToTangent(site.latDeg, site.lonDeg) * bodyFixed;
}

/// The Earth seen from the site's body at `time` (tangent frame, angular radius); none from Earth.
std::optional<terrain::SunDisc> earthFrom(const Site& site, scene::UtcTime time) {
  if (site.body->name == "Earth" || !scene::hasEphemeris(site.body->name) || !scene::hasRotationModel(site.body->name))
    return std::nullopt;
  const glm::dvec3 toEarth = scene::heliocentricPositionM("Earth", time) - scene::heliocentricPositionM(site.body->name, time);
  const glm::dvec3 bodyFixed = glm::transpose(scene::bodyFixedToInertial(site.body->name, time)) * glm::normalize(toEarth);
  terrain::SunDisc earth;
  earth.direction = inTangentFrame(site, bodyFixed);
  earth.angularRadiusRad = std::asin(std::min(1.0, scene::findPreset("Earth")->meanRadiusM / glm::length(toEarth)));
  return earth;
}

/// The body that can stand in front of the Sun seen from the site's (the Earth from the
/// Moon, the Moon from the Earth), on the Sun's disc as the grid's centre sees it; none
/// when it does not touch the disc.
std::optional<terrain::OccluderOnDisc> occluderOfSun(const Site& site, scene::UtcTime time, const terrain::SunDisc& sun) {
  const std::string& body = site.body->name;
  const char* other = body == "Moon" ? "Earth" : body == "Earth" ? "Moon" : nullptr;
  if (!other || !scene::hasRotationModel(body)) return std::nullopt;
  const glm::dvec3 towards = scene::heliocentricPositionM(other, time) - scene::heliocentricPositionM(body, time);
  const glm::dvec3 bodyFixed = glm::transpose(scene::bodyFixedToInertial(body, time)) * glm::normalize(towards);
  const double radiusRad = std::asin(std::min(1.0, scene::findPreset(other)->meanRadiusM / glm::length(towards)));
  const terrain::OccluderOnDisc o = terrain::occluderOnDisc(sun.direction, sun.angularRadiusRad, inTangentFrame(site, bodyFixed),
                                                            radiusRad, glm::dvec3(0.0, 0.0, 1.0));
  return terrain::overlaps(o) ? std::optional(o) : std::nullopt;
}

double elevationDegOf(const glm::dvec3& d) { return std::asin(std::clamp(glm::normalize(d).z, -1.0, 1.0)) / kDeg; }
double azimuthDegOf(const glm::dvec3& d) {
  const double a = std::atan2(d.x, d.y) / kDeg;
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

std::vector<Point> lightingPoints(const Options& o, const terrain::HeightField& f) {
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
LightingShare lightSteps(const Options& o, const Site& site, const std::vector<Point>& points,
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
      csv << timeLabel(times[k]) << ',' << p + 1 << ',' << q.i << ',' << q.j << ',' << fmt(elevationDegOf(sun.direction))
          << ',' << fmt(azimuthDegOf(sun.direction)) << ',' << fmt(eclipseFraction) << ',' << fmt(v);
      if (earth)
        csv << ',' << fmt(elevationDegOf(earth->direction)) << ','
            << fmt(terrain::visibleFraction(field, mip, q.i, q.j, *earth, terrain::ShadowOptions{}));
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
void writeLighting(const Options& o, const Site& site, const std::vector<Point>& points, std::size_t steps,
                   const terrain::LightingMaps& maps, const std::string& csvRows, const std::vector<double>& series) {
  const terrain::HeightField& field = site.dem.field;
  if (output::extensionOf(o.output) == ".vti") {
    writeLightingVti(o.output, field, maps);
  } else {
    writeLightingExr(o.output, maps,
                     {{"source", site.source}, {"method", o.method}, {"from", o.from}, {"to", o.to}, {"step", o.step},
                      {"steps", std::to_string(steps)}, {"body", site.body->name},
                      {"latDeg", fmt(site.latDeg)}, {"lonDeg", fmt(site.lonDeg)}, {"spacingM", fmt(field.spacingM)},
                      {"bodyRadiusM", fmt(field.bodyRadiusM)}, {"totalS", fmt(maps.totalS)}});
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

int runLighting(const Options& o) {
  const auto start = std::chrono::steady_clock::now();
  output::checkWritable(o.output, {".exr", ".vti"});
  if (!o.csv.empty()) output::checkWritable(o.csv, {".csv"});
  if (!o.plot.empty()) output::checkWritable(o.plot, {".png", ".svg"});
  if (o.method != "sweep" && o.method != "dp") throw CommandError("--method: expected sweep or dp, got '" + o.method + "'");
  const std::vector<scene::UtcTime> times = timeSteps(o.from, o.to, o.step);
  const Site site = loadSite(o);
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

namespace {
/// The options that name the terrain (loadSite) and the check of them run before the
/// command: --dem or --synthetic, --size, --spacing, --body, --body-radius, --lat-deg, --lon-deg.
std::function<void()> addSiteOptions(CLI::App* command, Options& o, const std::string& centreFor) {
  auto* dem = command->add_option("--dem", o.dem, "DEM raster (GeoTIFF or any GDAL raster; heights in m, projected CRS)");
  auto* synthetic = command->add_option("--synthetic", o.seed, "Synthetic crater field with this seed (>= 0)");
  dem->excludes(synthetic);
  command->add_option("--size", o.size, "Synthetic field: samples per side")->capture_default_str()->check(CLI::Range(2, 8192));
  command->add_option("--spacing", o.spacing, "Sample spacing (synthetic field, or a DEM without georeferencing)")
      ->capture_default_str();
  command->add_option("--body", o.body, "Body (radius; ephemeris and rotation for the Sun's times)")->capture_default_str();
  command->add_option("--body-radius", o.bodyRadius, "Override the body radius (units m, km)");
  command->add_option("--lat-deg", o.latitudeDeg, "Latitude of the DEM centre" + centreFor + " (default: georeferencing, else -90)");
  command->add_option("--lon-deg", o.longitudeDeg, "Longitude of the DEM centre" + centreFor + " (default: georeferencing, else 0)");
  return [&o, dem, synthetic] {
    if (dem->count() == 0 && synthetic->count() == 0) throw CommandError("give --dem FILE or --synthetic SEED");
    if (synthetic->count() && o.seed < 0) throw CommandError("--synthetic: expected a seed >= 0");
  };
}

void addLightingCommand(CLI::App* terrainCmd, Action& action) {
  CLI::App* lighting = terrainCmd->add_subcommand(
      "lighting",
      "Lighting over time at every sample of a DEM: the fraction of the time lit, the longest continuous shadow "
      "and the mean visible fraction of the solar disc (maps), and at chosen points the Sun's and the Earth's "
      "visibility at each step (CSV)");
  auto o = std::make_shared<Options>();
  o->method = "sweep";
  const auto checkSite = addSiteOptions(lighting, *o, "");
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
} // namespace

void addTerrainCommand(CLI::App& app, Action& action) {
  CLI::App* terrainCmd = app.add_subcommand("terrain", "Terrain: soft horizon shadows of the Sun on a DEM");
  terrainCmd->require_subcommand(1);
  CLI::App* shadow = terrainCmd->add_subcommand(
      "shadow", "Visible fraction of the solar disc (0 = umbra, 1 = fully lit) at every sample of a DEM");
  auto o = std::make_shared<Options>();
  const auto checkSite = addSiteOptions(shadow, *o, " for --time");
  shadow->add_option("--sun-elevation-deg", o->elevationDeg, "Sun elevation at the DEM centre [deg]");
  shadow->add_option("--sun-azimuth-deg", o->azimuthDeg, "Sun azimuth at the DEM centre, from north (+y) to east (+x) [deg]");
  shadow->add_option("--time", o->time, "UTC instant (ISO 8601): the Sun from the ephemeris and the body's rotation");
  shadow->add_option("--method", o->method, "dp (maximum mipmap, Algorithm 1), uniform or reference")->capture_default_str();
  shadow->add_option("--levels", o->levels, "DP: mip levels N' per concatenated interval")->capture_default_str()->check(CLI::Range(1, 30));
  shadow->add_option("--uniform-steps", o->uniformSteps, "uniform: steps along each shadow ray")->capture_default_str()->check(CLI::Range(1, 1 << 20));
  shadow->add_option("--limb-darkening", o->limbDarkening, "Linear limb darkening of the disc (0: uniform)")->capture_default_str()->check(CLI::Range(0.0, 1.0));
  shadow->add_option("--output", o->output, "Output: .exr (float), .png (16-bit linear gray), .vti (heights + fraction)")->required();
  addLightingCommand(terrainCmd, action);
  shadow->callback([&action, o, checkSite] {
    action = [o, checkSite] {
      checkSite();
      return runShadow(*o);
    };
  });
}

} // namespace umbra::cli
