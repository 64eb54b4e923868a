// umbra profile shadow (--occluder BODY --distance 384400km | --scene FILE [--time T]) [--samples N] [--exact]
//                      [--atmosphere PRESET [--limb-size N] [--draft-tables]] --csv FILE [--plot FILE]
// With --atmosphere the LuT is the atmospheric one and the plot is log-scale I/I_sun with
// the umbra's and the penumbra's edges marked (the eclipse paper's Figure 12).
#include "Commands.hpp"
#include "OutputFile.hpp"
#include "ProfileExport.hpp"
#include "ShadowCommon.hpp"
#include "ShadowMapping.hpp"
#include "SolarDisc.hpp"
#include "vtkEclipseShadowLutSource.h"
#include "vtkShadowProfileFilter.h"
#include "FieldParameters.h"
#include "ShadowLutData.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkTable.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>

namespace umbra::cli {

namespace {

struct ProfileOptions {
  std::string occluder, distance, sunDistance, occluderRadius, maxOffset, csv, plot, lut, scene, time;
  int samples = 1001, size = 256;
  bool noAtmosphere = false, exact = false, logPlot = false;
  double limbDarkening = 0.6;
  EclipseAtmosphereChoice atmosphere;
  CacheOptions cache;
};

/// The options of `profile shadow`; returns --size (whether it was given matters).
CLI::Option* addProfileOptions(CLI::App* shadow, ProfileOptions& o) {
  CLI::Option* occluder = shadow->add_option("--occluder", o.occluder, "Occluding body: Earth, Moon, Mars, Phobos, Deimos");
  CLI::Option* distance = shadow->add_option(
      "--distance", o.distance,
      "Distance of the cross-section behind the occluder's centre, along the shadow axis (units m, km, au; e.g. 384400km)");
  CLI::Option* scene = shadow->add_option(
      "--scene", o.scene,
      "Take the bodies from a scene file instead: the receiver is the camera's target, the occluder the body "
      "whose shadow it is in, the distance the receiver's");
  shadow->add_option("--time", o.time, "With --scene: UTC time, ISO 8601 (default: the scene's)")->needs(scene);
  scene->excludes(occluder)->excludes(distance);
  shadow->add_option("--sun-distance", o.sunDistance, "Sun-occluder distance (default: the body's mean distance)");
  shadow->add_option("--occluder-radius", o.occluderRadius, "Occluder radius (default: the body's mean radius)");
  shadow->add_option("--max-offset", o.maxOffset, "Largest offset from the axis (default: 1.25 x the penumbra's radius)");
  shadow->add_option("--samples", o.samples, "Samples across the profile")->capture_default_str()->check(CLI::Range(2, 1000000));
  CLI::Option* size = shadow->add_option("--size", o.size, "Texels along u and v of the shadow LuT (with --scene: the scene's)")->capture_default_str()->check(CLI::Range(8, 4096));
  shadow->add_option("--limb-darkening", o.limbDarkening, "Linear limb-darkening coefficient of the Sun (Eq. 1)")->check(CLI::Range(0.0, 1.0))
      ->capture_default_str()->check(CLI::Range(0.0, 1.0));
  shadow->add_flag("--no-atmosphere", o.noAtmosphere, "Treat the occluder as airless (the default without --atmosphere)");
  shadow->add_flag("--log", o.logPlot, "Log-scale plot with the umbra's and penumbra's edges (default with --atmosphere)");
  o.atmosphere.addTo(shadow);
  shadow->add_option("--lut", o.lut, "Read the shadow LuT from this EXR (from 'umbra precompute shadow') instead of building it")
      ->check(CLI::ExistingFile);
  shadow->add_flag("--exact", o.exact, "Compute every sample directly instead of through the LuT");
  shadow->add_option("--csv", o.csv, "CSV file to write (offset_km,r,g,b,luminance)")->required();
  shadow->add_option("--plot", o.plot, "Plot to write: FILE.png (needs an X display) or FILE.svg");
  o.cache.addTo(shadow);
  return size;
}

/// Where the cross-section is: the occluder, the distance behind it, the Sun's radius and
/// the place's name for the plot; from a scene (its LuT size, unless `size` was given) or
/// from the options.
struct CrossSection {
  OccluderChoice occ;
  double distanceM = 0.0, sunRadiusM = eclipse::kSunRadiusM;
  std::string where;
};

CrossSection crossSection(const ProfileOptions& o, bool sizeGiven, int& size) {
  CrossSection c;
  c.where = o.distance;
  if (!o.scene.empty()) {
    const SceneShadow ss = sceneShadow(o.scene, o.time);
    c.occ = ss.occluder;
    c.distanceM = ss.geometry.receiverDistanceM;
    c.sunRadiusM = ss.geometry.sunRadiusM;
    if (!sizeGiven) size = ss.lutSize;
    c.where = std::to_string(std::lround(c.distanceM / 1e3)) + " km";
    std::cout << ss.geometry.receiver << " is " << std::lround(c.distanceM / 1e3) << " km behind " << c.occ.name
              << " and " << std::lround(ss.geometry.offsetM / 1e3) << " km from its shadow axis\n";
  } else {
    if (o.occluder.empty() || o.distance.empty())
      throw CommandError("give --occluder and --distance, or --scene");
    c.occ = chooseOccluder(o.occluder, o.occluderRadius, o.sunDistance);
    c.distanceM = lengthOption("--distance", o.distance);
    if (!(c.distanceM > 0.0)) throw CommandError("--distance: expected a positive length, got " + o.distance);
    // Behind the occluder's centre, beyond its surface.
    c.distanceM = lengthOption("--distance", o.distance, c.occ.radiusM, kMaxDistanceM);
  }
  return c;
}

/// The shadow LuT the filter samples (read from --lut, or made for this cross-section),
/// or, with --exact --atmosphere, the profile computed point by point (returned).
vtkSmartPointer<vtkTable> connectProfileInput(const ProfileOptions& o, int size, const OccluderChoice& occ,
                                              double distanceM, double sunRadiusM, double maxOffsetM,
                                              bool withAtmosphere, vtkShadowProfileFilter* filter,
                                              vtkSmartPointer<vtkEclipseShadowLutSource>& lut) {
  vtkSmartPointer<vtkTable> exactAtmospheric;
  if (withAtmosphere && o.exact) {
    exactAtmospheric = atmosphericProfile(o.atmosphere, occ, distanceM, maxOffsetM, o.samples, o.limbDarkening);
  } else if (!o.lut.empty() && !o.exact) {
    vtkSmartPointer<vtkImageData> table = readShadowLut(o.lut);
    // Whose shadow it is: an atmospheric LuT holds its occluder's atmosphere; an airless
    // one (Eq. 3-6 scale the discs away) serves any occluder, with a note.
    const auto header = filters::fieldParameters(table);
    const auto of = header.find("occluder"), kind = header.find("kind");
    if (of != header.end() && !of->second.empty() && of->second != occ.name) {
      if (kind != header.end() && kind->second == filters::kAtmosphereShadowLutKind)
        throw CommandError("--lut: " + o.lut + " is the shadow of " + of->second + " through its atmosphere, not " +
                           occ.name + "'s (--occluder)");
      std::cerr << "note: --lut " << o.lut << " was made for " << of->second << "; an airless LuT serves "
                << occ.name << " as well\n";
    }
    filter->SetInputData(table);
  } else if (!o.exact) {
    // Near the occluder the penumbra is 2u of the LuT's height (docs/eclipse-shadows.md):
    // below 16 rows the LuT covers only this cross-section's ranges.
    const eclipse::SunOccluderSystem system{sunRadiusM, occ.radiusM, occ.sunDistanceM};
    const double offsetM =
        maxOffsetM > 0.0 ? maxOffsetM : 1.25 * eclipse::shadowConeRadii(system, distanceM).penumbraRadiusM;
    eclipse::LutRange range;
    bool ranged = false;
    try {
      range = eclipse::lutRangeForDistances(system, distanceM, std::hypot(distanceM, offsetM), !withAtmosphere,
                                            size);
      ranged = eclipse::rangedLutPays(range, size);
    } catch (const std::invalid_argument&) {  // a cross-section reaching the Sun: the whole LuT
    }
    if (ranged)
      std::cerr << "note: the penumbra is " << std::lround(2.0 * range.uMax * size)
                << " rows of a whole LuT here; using one over this cross-section's distances\n";
    lut = updateShadowLut(size, o.limbDarkening, o.cache, &occ, &o.atmosphere, ranged ? &range : nullptr);
    filter->SetInputConnection(lut->GetOutputPort());
  }
  return exactAtmospheric;
}

void writeProfilePlotOf(const ProfileOptions& o, vtkTable* table, vtkShadowProfileFilter* filter,
                        const CrossSection& c, bool withAtmosphere, const eclipse::ShadowConeRadii& r) {
  const OccluderChoice& occ = c.occ;
  const std::string& where = c.where;
  if (!o.plot.empty()) {
    plot::ProfilePlotStyle style;
    style.logScale = o.logPlot || withAtmosphere;
    if (o.exact) {
      style.subtitle = "computed point by point (--exact)";
    } else if (auto* image = vtkImageData::SafeDownCast(filter->GetInputDataObject(0, 0))) {
      int dims[3];
      image->GetDimensions(dims);
      style.subtitle = "sampled from the " + std::to_string(dims[0]) + "x" + std::to_string(dims[1]) +
                       (withAtmosphere ? " atmospheric" : "") + " shadow LuT" +
                       (o.lut.empty() ? "" : " " + o.lut) + " as the renderer reads it (bilinear)";
    }
    if (style.logScale) {
      style.markersKm.emplace_back(std::max(r.umbraRadiusM, r.antumbraRadiusM) / 1e3,
                                   r.antumbraRadiusM > 0.0 ? "antumbra" : "umbra");
      style.markersKm.emplace_back(r.penumbraRadiusM / 1e3, "penumbra");
    }
    plot::writeProfilePlot(table, o.plot,
                           occ.name + "'s shadow at " + where +
                               (withAtmosphere ? " through " + o.atmosphere.atmosphere : "") +
                               (o.exact ? " (exact)" : ""),
                           style);
    std::cout << "wrote " << o.plot << "\n";
  }
}

int runProfile(const ProfileOptions& o, bool sizeGiven) {
  output::checkWritable(o.csv, {".csv"});
  if (!o.plot.empty()) output::checkWritable(o.plot, {".png", ".svg"});
  int size = o.size;
  CrossSection c = crossSection(o, sizeGiven, size);
  OccluderChoice& occ = c.occ;
  const double distanceM = c.distanceM, sunRadiusM = c.sunRadiusM;
  const std::string& where = c.where;
  double maxOffsetM = 0.0;
  if (!o.maxOffset.empty()) {
    maxOffsetM = lengthOption("--max-offset", o.maxOffset);
    if (!(maxOffsetM > 0.0)) throw CommandError("--max-offset: expected a positive length, got " + o.maxOffset);
    maxOffsetM = lengthOption("--max-offset", o.maxOffset, 1.0, kMaxDistanceM);
  }
  const bool withAtmosphere = !o.atmosphere.atmosphere.empty();
  if (withAtmosphere && o.noAtmosphere) throw CommandError("--atmosphere and --no-atmosphere exclude each other");
  if (withAtmosphere && !o.lut.empty()) throw CommandError("--lut and --atmosphere exclude each other");
  if (withAtmosphere) occ.radiusM = o.atmosphere.bottomRadiusM();
  if (occ.hasAtmosphere && !o.noAtmosphere && !withAtmosphere)
    std::cerr << "note: this is the shadow of an airless " << occ.name << "; --atmosphere PRESET adds its "
              << "atmosphere (--no-atmosphere silences this note)\n";

  vtkNew<vtkShadowProfileFilter> filter;
  vtkSmartPointer<vtkEclipseShadowLutSource> lut;  // exact mode needs none
  const vtkSmartPointer<vtkTable> exactAtmospheric =
      connectProfileInput(o, size, occ, distanceM, sunRadiusM, maxOffsetM, withAtmosphere, filter, lut);
  filter->SetSunRadiusM(sunRadiusM);
  filter->SetOccluderRadiusM(occ.radiusM);
  filter->SetSunOccluderDistanceM(occ.sunDistanceM);
  filter->SetReceiverDistanceM(distanceM);
  filter->SetMaxOffsetM(maxOffsetM);
  filter->SetSamples(o.samples);
  filter->SetExact(o.exact);
  filter->SetLimbDarkening(o.limbDarkening);
  if (!exactAtmospheric) filter->Update();
  vtkTable* table = exactAtmospheric ? exactAtmospheric.Get() : filter->GetOutput();
  if (table->GetNumberOfRows() != o.samples) throw CommandError("the shadow profile could not be computed");

  plot::writeProfileCsv(table, o.csv);
  std::cout << "wrote " << o.csv << "\n";
  const eclipse::ShadowConeRadii r = eclipse::shadowConeRadii({sunRadiusM, occ.radiusM, occ.sunDistanceM}, distanceM);
  writeProfilePlotOf(o, table, filter, c, withAtmosphere, r);
  std::cout << std::fixed << std::setprecision(1) << "geometric radii at " << where << ": "
            << (r.antumbraRadiusM > 0.0 ? "antumbra " : "umbra ") << std::max(r.umbraRadiusM, r.antumbraRadiusM) / 1e3
            << " km, penumbra " << r.penumbraRadiusM / 1e3 << " km\n";
  return 0;
}

} // namespace

void addProfileCommand(CLI::App& app, Action& action) {
  CLI::App* profile = app.add_subcommand("profile", "Cross-sections of shadows, as CSV and plots");
  profile->require_subcommand(1);
  CLI::App* shadow = profile->add_subcommand(
      "shadow", "The shadow of an occluder across its axis, at a distance behind it (I/I_sun per channel)");
  auto o = std::make_shared<ProfileOptions>();
  CLI::Option* size = addProfileOptions(shadow, *o);
  shadow->callback([&action, o, size] {
    const bool sizeGiven = size->count() > 0;
    action = [o, sizeGiven] { return runProfile(*o, sizeGiven); };
  });
}

} // namespace umbra::cli
