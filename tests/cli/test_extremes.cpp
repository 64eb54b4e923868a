// The extremes sweep: every value option of every command, and every number in a scene file
// and an atmosphere file, at 0, -0, 1e-300, 1e308, -1e308, NaN, +-inf and the empty string
// (and, where the value holds several numbers, such as 80:90:5, 10km or a UTC time, each of
// them at those values in turn). Each run must either exit 0 with finite output (stdout and
// every CSV, text, SVG and EXR file it wrote) or exit non-zero with one error line on
// stderr, "umbra: error: ...", that names the option or field (before it at most umbra's
// notes on the tables it used), leaving no file behind; none may crash or run past its
// time limit.
//
// The options are read from the command line's own definition (app/cli), so a new option
// is swept without being listed here. By default a sample runs (two values per option or
// field, rotating through the list); UMBRA_EXTREMES=full runs every case
// (bench/extremes_sweep.sh).
#include "CliRunner.hpp"
#include "Commands.hpp"

#include "umbra/tables/Exr.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>

using namespace umbra::test;
namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kExtremes{"0", "-0", "1e-300", "1e308", "-1e308", "nan", "inf", "-inf", ""};
constexpr int kTimeLimitS = 120;

struct Tally {
  std::size_t runs = 0, succeeded = 0, refused = 0;
} tally;

/// Prints the tally once every test has run (bench/extremes_sweep.sh reports it).
class TallyPrinter : public testing::Environment {
  void TearDown() override {
    std::printf("extremes sweep: %zu runs, %zu exited 0 with finite output, %zu refused with one error line\n",
                tally.runs, tally.succeeded, tally.refused);
  }
};
const testing::Environment* const kTallyPrinter = testing::AddGlobalTestEnvironment(new TallyPrinter);

bool fullSweep() {
  const char* mode = std::getenv("UMBRA_EXTREMES");
  return mode && std::string(mode) == "full";
}

/// The values to try for an option or field whose usual value is `usual`: the extremes
/// alone, then each number inside `usual` replaced by each extreme (its unit or separators
/// kept).
std::vector<std::string> valuesFor(const std::string& usual) {
  std::vector<std::string> values = kExtremes;
  static const std::regex number(R"([-+]?[0-9]+(\.[0-9]+)?([eE][-+]?[0-9]+)?)");
  for (auto it = std::sregex_iterator(usual.begin(), usual.end(), number); it != std::sregex_iterator(); ++it) {
    if (it->position() == 0 && it->length() == static_cast<std::ptrdiff_t>(usual.size())) break;  // a bare number
    for (const std::string& e : kExtremes) {
      std::string v = usual;
      v.replace(static_cast<std::size_t>(it->position()), static_cast<std::size_t>(it->length()), e);
      values.push_back(v);
    }
  }
  std::set<std::string> seen;
  std::vector<std::string> unique;
  for (const std::string& v : values)
    if (seen.insert(v).second) unique.push_back(v);
  return unique;
}

/// Which of `count` cases of item number `item` run: all in a full sweep, else two.
std::vector<std::size_t> chosen(std::size_t item, std::size_t count) {
  std::vector<std::size_t> picks;
  if (fullSweep()) {
    for (std::size_t i = 0; i < count; ++i) picks.push_back(i);
    return picks;
  }
  picks.push_back(item % count);
  if (count > 1) picks.push_back((item * 5 + 3) % count == picks[0] ? (picks[0] + 1) % count : (item * 5 + 3) % count);
  return picks;
}

bool hasNonFiniteWord(const std::string& text) {
  static const std::regex word(R"((^|[^A-Za-z_])[-+]?(nan|inf|infinity)([^A-Za-z_]|$))", std::regex::icase);
  return std::regex_search(text, word);
}

/// What is wrong with the files a successful run wrote under `dir` ("" when nothing).
std::string nonFiniteOutput(const fs::path& dir) {
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    const fs::path& p = entry.path();
    const std::string ext = p.extension().string();
    if (ext == ".csv" || ext == ".txt" || ext == ".svg" || ext == ".json") {
      if (hasNonFiniteWord(readAll(p))) return p.string() + " holds a non-finite value";
    } else if (ext == ".exr") {
      try {
        const umbra::tables::Table t = umbra::tables::readExr(p.string());
        for (float v : t.data)
          if (!std::isfinite(v)) return p.string() + " holds a non-finite value";
      } catch (const std::exception& e) {
        return std::string("unreadable output: ") + e.what();
      }
    }
  }
  return "";
}

/// One run of umbra in its own directory `dir` (relative outputs land there; '@' in an
/// argument is replaced by it), with the time limit. Checks the rule; `names` are the
/// words of which the error line must hold one (the option's or field's names);
/// `fileName` is an output file's name given (it may read "nan").
void expectCleanOutcome(const std::vector<std::string>& argsIn, const std::vector<std::string>& names,
                        const fs::path& cache, const std::string& label, const std::string& fileName = "") {
  TempDir dir;
  std::vector<std::string> args;
  for (std::string a : argsIn) {
    for (std::size_t at; (at = a.find('@')) != std::string::npos;) a.replace(at, 1, dir.path.string());
    args.push_back(a);
  }
  const auto outPath = dir.path.parent_path() / (dir.path.filename().string() + ".out");
  const auto errPath = dir.path.parent_path() / (dir.path.filename().string() + ".err");
  std::string cmd = "cd " + quote(dir.path.string()) + " && UMBRA_CACHE_DIR=" + quote(cache.string()) +
                    " timeout -k 5 " + std::to_string(kTimeLimitS) + " " + quote(UMBRA_EXE);
  for (const std::string& a : args) cmd += " " + quote(a);
  cmd += " </dev/null >" + quote(outPath.string()) + " 2>" + quote(errPath.string());
  const int status = std::system(cmd.c_str());
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  const std::string out = readAll(outPath), err = readAll(errPath);
  fs::remove(outPath);
  fs::remove(errPath);
  std::string shown = "umbra";
  for (const std::string& a : args) shown += " " + quote(a);
  SCOPED_TRACE(label + ": " + shown + "\nstderr: " + err);
  ++tally.runs;
  ASSERT_NE(code, 124) << "ran past " << kTimeLimitS << " s";
  ASSERT_LT(code, 124) << "crashed (exit " << code << ")";
  if (code == 0) {
    std::string said = out;  // a file called "nan" may be named
    if (!fileName.empty())
      for (std::size_t at; (at = said.find(fileName)) != std::string::npos;) said.erase(at, fileName.size());
    EXPECT_FALSE(hasNonFiniteWord(said)) << "stdout holds a non-finite value: " << out;
    EXPECT_EQ(nonFiniteOutput(dir.path), "");
    ++tally.succeeded;
    return;
  }
  ++tally.refused;
  // One error line, the last; before it at most umbra's own notes on the tables it used.
  std::vector<std::string> lines;
  for (std::istringstream in(err); std::getline(in, lines.emplace_back());) {
  }
  lines.pop_back();
  ASSERT_FALSE(lines.empty()) << "no error line";
  EXPECT_EQ(lines.back().rfind("umbra: error: ", 0), 0u) << "the last line is not umbra's error line";
  for (std::size_t i = 0; i + 1 < lines.size(); ++i) {
    bool note = false;
    for (const char* prefix : {"cached: ", "cache hit: ", "atmosphere tables: ", "note: ", "umbra: note: ", "umbra: warning: ", "umbra: cache: "})
      note = note || lines[i].rfind(prefix, 0) == 0;
    EXPECT_TRUE(note) << "a line that is neither the error nor a note: " << lines[i];
  }
  bool named = false;
  for (const std::string& n : names) named = named || lines.back().find(n) != std::string::npos;
  EXPECT_TRUE(named) << "the error does not name " << names.front();
  EXPECT_EQ(dir.fileCount(), 0) << "a file was left behind";
}

/// A command as the sweep runs it: quick arguments that succeed, and the usual values of
/// options the base leaves out (swept around those).
struct Command {
  std::vector<std::string> path;  ///< e.g. {"atmosphere", "sky"}
  std::vector<std::string> base;
  std::map<std::string, std::string> usual;  ///< option -> a typical value
};

std::string sourcePath(const std::string& relative) { return std::string(UMBRA_SOURCE_DIR) + "/" + relative; }

const std::vector<Command>& commands() {
  static const std::string t = "2015-09-28T02:47:00Z";
  static const std::vector<Command> list{
      {{"render"},
       {sourcePath("examples/scenes/lunar-eclipse-2015-09-28.json"), "--size", "32x24", "-o", "@/r.png"},
       {{"--time", t}, {"--from", t}, {"--to", "2015-09-28T03:17:00Z"}, {"--step", "30min"},
        {"--exposure", "-5"}, {"--glare", "1"}}},
      {{"planets"}, {"--time", "2027-08-02T10:06:00Z", "--csv", "@/p.csv"}, {{"--observer", "25.6872,32.6396,80"}}},
      {{"moon"}, {"--time", "2026-10-26T04:00:00Z", "--observer", "18.47,-66.11,10"},
       {{"--from", "2026-10-01T00:00:00Z"}, {"--to", "2026-10-03T00:00:00Z"}, {"--step", "1d"}, {"--csv", "@/m.csv"}}},
      {{"precompute", "shadow"}, {"--occluder", "Earth", "--size", "16", "--no-cache", "-o", "@/s.exr"},
       {{"--distance-range", "350000km:400000km"}}},
      {{"precompute", "eclipse"},
       {"--occluder", "Earth", "--atmosphere", "earth", "--size", "16", "--limb-lut-size", "4", "--limb-size", "8",
        "--scattering-cells", "2", "--orders", "1", "--draft-tables", "-o", "@/e"},
       {{"--distance-range", "350000km:400000km"}, {"--scattering-nu", "8"}, {"--layers", "2"}}},
      {{"profile", "shadow"},
       {"--occluder", "Earth", "--distance", "384400km", "--samples", "21", "--size", "16", "--csv", "@/p.csv"},
       {{"--sun-distance", "1au"}, {"--occluder-radius", "6371km"}, {"--max-offset", "9000km"}, {"--plot", "@/p.svg"},
        {"--scene", sourcePath("examples/scenes/lunar-eclipse-2015-09-28.json")}, {"--time", t}}},
      {{"inspect"}, {"@/none.exr"}, {}},
      {{"atmosphere", "precompute"},
       {"--preset", "earth", "--orders", "1", "--transmittance-size", "16x8", "--scattering-size", "4,8,4,2",
        "--irradiance-size", "8x4", "--refraction-size", "16x8", "--no-cache", "--output", "@/a"},
       {{"--wavelengths", "3"}}},
      {{"atmosphere", "refraction"}, {"--preset", "earth", "--zenith-deg", "80:90:5", "--csv", "@/r.csv"},
       {{"--altitude", "100m"}, {"--step", "10km"}}},
      {{"atmosphere", "sky"},
       {"--preset", "earth", "--sun-zenith-deg", "60", "--zenith-step", "30", "--azimuth-step", "90", "--orders", "1",
        "--wavelengths", "3", "--csv", "@/s.csv"},
       {{"--lowest-sun-zenith-deg", "100"}, {"--density-directions", "8"}, {"--observer-altitude", "100m"},
        {"--plot-size", "32"}, {"--plot", "@/sky.png"}}},
      {{"terrain", "shadow"},
       {"--synthetic", "1", "--size", "16", "--sun-elevation-deg", "5", "--sun-azimuth-deg", "90", "--output", "@/t.exr"},
       {{"--time", t}, {"--dem", "@/dem.tif"}, {"--body-radius", "1737.4km"}, {"--lat-deg", "-89.5"}, {"--lon-deg", "10"}, {"--spacing", "30m"}}},
      {{"terrain", "lighting"},
       {"--synthetic", "1", "--size", "16", "--from", "2024-03-01T00:00:00Z", "--to", "2024-03-02T00:00:00Z", "--step",
        "6h", "--output", "@/l.exr"},
       {{"--dem", "@/dem.tif"}, {"--body-radius", "1737.4km"}, {"--lat-deg", "-89.5"}, {"--lon-deg", "10"},
        {"--spacing", "30m"}, {"--method", "dp"}, {"--point", "3,4"}, {"--csv", "@/l.csv"}, {"--plot", "@/l.svg"}}},
      {{"sweep"}, {sourcePath("examples/sweeps/moon-in-totality-quick.json"), "--csv", "@/s.csv"},
       {{"--plot", "@/s.svg"}}},
      {{"atmosphere", "eclipse-sky"},
       {"--preset", "earth-bruneton", "--time", "2017-08-21T18:25:30Z", "--observer", "36.97,-87.67", "--paths", "20",
        "--step-deg", "30", "--csv", "@/e.csv"},
       {{"--wavelengths", "3"}, {"--seed", "1"}, {"--plot-vertical", "@/v.svg"}, {"--plot-almucantar", "@/a.svg"},
        {"--method", "fast"}}},
      {{"eclipses"}, {"--from", "2017-08-20", "--to", "2017-08-22", "--kind", "solar", "--csv", "@/e.csv"},
       {{"--delta-t", "70.3"}, {"--lunar-shadow", "chauvenet"}}},
      {{"eclipse", "local"}, {"--date", "2017-08-21", "--observer", "36.97,-87.67", "--csv", "@/l.csv"},
       {{"--delta-t", "70.3"}}},
      {{"eclipse", "path"}, {"--date", "2017-08-21", "--step", "900", "--geojson", "@/p.geojson"},
       {{"--png", "@/p.png"}, {"--delta-t", "70.3"}}},
      {{"eclipse", "brightness"},
       {"--date", "2018-07-27", "--atmosphere", "earth", "--draft-tables", "--orders", "1", "--limb-size", "16",
        "--scattering-cells", "2", "--samples", "64", "--csv", "@/b.csv"},
       {{"--delta-t", "70.8"}, {"--scattering-nu", "8"}}},
  };
  return list;
}

const CLI::App* leaf(const CLI::App& app, const std::vector<std::string>& path) {
  const CLI::App* at = &app;
  for (const std::string& name : path) at = at->get_subcommand(name);
  return at;
}

/// `base` with option `names` (and its value) taken out and `option value` added, or the
/// positional argument (the first one that is not an option's) replaced.
std::vector<std::string> withValue(const std::vector<std::string>& base, const CLI::Option& option,
                                   const std::string& value) {
  std::vector<std::string> args;
  if (option.get_positional() && !option.nonpositional()) {
    bool replaced = false;
    for (std::size_t i = 0; i < base.size(); ++i) {
      const bool isOption = base[i].rfind("-", 0) == 0;
      if (!replaced && !isOption && (i == 0 || base[i - 1].rfind("-", 0) != 0)) {
        args.push_back(value);
        replaced = true;
      } else {
        args.push_back(base[i]);
      }
    }
    return args;
  }
  for (std::size_t i = 0; i < base.size(); ++i) {
    if (option.check_name(base[i])) {
      ++i;  // its value too
      continue;
    }
    args.push_back(base[i]);
  }
  args.push_back(option.get_lnames().empty() ? "-" + option.get_snames().front() : "--" + option.get_lnames().front());
  args.push_back(value);
  return args;
}

void sweepCommand(const Command& command) {
  CLI::App app;
  umbra::cli::Action action;
  umbra::cli::addCommands(app, action);
  const CLI::App* sub = leaf(app, command.path);
  TempDir cache;
  std::size_t item = 0;
  for (const CLI::Option* option : sub->get_options()) {
    if (option->get_expected_max() == 0) continue;  // a flag
    std::string usual = option->get_default_str();
    for (std::size_t i = 0; i + 1 < command.base.size(); ++i)
      if (option->check_name(command.base[i])) usual = command.base[i + 1];
    if (option->get_positional() && !option->nonpositional()) usual = command.base.front();
    if (auto it = command.usual.find(option->get_lnames().empty() ? "" : "--" + option->get_lnames().front());
        it != command.usual.end())
      usual = it->second;
    std::vector<std::string> names;
    for (const std::string& n : option->get_lnames()) names.push_back(n);
    if (names.empty()) names.push_back(option->get_name());
    const std::vector<std::string> values = valuesFor(usual);
    for (std::size_t pick : chosen(item++, values.size())) {
      std::vector<std::string> args = command.path;
      const std::vector<std::string> rest = withValue(command.base, *option, values[pick]);
      args.insert(args.end(), rest.begin(), rest.end());
      // A file's name may stand for the option in the error ("nan: unsupported file type").
      const bool file = usual.find('/') != std::string::npos;
      std::vector<std::string> accepted = names;
      if (file && !values[pick].empty()) accepted.push_back(values[pick]);
      expectCleanOutcome(args, accepted, cache.path, names.front() + " = '" + values[pick] + "'",
                         file ? values[pick] : "");
    }
  }
}

/// Every number in `doc` (and every number inside a string, such as "1737.4km") at the
/// extremes: JSON numbers as 0, -0, 1e-300, +-1e308, 1e999 (an overflow), null and "";
/// `run` gets the file and the key that must be named.
void sweepJson(const nlohmann::json& doc, const std::string& fileName,
               const std::function<std::vector<std::string>(const std::string& file)>& argsFor) {
  const nlohmann::json flat = doc.flatten();
  TempDir files, cache;
  std::size_t item = 0;
  for (const auto& [pointer, value] : flat.items()) {
    std::vector<std::string> raw;  // JSON text of each replacement
    if (value.is_number()) {
      raw = {"0", "-0.0", "1e-300", "1e308", "-1e308", "1e999", "null", "\"\""};
    } else if (value.is_string()) {
      const std::string s = value.get<std::string>();
      if (s.find_first_of("0123456789") == std::string::npos) continue;
      for (const std::string& v : valuesFor(s))
        if (v != s) raw.push_back(nlohmann::json(v).dump());
    } else {
      continue;
    }
    // The key that names the field: the last part of the path that is not an array index.
    std::string key = pointer;
    while (!key.empty()) {
      const std::string last = key.substr(key.rfind('/') + 1);
      if (last.find_first_not_of("0123456789") != std::string::npos) {
        key = last;
        break;
      }
      key = key.substr(0, key.rfind('/'));
    }
    // Arrays of many numbers (an ozone cross-section): their first two elements in a sample.
    const std::string index = pointer.substr(pointer.rfind('/') + 1);
    if (!fullSweep() && index.find_first_not_of("0123456789") == std::string::npos && std::stoi(index) > 1) continue;
    for (std::size_t pick : chosen(item++, raw.size())) {
      nlohmann::json edited = flat;
      edited[pointer] = "@@value@@";
      std::string text = edited.unflatten().dump(1);
      text.replace(text.find("\"@@value@@\""), 11, raw[pick]);
      const std::string file = files / fileName;
      std::ofstream(file) << text;
      expectCleanOutcome(argsFor(file), {key, fileName}, cache.path, pointer + " = " + raw[pick]);
    }
  }
}

nlohmann::json readJson(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in, nullptr, true, true);
}

// `umbra render` of `scene` written as dir/name.json, with small tables, to dir/name.exr.
RunResult renderSceneIn(const TempDir& dir, const nlohmann::json& scene, const std::string& name) {
  std::ofstream(dir.path / (name + ".json")) << scene.dump();
  return run(UMBRA_EXE, {"render", (dir.path / (name + ".json")).string(), "--atmosphere-tables", "small", "-o",
                         (dir.path / (name + ".exr")).string()});
}

// Every pixel of dir/name.exr is finite.
void expectFiniteExr(const TempDir& dir, const std::string& name) {
  const umbra::tables::Table t = umbra::tables::readExr((dir.path / (name + ".exr")).string(), {"R", "G", "B"});
  for (float v : t.data) ASSERT_TRUE(std::isfinite(v)) << name;
}

}  // namespace

/// The command of the sweep at `path` (e.g. {"atmosphere", "sky"}).
const Command& command(const std::vector<std::string>& path) {
  for (const Command& c : commands())
    if (c.path == path) return c;
  throw std::invalid_argument("no command " + path.front() + " in the sweep");
}

TEST(Extremes, Render) { sweepCommand(command({"render"})); }
TEST(Extremes, Planets) { sweepCommand(command({"planets"})); }
TEST(Extremes, Moon) { sweepCommand(command({"moon"})); }
TEST(Extremes, PrecomputeShadow) { sweepCommand(command({"precompute", "shadow"})); }
TEST(Extremes, PrecomputeEclipse) { sweepCommand(command({"precompute", "eclipse"})); }
TEST(Extremes, ProfileShadow) { sweepCommand(command({"profile", "shadow"})); }
TEST(Extremes, Inspect) { sweepCommand(command({"inspect"})); }
TEST(Extremes, AtmospherePrecompute) { sweepCommand(command({"atmosphere", "precompute"})); }
TEST(Extremes, AtmosphereRefraction) { sweepCommand(command({"atmosphere", "refraction"})); }
TEST(Extremes, AtmosphereSky) { sweepCommand(command({"atmosphere", "sky"})); }
TEST(Extremes, TerrainShadow) { sweepCommand(command({"terrain", "shadow"})); }
TEST(Extremes, TerrainLighting) { sweepCommand(command({"terrain", "lighting"})); }
TEST(Extremes, Sweep) { sweepCommand(command({"sweep"})); }
TEST(Extremes, AtmosphereEclipseSky) { sweepCommand(command({"atmosphere", "eclipse-sky"})); }
TEST(Extremes, Eclipses) { sweepCommand(command({"eclipses"})); }
TEST(Extremes, EclipseLocal) { sweepCommand(command({"eclipse", "local"})); }
TEST(Extremes, EclipsePath) { sweepCommand(command({"eclipse", "path"})); }
TEST(Extremes, EclipseBrightness) { sweepCommand(command({"eclipse", "brightness"})); }

// Every number of a sweep file at the extremes.
TEST(Extremes, SweepFields) {
  sweepJson(readJson(sourcePath("examples/sweeps/moon-in-totality-quick.json")), "sweep.json",
            [](const std::string& file) { return std::vector<std::string>{"sweep", file, "--csv", "@/s.csv"}; });
}

// Every command of the CLI is in the sweep.
TEST(Extremes, EveryCommandSwept) {
  CLI::App app;
  umbra::cli::Action action;
  umbra::cli::addCommands(app, action);
  std::set<std::vector<std::string>> swept;
  for (const Command& c : commands()) swept.insert(c.path);
  std::function<void(const CLI::App*, std::vector<std::string>)> visit = [&](const CLI::App* a,
                                                                             std::vector<std::string> path) {
    const auto subs = a->get_subcommands([](const CLI::App*) { return true; });
    if (subs.empty()) {
      EXPECT_TRUE(swept.count(path)) << "not swept: umbra " << path.front();
      return;
    }
    for (const CLI::App* s : subs) {
      std::vector<std::string> p = path;
      p.push_back(s->get_name());
      visit(s, p);
    }
  };
  visit(&app, {});
}

// A scene with every kind of field: observer camera, a body with explicit radius, albedo,
// colour and photometry, and a terrain patch; small image and LuT.
TEST(Extremes, SceneFields) {
  const nlohmann::json scene = nlohmann::json::parse(R"({
    "name": "extremes", "time": "2015-09-28T02:47:00Z",
    "bodies": [{"preset": "Sun"}, {"preset": "Earth"},
               {"preset": "Moon", "radius": "1737.4km", "albedo": 0.12, "color": [0.92, 0.79, 0.64],
                "photometry": "hapke", "albedoMap": "none", "relief": 1.0,
                "terrain": {"seed": 1, "size": 16, "spacing": "30m", "latDeg": -10, "lonDeg": 10}}],
    "camera": {"observer": {"body": "Earth", "latDeg": 1.33, "lonDeg": -29.02, "altM": 10},
               "target": "Moon", "fovDeg": 0.71},
    "stars": {"limitingMagnitude": 4.0},
    "exposure": -5, "image": {"width": 32, "height": 24}, "shadow": {"lutSize": 16}})");
  sweepJson(scene, "scene.json", [](const std::string& file) {
    return std::vector<std::string>{"render", file, "-o", "@/r.png"};
  });
}

// Stars at the extremes of place and time: an observer at the pole looking at the horizon,
// a camera 2 au from the Sun, a date 2000 years on (proper motion applied; a note that the
// ephemeris's years are left), each rendered with finite output; a catalogue with a bad row
// refused with the file, the line and the column, and no image left behind.
TEST(Extremes, StarScenes) {
  TempDir dir;
  nlohmann::json base = nlohmann::json::parse(R"({
    "time": "2024-01-15T21:30:00Z",
    "bodies": [{"preset": "Sun"}, {"preset": "Earth", "atmosphere": "earth"}],
    "camera": {"observer": {"body": "Earth", "latDeg": 90, "lonDeg": 0, "altM": 2},
               "target": {"azimuthDeg": 0, "elevationDeg": 0}, "up": "zenith", "fovDeg": 60},
    "stars": {"catalogue": "few.dat", "limitingMagnitude": 9},
    "exposure": 8, "image": {"width": 32, "height": 24}, "shadow": {"lutSize": 16}})");
  std::ofstream(dir.path / "few.dat")
      << "064508.92 -164258.0 -000546.0-001223.100379.2 -1.4400.01A0 1            , alp CMa, Sirius\n"
         "023149.09 +891550.8 +000044.2-000011.700007.6 01.9700.64F7 0 0.04   3.97, alp UMi, Polaris\n"
         "183656.34 +384701.3 +000201.0+000287.500128.9 00.03-0.00A0 0            , alp Lyr, Vega\n";
  std::ofstream(dir.path / "bad.dat")
      << "064508.92 -164258.0 -000546.0-001223.100379.2 -1.4400.01A0 1            , alp CMa, Sirius\n"
         "183656.34 +38470X.3 +000201.0\n";
  auto render = [&](const nlohmann::json& scene, const std::string& name) { return renderSceneIn(dir, scene, name); };
  auto expectFinite = [&](const std::string& name) { expectFiniteExr(dir, name); };

  RunResult r = render(base, "pole");
  EXPECT_EQ(r.exitCode, 0) << r.err;
  expectFinite("pole");

  nlohmann::json far = base;
  far["bodies"][1].erase("atmosphere");
  far["camera"] = {{"position", {0, 3.0e11, 1.5e11}}, {"target", {0, 3.0e11, 0}}, {"fovDeg", 60}};
  r = render(far, "far");
  EXPECT_EQ(r.exitCode, 0) << r.err;
  expectFinite("far");

  nlohmann::json future = base;
  future["time"] = "4024-01-15T21:30:00Z";
  r = render(future, "future");
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("outside 1900-2100"), std::string::npos) << r.err;
  expectFinite("future");

  nlohmann::json bad = base;
  bad["stars"]["catalogue"] = "bad.dat";
  r = render(bad, "bad");
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("bad.dat:2: "), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path / "bad.exr"));
}

// Cloud layers at the extremes through the CLI: at 0 m and above the atmosphere's top,
// coverage 0 and 1, optical depth 0 and 1000, four layers at once, seen from the ground by
// day and by night and from space (there over the Blue Marble colour map when marble-qt-data
// has it): each renders finite pixels. Bad layers are refused naming the field, and no file
// is left.
TEST(Extremes, CloudScenes) {
  TempDir dir;
  nlohmann::json base = nlohmann::json::parse(R"({
    "time": "2024-01-15T12:00:00Z",
    "bodies": [{"preset": "Sun"}, {"preset": "Earth", "atmosphere": "earth", "clouds": []}, {"preset": "Moon"}],
    "camera": {"observer": {"body": "Earth", "latDeg": 10, "lonDeg": 0, "altM": 2},
               "target": {"azimuthDeg": 180, "elevationDeg": 20}, "up": "zenith", "fovDeg": 120},
    "stars": false, "exposure": -8, "image": {"width": 32, "height": 24}, "shadow": {"lutSize": 16}})");
  auto render = [&](const nlohmann::json& scene, const std::string& name) { return renderSceneIn(dir, scene, name); };
  auto expectFinite = [&](const std::string& name) { expectFiniteExr(dir, name); };
  const nlohmann::json all = nlohmann::json::array(
      {{{"altitude", 0}, {"coverage", 1}, {"opticalDepth", 1000}},
       {{"altitude", "200 km"}, {"coverage", 0.5}, {"opticalDepth", 3}, {"seed", 2}},
       {{"altitude", "1 km"}, {"coverage", 0}, {"opticalDepth", 0}},
       {{"altitude", "5 km"}, {"coverage", 0.5}, {"opticalDepth", 1000}, {"featureSize", "1 km"}, {"wind", {1000, -1000}}}});
  int n = 0;
  for (const char* time : {"2024-01-15T12:00:00Z", "2024-01-15T23:00:00Z"}) {
    for (const nlohmann::json& layers : {all, nlohmann::json::array({all[0]}), nlohmann::json::array({all[1]})}) {
      for (double altM : {2.0, 4.0e7}) {
        nlohmann::json scene = base;
        scene["time"] = time;
        scene["bodies"][1]["clouds"] = layers;
        scene["camera"]["observer"]["altM"] = altM;
        if (altM > 1e6) scene["camera"]["target"] = "Earth";
        if (altM > 1e6 && fs::exists("/usr/share/marble/data/maps/earth/bluemarble/bluemarble.jpg"))
          scene["bodies"][1]["albedoMap"] = "bluemarble";
        const std::string name = "clouds" + std::to_string(n++);
        const RunResult r = render(scene, name);
        EXPECT_EQ(r.exitCode, 0) << name << ": " << r.err;
        expectFinite(name);
      }
    }
  }
  nlohmann::json bad = base;
  bad["bodies"][1]["clouds"] = {{{"opticalDepth", -1}}};
  RunResult r = render(bad, "bad");
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("bodies[1].clouds[0].opticalDepth"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path / "bad.exr"));
  bad["bodies"][1]["clouds"] = nlohmann::json::array({all[0], all[0], all[0], all[0], all[0]});
  r = render(bad, "five");
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("at most 4 layers"), std::string::npos) << r.err;
  bad = base;
  bad["bodies"][1].erase("atmosphere");
  bad["bodies"][1]["clouds"] = {{{"coverage", 0.5}}};
  r = render(bad, "noair");
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("give the body \"atmosphere\""), std::string::npos) << r.err;
}

// A scene of fixed positions (Phobos in Mars' shadow): positions, the up vector.
TEST(Extremes, FixedSceneFields) {
  nlohmann::json scene = readJson(sourcePath("examples/scenes/phobos-in-mars-shadow.json"));
  scene["image"] = {{"width", 32}, {"height", 24}};
  scene["shadow"] = {{"lutSize", 16}};
  sweepJson(scene, "scene.json", [](const std::string& file) {
    return std::vector<std::string>{"render", file, "-o", "@/r.png"};
  });
}

// The Earth's atmosphere file, through the sky (every component's optics and profiles).
TEST(Extremes, AtmosphereFields) {
  const nlohmann::json atmosphere = readJson(sourcePath("atmosphere/presets/earth.json"));
  sweepJson(atmosphere, "atmosphere.json", [](const std::string& file) {
    return std::vector<std::string>{"atmosphere", "sky", "--config", file, "--sun-zenith-deg", "60", "--zenith-step",
                                    "30", "--azimuth-step", "90", "--orders", "1", "--wavelengths", "3",
                                    "--csv", "@/s.csv"};
  });
}
