// umbra sweep SWEEP.json --csv FILE.csv [--plot FILE.svg|FILE.png] [--cache-dir DIR | --no-cache]
//   a parameter study of an eclipse through an atmosphere: each case (a grid of values or a
//   list) changes fields of the atmosphere file, the distance behind the occluder or the
//   occluder's distance from the Sun; per case the light in the shadow is computed directly
//   (no LuT) and one CSV row written. Under mpirun the cases are shared by the ranks.
//   The file's format: docs/eclipse-shadows.md, "Parameter sweeps".
#include "Commands.hpp"
#include "OutputFile.hpp"
#include "ProfileExport.hpp"
#include "Ranks.hpp"
#include "ShadowCommon.hpp"
#include "vtkEclipseShadowLutSource.h"

#include "Atmosphere.hpp"
#include "AtmosphericShadow.hpp"
#include "EclipseAtmosphere.hpp"

#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkTable.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

namespace umbra::cli {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

/// The keys of a case that are not atmosphere fields.
constexpr const char* kDistanceKey = "distance";        ///< behind the occluder's centre
constexpr const char* kSunDistanceKey = "sunDistance";  ///< of the occluder from the Sun

struct Sweep {
  std::string path, description, occluder = "earth", atmosphere = "earth";
  std::string distance = "384400km", sunDistance;  ///< texts with units; sunDistance empty: the body's mean
  std::vector<double> offsetsKm;
  EclipseAtmosphereChoice quality;
  std::vector<std::string> keys;          ///< what varies, in order
  std::vector<std::vector<Json>> cases;   ///< each: one value per key
};

/// "SWEEP.json: FIELD: why".
[[noreturn]] void sweepError(const Sweep& s, const std::string& field, const std::string& why) {
  throw CommandError(s.path + ": " + field + ": " + why);
}

std::string valueText(const Json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

/// The JSON pointer of an atmosphere field key: "/a/b" as it is, "a" as "/a".
Json::json_pointer fieldPointer(const std::string& key) { return Json::json_pointer(key[0] == '/' ? key : "/" + key); }

Sweep readSweep(const std::string& path) {
  Sweep s;
  s.path = path;
  std::ifstream in(path);
  if (!in) throw CommandError(path + ": cannot read");
  Json j;
  try {
    j = Json::parse(in, nullptr, true, /*ignore_comments=*/true);
  } catch (const std::exception& e) {
    throw CommandError(path + ": not JSON: " + e.what());
  }
  if (!j.is_object()) throw CommandError(path + ": expected an object");
  const auto text = [&](const char* key, std::string& out) {
    if (!j.contains(key)) return;
    if (!j[key].is_string() || j[key].get<std::string>().empty()) sweepError(s, key, "expected a non-empty string");
    out = j[key].get<std::string>();
  };
  const auto count = [&](const char* key, int& out, int lo, int hi) {
    if (!j.contains(key)) return;
    if (!j[key].is_number_integer() || j[key].get<long long>() < lo || j[key].get<long long>() > hi)
      sweepError(s, key, "expected an integer in " + std::to_string(lo) + ".." + std::to_string(hi));
    out = j[key].get<int>();
  };
  static const std::vector<std::string> known = {"description", "occluder", "atmosphere", "distance", "sunDistance",
                                                 "offsetsKm", "tables", "orders", "limbSize", "scatteringCells",
                                                 "grid", "cases"};
  for (const auto& [key, value] : j.items())
    if (std::find(known.begin(), known.end(), key) == known.end()) sweepError(s, key, "unknown key");
  text("description", s.description);
  text("occluder", s.occluder);
  text("atmosphere", s.atmosphere);
  text("distance", s.distance);
  text("sunDistance", s.sunDistance);
  s.quality.limbSize = 64;
  count("orders", s.quality.orders, 1, 64);
  count("limbSize", s.quality.limbSize, 4, 4096);
  count("scatteringCells", s.quality.scatteringCells, 1, 1024);
  if (j.contains("tables")) {
    if (j["tables"] != "draft" && j["tables"] != "default") sweepError(s, "tables", "expected \"draft\" or \"default\"");
    s.quality.draftTables = j["tables"] == "draft";
  }
  if (j.contains("offsetsKm")) {
    if (!j["offsetsKm"].is_array()) sweepError(s, "offsetsKm", "expected a list of offsets in km");
    for (const Json& v : j["offsetsKm"]) {
      if (!v.is_number() || !(v.get<double>() >= 0.0) || !std::isfinite(v.get<double>()))
        sweepError(s, "offsetsKm", "expected offsets >= 0 km, got " + v.dump());
      s.offsetsKm.push_back(v.get<double>());
    }
  }
  if (j.contains("grid") == j.contains("cases")) throw CommandError(path + ": give either \"grid\" or \"cases\"");
  if (j.contains("grid")) {
    // Every combination, the first key outermost.
    if (!j["grid"].is_object() || j["grid"].empty()) sweepError(s, "grid", "expected an object of value lists");
    s.cases = {{}};
    for (const auto& [key, values] : j["grid"].items()) {
      if (!values.is_array() || values.empty()) sweepError(s, "grid." + key, "expected a non-empty list of values");
      s.keys.push_back(key);
      std::vector<std::vector<Json>> next;
      for (const std::vector<Json>& c : s.cases)
        for (const Json& v : values) {
          next.push_back(c);
          next.back().push_back(v);
        }
      s.cases = std::move(next);
      if (s.cases.size() > 100000) sweepError(s, "grid", "more than 100000 cases");
    }
  } else {
    if (!j["cases"].is_array() || j["cases"].empty()) sweepError(s, "cases", "expected a non-empty list of objects");
    for (std::size_t k = 0; k < j["cases"].size(); ++k) {
      const Json& c = j["cases"][k];
      const std::string where = "cases[" + std::to_string(k) + "]";
      if (!c.is_object() || c.empty()) sweepError(s, where, "expected an object of values");
      if (k == 0)
        for (const auto& [key, v] : c.items()) s.keys.push_back(key);
      std::vector<Json> values;
      for (const std::string& key : s.keys) {
        if (!c.contains(key)) sweepError(s, where, "no \"" + key + "\" (every case gives the same keys)");
        values.push_back(c[key]);
      }
      if (c.size() != s.keys.size()) sweepError(s, where, "other keys than cases[0]'s");
      s.cases.push_back(std::move(values));
    }
  }
  for (const std::string& key : s.keys) {
    if (key.empty()) sweepError(s, "grid", "an empty key");
    try {
      fieldPointer(key);
    } catch (const std::exception&) {
      sweepError(s, key, "not a field name or a JSON pointer");
    }
  }
  return s;
}

/// A case's figures, in the CSV's order after the case's values.
std::vector<std::string> figureColumns(const Sweep& s) {
  std::vector<std::string> c = {"centre_r",           "centre_g",           "centre_b", "centre_luminance",
                                "centre_delta_v_mag", "umbra_radius_km", "penumbra_radius_km"};
  for (double km : s.offsetsKm) {
    char name[64];
    std::snprintf(name, sizeof name, "luminance_at_%gkm", km);
    c.push_back(name);
  }
  return c;
}

/// The atmosphere document of case `k` (the base with the case's fields set) and its
/// distances.
struct CaseSetup {
  Json atmosphere;
  std::string distance, sunDistance;
};

CaseSetup setUpCase(const Sweep& s, const Json& base, std::size_t k) {
  CaseSetup c{base, s.distance, s.sunDistance};
  for (std::size_t q = 0; q < s.keys.size(); ++q) {
    const std::string& key = s.keys[q];
    const Json& v = s.cases[k][q];
    if (key == kDistanceKey || key == kSunDistanceKey) {
      if (!v.is_string()) sweepError(s, key, "expected a length with its unit (e.g. \"384400km\"), got " + v.dump());
      (key == kDistanceKey ? c.distance : c.sunDistance) = v.get<std::string>();
      continue;
    }
    const Json::json_pointer p = fieldPointer(key);
    if (!c.atmosphere.contains(p.parent_pointer()) || !c.atmosphere[p.parent_pointer()].is_object())
      sweepError(s, key, "no such object in the atmosphere " + s.atmosphere + " (" + p.parent_pointer().to_string() +
                             ")");
    c.atmosphere[p] = v;
  }
  return c;
}

/// The figures of case `k` (its atmosphere file written into `dir`).
std::vector<double> computeCase(const Sweep& s, const Json& base, std::size_t k, const fs::path& dir,
                                const CacheOptions& cache) {
  const CaseSetup c = setUpCase(s, base, k);
  const fs::path file = dir / ("case-" + std::to_string(k) + ".json");
  {
    std::ofstream out(file);
    out << c.atmosphere.dump(2);
    if (!out.flush()) throw std::runtime_error(file.string() + ": cannot write");
  }
  EclipseAtmosphereChoice choice = s.quality;
  choice.atmosphere = file.string();
  OccluderChoice occ = chooseOccluder(s.occluder, "", c.sunDistance);
  occ.radiusM = choice.bottomRadiusM();
  const double distanceM = lengthOption("distance", c.distance, occ.radiusM, kMaxDistanceM);
  auto source = vtkSmartPointer<vtkEclipseShadowLutSource>::New();
  choice.configure(source, occ);
  source->SetCacheDirectory(cache.directory.c_str());
  source->SetUseCache(!cache.disabled);
  source->ConnectAtmosphereTables();  // the tables through the cache
  const std::shared_ptr<const eclipse::EclipseAtmosphere> prepared = source->GetPreparedAtmosphere();
  eclipse::AtmosphericShadowModel model = prepared->model;
  model.limbDarkening = eclipse::kDefaultLimbDarkening;
  const eclipse::LimbViewParams limb{choice.limbSize, choice.limbSize, choice.scatteringCells, choice.scatteringCells};
  const eclipse::ProfileSample centre = eclipse::atmosphericShadowAt(model, distanceM, 0.0, limb);
  const eclipse::ShadowConeRadii radii = eclipse::shadowConeRadii(model.system, distanceM);
  std::vector<double> row = {centre.rgb.r, centre.rgb.g, centre.rgb.b, centre.luminance,
                             -2.5 * std::log10(std::max(centre.luminance, 1e-300)),
                             std::max(radii.umbraRadiusM, radii.antumbraRadiusM) / 1e3, radii.penumbraRadiusM / 1e3};
  for (double km : s.offsetsKm) row.push_back(eclipse::atmosphericShadowAt(model, distanceM, km * 1e3, limb).luminance);
  for (double v : row)
    if (!std::isfinite(v)) throw std::runtime_error("a figure is not finite");
  return row;
}

/// A fresh directory for the cases' atmosphere files, removed with everything in it.
struct CaseDirectory {
  fs::path path;
  CaseDirectory() {
    std::string pattern = (fs::temp_directory_path() / "umbra-sweep-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw std::runtime_error("cannot make a temporary directory in " +
                                                            fs::temp_directory_path().string());
    path = pattern;
  }
  ~CaseDirectory() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

void writeCsv(const Sweep& s, const std::vector<std::vector<double>>& rows, const std::string& path) {
  output::OutputFile out(path);
  {
    std::ofstream f(out.tempPath());
    f << "case";
    for (const std::string& key : s.keys) f << "," << key;
    for (const std::string& c : figureColumns(s)) f << "," << c;
    f << "\n";
    char buf[64];
    for (std::size_t k = 0; k < rows.size(); ++k) {
      f << k;
      for (const Json& v : s.cases[k]) {
        std::string t = valueText(v);
        if (t.find_first_of(",\"\n") != std::string::npos) {  // quoted as CSV wants
          std::string q = "\"";
          for (char ch : t) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
          t = q + "\"";
        }
        f << "," << t;
      }
      for (double v : rows[k]) {
        std::snprintf(buf, sizeof buf, ",%.10g", v);
        f << buf;
      }
      f << "\n";
    }
    if (!f.flush()) throw std::runtime_error(path + ": cannot write");
  }
  out.commit();
}

/// The umbra's centre (r, g, b, luminance, log scale) against the first key when its values
/// are numbers, else against the case number; the Danjon scale beside.
void writePlot(const Sweep& s, const std::vector<std::vector<double>>& rows, const std::string& path) {
  bool numeric = true;
  for (const std::vector<Json>& c : s.cases) numeric = numeric && c.front().is_number();
  vtkNew<vtkTable> t;
  const char* names[] = {"x", "r", "g", "b", "luminance"};
  vtkNew<vtkDoubleArray> cols[5];
  for (int q = 0; q < 5; ++q) {
    cols[q]->SetName(names[q]);
    t->AddColumn(cols[q]);
  }
  // Sorted by x (a grid whose first key is not the innermost repeats it: each x once, the
  // first case with it).
  std::vector<std::pair<double, std::size_t>> order;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const double x = numeric ? s.cases[k].front().get<double>() : static_cast<double>(k);
    bool seen = false;
    for (const auto& o : order) seen = seen || o.first == x;
    if (!seen) order.emplace_back(x, k);
  }
  std::sort(order.begin(), order.end());
  for (const auto& [x, k] : order) {
    cols[0]->InsertNextValue(x);
    for (int q = 0; q < 4; ++q) cols[q + 1]->InsertNextValue(rows[k][q]);
  }
  plot::ProfilePlotStyle style;
  style.logScale = true;
  style.legendTop = true;  // the Moon darkens to the right: the top stays empty
  style.xColumn = "x";
  // Values over more than a decade, all positive: a log axis.
  style.xLogScale = numeric && order.front().first > 0.0 && order.back().first >= 20.0 * order.front().first;
  style.xLabel = numeric ? s.keys.front() : std::string("case");
  style.subtitle = "I / I_sun at the umbra's centre, " + s.distance + " behind " + s.occluder + "'s centre";
  style.notes = {"Danjon scale (L, judged by eye at mid-totality):",
                 "4  very bright, copper-red or orange; bluish, bright umbral rim",
                 "3  brick-red; bright or yellow umbral rim",
                 "2  deep red or rust; dark centre, brighter outer umbra",
                 "1  dark, grey or brownish; details hard to see",
                 "0  very dark; the Moon almost invisible"};
  plot::writeProfilePlot(t, path, s.description.empty() ? "umbra sweep " + s.path : s.description, style);
}

struct SweepOptions {
  std::string file, csv, plot;
  CacheOptions cache;
};

int runSweep(const SweepOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  output::checkWritable(o.csv, {".csv"});
  if (!o.plot.empty()) output::checkWritable(o.plot, {".png", ".svg"});
  const Sweep s = readSweep(o.file);
  Json base;
  try {
    base = Json::parse(atmosphere::resolvedAtmosphereJson(s.atmosphere), nullptr, true, true);
  } catch (const std::exception& e) {
    sweepError(s, "atmosphere", e.what());
  }
  for (std::size_t k = 0; k < s.cases.size(); ++k) setUpCase(s, base, k);  // every case's keys, before any work

  parallel::Ranks& ranks = parallel::Ranks::world();
  const auto [begin, end] = parallel::share(s.cases.size(), ranks.rank(), ranks.size());
  const std::size_t figures = figureColumns(s).size();
  std::vector<double> mine;  // this rank's rows, one after the other
  std::string error;
  {
    std::optional<ProgressLine> progress;
    if (ranks.root()) progress.emplace("sweep (" + std::to_string(s.cases.size()) + " cases)");
    try {
      const CaseDirectory dir;
      for (std::size_t k = begin; k < end; ++k) {
        try {
          const std::vector<double> row = computeCase(s, base, k, dir.path, o.cache);
          mine.insert(mine.end(), row.begin(), row.end());
        } catch (const std::exception& e) {
          std::string values;
          for (std::size_t q = 0; q < s.keys.size(); ++q)
            values += (q ? ", " : "") + s.keys[q] + " " + valueText(s.cases[k][q]);
          throw CommandError(s.path + ": case " + std::to_string(k) + " (" + values + "): " + e.what());
        }
        if (progress) progress->update(static_cast<double>(k + 1 - begin) / static_cast<double>(end - begin));
      }
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  if (const std::string errors = ranks.finish(error); !errors.empty()) throw CommandError(errors);
  const std::vector<double> all = ranks.gather(mine);
  if (!ranks.root()) return 0;
  std::vector<std::vector<double>> rows;
  for (std::size_t k = 0; k < s.cases.size(); ++k)
    rows.emplace_back(all.begin() + static_cast<std::ptrdiff_t>(k * figures),
                      all.begin() + static_cast<std::ptrdiff_t>((k + 1) * figures));
  writeCsv(s, rows, o.csv);
  std::cout << "wrote " << o.csv << " (" << s.cases.size() << " cases of " << o.file << ")" << ranksNote(start)
            << "\n";
  if (!o.plot.empty()) {
    writePlot(s, rows, o.plot);
    std::cout << "wrote " << o.plot << "\n";
  }
  return 0;
}

}  // namespace

void addSweepCommand(CLI::App& app, Action& action) {
  CLI::App* sweep = app.add_subcommand(
      "sweep", "A parameter study of an eclipse through an atmosphere: per case (atmosphere fields, distances) the "
               "light at the umbra's centre and at chosen offsets, one CSV row each; under mpirun the cases are "
               "shared by the ranks (docs/eclipse-shadows.md, \"Parameter sweeps\")");
  auto o = std::make_shared<SweepOptions>();
  sweep->add_option("file", o->file, "The sweep: a JSON file (examples/sweeps/)")->required();
  sweep->add_option("--csv", o->csv, "CSV file to write: one row per case")->required();
  sweep->add_option("--plot", o->plot,
                    "Plot to write (.svg, or .png): the umbra's centre against the first key, the Danjon scale beside");
  o->cache.addTo(sweep);
  sweep->callback([&action, o] { action = [o] { return runSweep(*o); }; });
}

}  // namespace umbra::cli
