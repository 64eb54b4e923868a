// Time and error of the eclipse tables through an atmosphere: the complete Earth
// set (atmosphere tables with refraction, shadow LuT, limb-luminance LuT), how each stage
// scales with its size, the full LuT against the part a scene needs (the u range of the
// Moon's distances), and the error of the shadow LuT, the limb-view size and the refraction
// step against a brute-force reference: illuminanceAt computed directly at each point of a
// profile (no LuT interpolation) with a fine limb view (--reference-limb rows, 128 x 128
// scattering cells) and a fine deviation table (1024 x 512, 2.5 km step). Errors are the
// largest relative error of R and G and of the luminance over the profile at the Moon's
// mean distance (0 to 1.1 x the penumbra's radius), where the reference is above 1e-5.
// Prints Markdown tables for docs/accuracy-vs-speed/eclipse-luts.md.
//
//   build/bench/umbra-bench-eclipse-atmosphere [--sections set,scaling,extent,error,columns] [--profile-points 41]
//
// `columns`: single beta columns of limb views (the limb-luminance LuT's, one layer) at 0,
// 0.25, 0.5, 0.75, 0.9 and 0.99 of the umbra's radius and halfway through the penumbra,
// against a view of --column-reference rows, for --column-sub sub-rows per solar diameter
// (0: point samples), and the precomputation's time for each.
#include "AtmosphericShadow.hpp"
#include "Colour.hpp"
#include "EclipseAtmosphere.hpp"
#include "SightLines.hpp"
#include "Spectrum.hpp"

#include <CLI/CLI.hpp>

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

using namespace umbra;
using eclipse::AtmosphericShadowModel;

namespace {

double seconds(const std::chrono::steady_clock::time_point& t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
template <class F>
double timed(const F& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return seconds(t0);
}

double kMoonM = 384400e3;  // the profile's distance (--distance)

struct Reference {
  std::vector<double> offsetsM;
  std::vector<glm::dvec3> rgb;
};

Reference reference(const AtmosphericShadowModel& m, int points, int rows) {
  Reference r;
  const double edge = 1.1 * eclipse::shadowConeRadii(m.system, kMoonM).penumbraRadiusM;
  for (int k = 0; k < points; ++k) r.offsetsM.push_back(edge * k / (points - 1));
  r.rgb.resize(points);
  const eclipse::LimbViewParams limb{rows, rows, 128, 128};
#pragma omp parallel for schedule(dynamic, 1)
  for (int k = 0; k < points; ++k) {
    const auto t = eclipse::illuminanceAt(m, eclipse::limbPositionBehind(m, kMoonM, r.offsetsM[k]), limb).total();
    r.rgb[k] = eclipse::rgbOfSpectralRatio(m.rays.wavelengthsNm, t.data());
  }
  return r;
}

struct Errors {
  double rg = 0.0, luminance = 0.0;
};
Errors compare(const Reference& ref, const std::vector<glm::dvec3>& values) {
  Errors e;
  for (std::size_t k = 0; k < values.size(); ++k) {
    for (int c = 0; c < 2; ++c)
      if (ref.rgb[k][c] > 1e-5) e.rg = std::max(e.rg, std::abs(values[k][c] / ref.rgb[k][c] - 1.0));
    const double l = colour::luminance(ref.rgb[k]);
    if (l > 1e-5) e.luminance = std::max(e.luminance, std::abs(colour::luminance(values[k]) / l - 1.0));
  }
  return e;
}

std::vector<glm::dvec3> direct(const AtmosphericShadowModel& m, const Reference& ref, const eclipse::LimbViewParams& limb) {
  std::vector<glm::dvec3> v(ref.offsetsM.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (int k = 0; k < static_cast<int>(v.size()); ++k) {
    const auto t = eclipse::illuminanceAt(m, eclipse::limbPositionBehind(m, kMoonM, ref.offsetsM[k]), limb).total();
    v[k] = eclipse::rgbOfSpectralRatio(m.rays.wavelengthsNm, t.data());
  }
  return v;
}

std::vector<glm::dvec3> sampled(const AtmosphericShadowModel& m, const Reference& ref, const eclipse::ShadowLut& lut) {
  std::vector<glm::dvec3> v;
  for (double off : ref.offsetsM) {
    const eclipse::LutCoords c = eclipse::lutCoordsOf(eclipse::limbPositionBehind(m, kMoonM, off));
    v.push_back(c.v >= 1.0 ? glm::dvec3(1.0) : lut.sample(c));
  }
  return v;
}

/// The command line (defaults as printed by --help).
struct Options {
  std::vector<std::string> sections{"set", "scaling", "extent", "error"};
  std::string preset = "earth";
  int points = 41, referenceRows = 2048;
  double distanceKm = 384400.0, sunDistanceM = 1.496e11;
  std::vector<int> lutSizes{64, 128, 256};
  std::vector<int> columnRows{64, 128, 256, 512};
  int columnReferenceRows = 16384;
  std::vector<double> columnSubRows{0, 32, 128};
  bool columnTiming = true;
  double columnReferenceSub = 512;
};

/// What the sections share: the atmosphere, its eclipse set (the tables, the deviation
/// table, the ray profile) and the time it took, the 256^2 shadow LuT once made.
struct Context {
  atmosphere::Atmosphere atm;
  std::unique_ptr<eclipse::EclipseAtmosphere> set;
  double tablesS = 0.0;
  eclipse::ShadowLut lut256;
};

/// The complete set at the default sizes, stage by stage.
void runSet(const Options& o, Context& c) {
  const std::string& preset = o.preset;
  const AtmosphericShadowModel& m = c.set->model;
  eclipse::AtmosphericShadowLutParams sp;  // 256^2, limb 256^2, 32^2 scattering cells
  const double shadowS = timed([&] { c.lut256 = eclipse::buildAtmosphericShadowLut(m, sp); });
  eclipse::LimbLuminanceLutParams lp;  // 64 x 64 x 64, 256 rows
  const double limbS = timed([&] { eclipse::buildLimbLuminanceLut(m, lp); });
  std::printf("## complete %s set\n\n| stage | seconds |\n|---|---|\n", preset.c_str());
  std::printf("| atmosphere tables (3 wavelengths, 4 orders, refracted paths) + refraction table's 2 top rows (512 wide) + ray profile | %.1f |\n", c.tablesS);
  std::printf("| shadow LuT 256^2 (limb views 256^2, scattering 16^2 cells) | %.1f |\n", shadowS);
  std::printf("| limb-luminance LuT 64x64x64 (views 64x256) | %.1f |\n", limbS);
  std::printf("| **total** | **%.1f** |\n\n", c.tablesS + shadowS + limbS);
}

/// The time of each table against its size knobs.
void runScaling(Context& c) {
  const AtmosphericShadowModel& m = c.set->model;
  std::printf("## scaling\n\n| table | size | seconds |\n|---|---|---|\n");
  for (int n : {32, 64, 128}) {
    eclipse::AtmosphericShadowLutParams sp;
    sp.width = sp.height = n;
    std::printf("| shadow LuT (limb 256^2, cells 16^2) | %d^2 | %.2f |\n", n, timed([&] { eclipse::buildAtmosphericShadowLut(m, sp); }));
  }
  for (int rows : {64, 128, 256, 512}) {
    eclipse::AtmosphericShadowLutParams sp;
    sp.width = sp.height = 64;
    sp.limb.rows = sp.limb.columns = rows;
    std::printf("| shadow LuT 64^2, limb rows | %d | %.2f |\n", rows, timed([&] { eclipse::buildAtmosphericShadowLut(m, sp); }));
  }
  for (int cells : {8, 16, 32, 64}) {
    eclipse::AtmosphericShadowLutParams sp;
    sp.width = sp.height = 64;
    sp.limb.scatteringColumns = sp.limb.scatteringRows = cells;
    std::printf("| shadow LuT 64^2, scattering cells | %d^2 | %.2f |\n", cells, timed([&] { eclipse::buildAtmosphericShadowLut(m, sp); }));
  }
  for (int n : {16, 32, 64}) {
    eclipse::LimbLuminanceLutParams lp;
    lp.width = lp.height = lp.columns = n;
    std::printf("| limb-luminance LuT | %dx%dx%d | %.2f |\n", n, n, n, timed([&] { eclipse::buildLimbLuminanceLut(m, lp); }));
  }
  std::printf("\n");
}

/// A whole shadow LuT against the columns the Moon can be in.
void runExtent(Context& c) {
  const AtmosphericShadowModel& m = c.set->model;
  // The Moon between perigee and apogee: the u texels its centre can be at (v from 0 to 1
  // moves u a little: take the range over v as well).
  const int n = 256;
  double uLo = 1.0, uHi = 0.0;
  for (double d : {356500e3, 406700e3})
    for (double offset : {0.0, 1.1 * eclipse::shadowConeRadii(m.system, d).penumbraRadiusM}) {
      const double u = eclipse::lutCoordsOf(eclipse::limbPositionBehind(m, d, offset)).u;
      uLo = std::min(uLo, u), uHi = std::max(uHi, u);
    }
  const eclipse::LutExtent ext{std::max(0, static_cast<int>(std::floor(uLo * n - 0.5))),
                               std::min(n, static_cast<int>(std::ceil(uHi * n + 0.5)) + 1), 0, n};
  eclipse::AtmosphericShadowLutParams sp;
  const double fullS = c.lut256.rgb.empty() ? timed([&] { c.lut256 = eclipse::buildAtmosphericShadowLut(m, sp); }) : -1.0;
  const double partS = timed([&] { eclipse::buildAtmosphericShadowLut(m, sp, ext); });
  std::printf("## full against scene-limited\n\n| request | texels | seconds |\n|---|---|---|\n");
  if (fullS >= 0) std::printf("| whole LuT | %d | %.1f |\n", n * n, fullS);
  else std::printf("| whole LuT | %d | (see the complete set) |\n", n * n);
  std::printf("| Moon 356 500-406 700 km: u texels %d-%d | %d | %.2f |\n\n", ext.uBegin, ext.uEnd - 1,
              (ext.uEnd - ext.uBegin) * n, partS);
}

/// Single columns of the limb-luminance LuT against rows and sub-rows.
void runColumns(const Options& o, Context& c) {
  const std::string& preset = o.preset;
  const AtmosphericShadowModel& m = c.set->model;
  // Single beta columns of the limb-luminance LuT (one layer: the column averaged over the
  // rows, as the LuT stores it) at o.points of the umbra, against --column-reference rows.
  // Error: the largest relative error per channel over the columns whose reference is above
  // 1 % of the brightest column of that channel (the others are dark ends of the Sun's image).
  // "sub" is LimbViewParams::subRowsPerSunDiameter (0: point samples, the old way).
  const double umbra = eclipse::shadowConeRadii(m.system, kMoonM).umbraRadiusM;
  const double penumbra = eclipse::shadowConeRadii(m.system, kMoonM).penumbraRadiusM;
  std::printf("## limb-luminance columns (%s, %.0f km; umbra radius %.0f km; 64 columns, 32^2 cells; "
              "reference %d rows, sub %g)\n\n| offset / umbra radius | rows | sub | max rel. error R | G | B |\n"
              "|---|---|---|---|---|---|\n",
              preset.c_str(), o.distanceKm, umbra / 1e3, o.columnReferenceRows, o.columnReferenceSub);
  auto columnsOf = [&](const eclipse::LimbPosition& p, int rows, double sub) {
    eclipse::LimbViewParams limb{64, rows, 32, 32};
    limb.subRowsPerSunDiameter = sub;
    return eclipse::layerAverages(eclipse::renderLimbView(m, p, limb), 1);
  };
  const int nc = m.rays.channels;
  std::vector<double> worst(o.columnSubRows.size() * o.columnRows.size() * 3, 0.0);
  for (double f : {0.0, 0.25, 0.5, 0.75, 0.9, 0.99, 0.5 * (1.0 + penumbra / umbra)}) {
    const eclipse::LimbPosition p = eclipse::limbPositionBehind(m, kMoonM, f * umbra);
    const std::vector<double> ref = columnsOf(p, o.columnReferenceRows, o.columnReferenceSub);
    for (std::size_t a = 0; a < o.columnSubRows.size(); ++a)
      for (std::size_t b = 0; b < o.columnRows.size(); ++b) {
        const std::vector<double> v = columnsOf(p, o.columnRows[b], o.columnSubRows[a]);
        std::printf("| %.2f | %d | %g |", f, o.columnRows[b], o.columnSubRows[a]);
        int q = 0;
        for (double nm : {680.0, 550.0, 440.0}) {
          int c = 0;  // the channel of this wavelength (or the nearest)
          for (int k = 1; k < nc; ++k)
            if (std::abs(m.rays.wavelengthsNm[k] - nm) < std::abs(m.rays.wavelengthsNm[c] - nm)) c = k;
          double top = 0.0, e = 0.0;
          for (int col = 0; col < 64; ++col) top = std::max(top, ref[col * nc + c]);
          for (int col = 0; col < 64; ++col)
            if (ref[col * nc + c] > 0.01 * top) e = std::max(e, std::abs(v[col * nc + c] / ref[col * nc + c] - 1.0));
          std::printf(" %.2e |", e);
          double& w = worst[(a * o.columnRows.size() + b) * 3 + q++];
          w = std::max(w, e);
        }
        std::printf("\n");
      }
  }
  std::printf("\n| worst over the o.points: rows | sub | R | G | B |\n|---|---|---|---|---|\n");
  for (std::size_t a = 0; a < o.columnSubRows.size(); ++a)
    for (std::size_t b = 0; b < o.columnRows.size(); ++b) {
      const double* w = &worst[(a * o.columnRows.size() + b) * 3];
      std::printf("| %d | %g | %.2e | %.2e | %.2e |\n", o.columnRows[b], o.columnSubRows[a], w[0], w[1], w[2]);
    }
  // Precomputation time, the settings interleaved (three rounds; the machine may be shared):
  // CPU seconds of the process (all threads), steadier than the wall time under load.
  std::printf("\n| precomputation, CPU seconds (3 rounds) | sub | |\n|---|---|---|\n");
  auto cpuTimed = [](const auto& f) {
    const std::clock_t c0 = std::clock();
    f();
    return static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  };
  std::vector<std::vector<double>> limbS(o.columnSubRows.size()), shadowS(o.columnSubRows.size());
  for (int round = 0; round < (o.columnTiming ? 3 : 0); ++round)
    for (std::size_t a = 0; a < o.columnSubRows.size(); ++a) {
      eclipse::LimbLuminanceLutParams lp;  // 64 x 64 x 64, views of 256 rows
      lp.limb.subRowsPerSunDiameter = o.columnSubRows[a];
      eclipse::AtmosphericShadowLutParams sp;  // limb views 256^2, 16^2 cells
      sp.width = sp.height = 128;
      sp.limb.subRowsPerSunDiameter = o.columnSubRows[a];
      limbS[a].push_back(cpuTimed([&] { eclipse::buildLimbLuminanceLut(m, lp); }));
      shadowS[a].push_back(cpuTimed([&] { eclipse::buildAtmosphericShadowLut(m, sp); }));
    }
  for (std::size_t a = 0; a < (o.columnTiming ? o.columnSubRows.size() : 0); ++a) {
    std::printf("| limb-luminance LuT 64x64x64 (views 64x256) | %g | %.2f %.2f %.2f |\n", o.columnSubRows[a], limbS[a][0],
                limbS[a][1], limbS[a][2]);
    std::printf("| shadow LuT 128^2 (limb views 256^2) | %g | %.2f %.2f %.2f |\n", o.columnSubRows[a], shadowS[a][0],
                shadowS[a][1], shadowS[a][2]);
  }
  std::printf("\n");
}

/// The tables' error against a brute-force reference, per knob.
void runError(const Options& o, Context& c) {
  const atmosphere::Atmosphere& atm = c.atm;
  const std::string& preset = o.preset;
  const AtmosphericShadowModel& m = c.set->model;
  // The reference: a fine deviation table and fine limb views, evaluated at each point.
  atmosphere::RefractionTable fine;
  const double fineS = timed([&] {
    fine = atmosphere::buildRefractionTable(atmosphere::refractiveMedium(atm, atm.refractivityReferenceWavelengthNm),
                                            1024, 512, 2.5e3);
  });
  AtmosphericShadowModel ref = m;
  ref.rays = eclipse::limbRayProfile(c.set->tables, &fine, 16384);
  Reference r;
  const double refS = timed([&] { r = reference(ref, o.points, o.referenceRows); });
  std::printf("## error against the brute-force reference (%s, %.0f km)\n\nreference: deviation table 1024x512 at 2.5 km "
              "(%.0f s), limb views %dx%d with 128^2 scattering cells, %d o.points (%.1f s)\n\n",
              preset.c_str(), o.distanceKm, fineS, o.referenceRows, o.referenceRows, o.points, refS);
  std::printf("| what | setting | seconds | max rel. error R,G | max rel. error luminance |\n|---|---|---|---|---|\n");
  for (int n : o.lutSizes) {
    eclipse::ShadowLut lut;
    double s = 0.0;
    eclipse::AtmosphericShadowLutParams sp;
    sp.width = sp.height = n;
    if (n == 256 && !c.lut256.rgb.empty()) lut = c.lut256;
    else s = timed([&] { lut = eclipse::buildAtmosphericShadowLut(m, sp); });
    const Errors e = compare(r, sampled(m, r, lut));
    std::printf("| shadow LuT (sampled) | %d^2 | %s | %.2e | %.2e |\n", n, s > 0 ? std::to_string(s).substr(0, 5).c_str() : "(set)", e.rg, e.luminance);
  }
  for (double sub : {0.0, eclipse::LimbViewParams{}.subRowsPerSunDiameter})
    for (int rows : {32, 64, 128, 256, 512}) {
      eclipse::LimbViewParams limb{rows, rows, 16, 16};
      limb.subRowsPerSunDiameter = sub;
      std::vector<glm::dvec3> v;
      const double s = timed([&] { v = direct(m, r, limb); });
      const Errors e = compare(r, v);
      std::printf("| limb view rows (direct, %d o.points, sub-rows %g) | %d | %.3f | %.2e | %.2e |\n", o.points, sub, rows, s,
                  e.rg, e.luminance);
    }
  for (int cells : {8, 16, 32, 64}) {
    eclipse::LimbViewParams limb{256, 256, cells, cells};
    const Errors e = compare(r, direct(m, r, limb));
    std::printf("| scattering cells (direct) | %d^2 | - | %.2e | %.2e |\n", cells, e.rg, e.luminance);
  }
  struct Refraction {
    int w, h;
    double step;
  };
  for (const Refraction& q : {Refraction{512, 256, 40e3}, Refraction{512, 256, 20e3}, Refraction{512, 256, 5e3},
                              Refraction{256, 128, 10e3}, Refraction{1024, 512, 10e3}}) {
    atmosphere::RefractionTable t;
    const double s = timed([&] {
      t = atmosphere::buildRefractionTable(atmosphere::refractiveMedium(atm, atm.refractivityReferenceWavelengthNm),
                                           q.w, q.h, q.step);
    });
    AtmosphericShadowModel mm = m;
    mm.rays = eclipse::limbRayProfile(c.set->tables, &t, 4096);
    const Errors e = compare(r, direct(mm, r, {256, 256, 16, 16}));
    std::printf("| deviation table (direct, limb 256^2) | %dx%d, %.0f km | %.1f | %.2e | %.2e |\n", q.w, q.h, q.step / 1e3, s,
                e.rg, e.luminance);
  }
  std::printf("\n");
}

} // namespace

int main(int argc, char** argv) {
  CLI::App app{"Time and error of the eclipse tables through an atmosphere"};
  Options o;
  app.add_option("--sections", o.sections, "Which parts to run")->delimiter(',');
  app.add_option("--atmosphere", o.preset, "Atmosphere preset")->capture_default_str();
  app.add_option("--profile-points", o.points, "Points of the error profile")->capture_default_str();
  app.add_option("--reference-limb", o.referenceRows, "Rows and columns of the reference limb views")->capture_default_str();
  app.add_option("--distance-km", o.distanceKm, "Distance of the error profile behind the occluder")->capture_default_str();
  app.add_option("--sun-distance-m", o.sunDistanceM, "Sun-occluder distance")->capture_default_str();
  app.add_option("--lut-sizes", o.lutSizes, "Shadow-LuT sizes of the error section")->delimiter(',');
  app.add_option("--column-rows", o.columnRows, "Limb-view rows of the columns section")->delimiter(',');
  app.add_option("--column-reference", o.columnReferenceRows, "Rows of the columns section's reference")->capture_default_str();
  app.add_option("--column-sub", o.columnSubRows, "Sub-rows per solar diameter of the columns section")
      ->delimiter(',');
  app.add_option("--column-reference-sub", o.columnReferenceSub, "Sub-rows per solar diameter of its reference")
      ->capture_default_str();
  app.add_option("--column-timing", o.columnTiming, "Time the precomputation in the columns section")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  kMoonM = o.distanceKm * 1e3;
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // lines as they come, also into a file
  const std::set<std::string> run(o.sections.begin(), o.sections.end());
  std::printf("threads: %d\n\n", omp_get_max_threads());

  Context c;
  c.atm = atmosphere::loadAtmosphere(o.preset, atmosphere::WavelengthSet::rgb().nm);
  const eclipse::EclipseAtmosphereOptions options;  // defaults: 4 orders, refraction 512 x 256, 10 km
  c.tablesS = timed([&] { c.set = eclipse::prepareEclipseAtmosphere(c.atm, o.preset, o.sunDistanceM, options); });
  if (run.count("set")) runSet(o, c);
  if (run.count("scaling")) runScaling(c);
  if (run.count("extent")) runExtent(c);
  if (run.count("columns")) runColumns(o, c);
  if (run.count("error")) runError(o, c);
  return 0;
}
