#include "AtmosphereShadow.h"

#include "Atmosphere.hpp"
#include "SceneInputs.h"
#include "Spectrum.hpp"
#include "ShadowMapping.hpp"
#include "vtkEclipseShadowLutSource.h"
#include "vtkLimbLuminanceSource.h"

#include <vtkImageData.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace umbra::pipeline {
namespace {
// Eq. 4's u for the given distances to the occluder and the Sun.
double lutU(double sunRadiusM, double sunDistanceM, double occRadiusM, double occDistanceM) {
  const double phiSun = eclipse::angularRadiusRad(sunRadiusM, sunDistanceM);
  const double phiOcc = eclipse::angularRadiusRad(occRadiusM, occDistanceM);
  return phiSun / (phiOcc + phiSun);
}

// The body with the scene's atmosphere (throws when it is not one of the scene's).
const SphereBody& atmosphereBody(const SceneInputs& in) {
  const auto occ = std::find_if(in.bodies.begin(), in.bodies.end(),
                                [&](const SphereBody& b) { return b.name == in.atmosphere->body; });
  if (occ == in.bodies.end()) throw std::invalid_argument("atmosphere of '" + in.atmosphere->body + "': no such body");
  return *occ;
}

// Tables of a scene in motion (an animation, the GUI's time slider through an eclipse) are
// asked for on grids, so that the frames of a while make one table, one cache file: the
// Sun's distance and the ends of a u range on geometric grids of these relative steps
// (docs/accuracy-vs-speed/eclipse-luts.md, "Tables for a scene in motion").
constexpr double kSunDistanceStep = 1e-4;
constexpr double kRangeUStep = 1e-3;

// The point of the grid {exp(k step)} at or below `x` > 0 (up: at or above).
double onGeometricGrid(double x, double step, bool up) {
  const double k = up ? std::ceil(std::log(x) / step) : std::floor(std::log(x) / step);
  double g = std::exp(k * step);
  if (up && g < x) g = std::exp((k + 1.0) * step);   // exp/log rounding
  if (!up && g > x) g = std::exp((k - 1.0) * step);
  return g;
}

// The request's occluder, model and geometry for `in`'s atmosphere; a table of `width` x `height`.
EclipseTableRequest tableRequest(const SceneInputs& in, int width, int height) {
  const SphereBody& occ = atmosphereBody(in);
  EclipseTableRequest r;
  r.occluder = occ.name;
  r.model = in.atmosphere->model;
  // The model's ground: the body's sphere is shrunk below an observer on it (by ~5 m, with
  // the camera's rounding), which would make every frame ask for another table.
  r.occluderRadiusM = in.atmosphere->bottomRadiusM > 0.0 ? in.atmosphere->bottomRadiusM : occ.radiusM;
  r.sunRadiusM = in.sun.radiusM;
  r.sunOccluderDistanceM = sunDistanceOnGrid(glm::length(occ.centreM - in.sun.positionM));
  r.width = width;
  r.height = height;
  return r;
}

// `source` set up for `r` (bodies, Sun, model, size) and its atmosphere tables connected
// (from their cache); `what` names the table in errors.
template <class Source>
vtkAlgorithm* setUpTable(Source* source, const EclipseTableRequest& r, const std::string& what) {
  if (!source) throw std::invalid_argument("no source for the " + what);
  source->SetOccluderName(r.occluder.c_str());
  source->SetOccluderRadiusM(r.occluderRadiusM);
  source->SetSunRadiusM(r.sunRadiusM);
  source->SetSunOccluderDistanceM(r.sunOccluderDistanceM);
  source->SetAtmosphereModel(r.model);
  source->SetWidth(r.width);
  source->SetHeight(r.height);
  try {
    return source->ConnectAtmosphereTables();  // the atmosphere tables from their cache
  } catch (const std::exception& e) {
    throw std::runtime_error(what + " of '" + r.occluder + "': " + e.what());
  }
}

// The least and the largest radius of an occluder's outline: its radius for a sphere; for a
// spheroid the polar and equatorial radii (the outline's towards the Sun lies between).
std::array<double, 2> outlineRadiiM(const SphereBody& occluder) {
  const eclipse::Occluder o = occluderOf(occluder);
  const double a = eclipse::equatorialRadiusM(o.radiusM, o.figure);
  return {a * (1.0 - o.figure.flattening), a};
}

// Adds to `u` (min, max) the u range of the points at [lo, hi] from `occluder`'s centre
// (for each radius its outline can have); false when they reach the Sun.
bool addDistances(const SunLight& sun, const SphereBody& occluder, double lo, double hi, bool darkUmbra, int height,
                  std::array<double, 2>& u) {
  for (const double radiusM : outlineRadiiM(occluder)) {
    const eclipse::SunOccluderSystem system{sun.radiusM, radiusM, glm::length(occluder.centreM - sun.positionM)};
    try {
      const eclipse::LutRange r = eclipse::lutRangeForDistances(system, lo, hi, darkUmbra, height);
      u = {std::min(u[0], r.uMin), std::max(u[1], r.uMax)};
    } catch (const std::invalid_argument&) {
      return false;
    }
  }
  return true;
}

// The ranges for the u range `u` (none when empty or when a whole LuT resolves it).
// The ends on the grid of kRangeUStep (outward: the range still holds every u asked for).
std::optional<eclipse::LutRange> rangeForU(const std::array<double, 2>& u, bool darkUmbra, int height) {
  if (!(u[0] < u[1])) return std::nullopt;
  const double uMin = u[0] > 0.0 ? onGeometricGrid(u[0], kRangeUStep, false) : 0.0;
  const double uMax = std::min(onGeometricGrid(u[1], kRangeUStep, true), 1.0);
  const eclipse::LutRange r = eclipse::lutRangeForU(uMin, uMax, darkUmbra, height);
  if (!eclipse::rangedLutPays(r, height)) return std::nullopt;
  return r;
}

// Sets `source` to `range` (rangedLutWidth of its width) or, without, to the whole LuT;
// runs `update` and gives the source its width back (also when `update` throws).
template <class Source, class Update>
void updateRanged(Source* source, const std::optional<eclipse::LutRange>& range, const Update& update) {
  const int width = source->GetWidth();
  source->SetLutRange(range ? *range : eclipse::LutRange{});
  if (range) source->SetWidth(rangedLutWidth(*range, width));
  struct Restore {
    Source* s;
    int w;
    ~Restore() { s->SetWidth(w); }
  } restore{source, width};
  update();
}

// `source` set up for `r` (setUpTable) and `update` run over its ranges (updateRanged);
// throws naming `what` and the body when that fails, was cancelled, or `made` (of the
// output) is false.
template <class Source, class Update, class Made>
void updateTable(Source* source, const EclipseTableRequest& r, const std::string& what, const Update& update,
                 const Made& made) {
  setUpTable(source, r, what);
  const std::string prefix = what + " of '" + r.occluder + "': ";
  try {
    updateRanged(source, r.range, update);
  } catch (const std::exception& e) {
    throw std::runtime_error(prefix + e.what());
  }
  if (!made(source->GetOutput()))
    throw std::runtime_error(prefix + (source->GetLastUpdateAborted() ? "cancelled" : "the table could not be made"));
}

// The tables of the atmosphere shared by the small shadow and limb-luminance LuTs.
// (atmosphere::kSmallTableSizes with 2 orders.)
void useSmallEclipseAtmosphere(vtkEclipseAtmosphereSource* s) {
  const atmosphere::TableSizes& small = atmosphere::kSmallTableSizes;
  s->SetOrders(2);
  s->SetTransmittanceSize(small.transmittance[0], small.transmittance[1]);
  s->SetScatteringSize(small.scattering[0], small.scattering[1], small.scattering[2], small.scattering[3]);
  s->SetIrradianceSize(small.irradiance[0], small.irradiance[1]);
  s->SetRefractionSize(small.refraction[0], small.refraction[1]);
}
} // namespace

double sunDistanceOnGrid(double distanceM) {
  if (!(distanceM > 0.0) || !std::isfinite(distanceM)) return distanceM;  // validated where it is used
  const double below = onGeometricGrid(distanceM, kSunDistanceStep, false);
  const double above = onGeometricGrid(distanceM, kSunDistanceStep, true);
  return distanceM - below <= above - distanceM ? below : above;
}

std::array<int, 2> shadowLutColumns(const SunLight& sun, const SphereBody& occluder, const SphereBody& receiver,
                                    int width) {
  validateSun(sun);
  validateBody(occluder);
  validateBody(receiver);
  if (width < 1) throw std::invalid_argument("shadow LuT width must be >= 1");
  const double dOcc = glm::length(receiver.centreM - occluder.centreM);
  const double dSun = glm::length(receiver.centreM - sun.positionM);
  const double r = receiver.radiusM;
  const auto outline = outlineRadiiM(occluder);
  const double uMin = lutU(sun.radiusM, dSun + r, outline[1], std::max(dOcc - r, 0.0));
  const double uMax = lutU(sun.radiusM, std::max(dSun - r, sun.radiusM), outline[0], dOcc + r);
  // Texel i's centre is at (i + 0.5) / width; a lookup at u reads floor(u w - 0.5) and the next.
  const int first = static_cast<int>(std::floor(uMin * width - 0.5));
  const int last = static_cast<int>(std::floor(uMax * width - 0.5)) + 1;
  return {std::clamp(first, 0, width - 1), std::clamp(last, 0, width - 1)};
}

bool canBeInPenumbra(const SunLight& sun, const SphereBody& occluder, const SphereBody& receiver) {
  const glm::dvec3 toOcc = occluder.centreM - sun.positionM;
  const double d = glm::length(toOcc);
  if (!(d > sun.radiusM + occluder.radiusM)) return true;  // touching the Sun: anything goes
  const glm::dvec3 axis = toOcc / d;
  // The apex lies between the Sun and the occluder, d R / (R + R_sun) from the occluder.
  const glm::dvec3 apex = occluder.centreM - axis * (d * occluder.radiusM / (occluder.radiusM + sun.radiusM));
  const double sinA = (sun.radiusM + occluder.radiusM) / d, cosA = std::sqrt(1.0 - sinA * sinA);
  const glm::dvec3 w = receiver.centreM - apex;
  const double along = glm::dot(w, axis), perp = glm::length(w - along * axis);
  const double margin = 1e-6 * glm::length(w) + 1.0;  // rounding
  // Nearest point of the cone's surface on its nappe, or else its apex.
  if (along * cosA + perp * sinA >= 0.0) return perp * cosA - along * sinA <= receiver.radiusM + margin;
  return glm::length(w) <= receiver.radiusM + margin;
}

std::optional<eclipse::LutRange> sceneLutRange(const SunLight& sun, const std::vector<SphereBody>& occluders,
                                               const std::vector<SphereBody>& receivers, bool darkUmbra, int height) {
  validateSun(sun);
  std::array<double, 2> u{1.0, 0.0};
  for (const SphereBody& occ : occluders) {
    validateBody(occ);
    for (const SphereBody& r : receivers) {
      validateBody(r);
      if (r.name == occ.name) continue;
      const SphereBody seen = occluderSeenBy(occ, r);  // where r's shading takes it
      if (!canBeInPenumbra(sun, seen, r)) continue;
      const double dOcc = glm::length(r.centreM - seen.centreM);
      const double lo = std::max(dOcc - r.radiusM, seen.radiusM), hi = dOcc + r.radiusM;
      if (hi <= lo) continue;  // inside the occluder: never seen
      if (!addDistances(sun, seen, lo, hi, darkUmbra, height, u)) return std::nullopt;
    }
  }
  return rangeForU(u, darkUmbra, height);
}

std::optional<eclipse::LutRange> pointLutRange(const SunLight& sun, const SphereBody& occluder,
                                               const glm::dvec3& pointM, bool darkUmbra, int height) {
  validateSun(sun);
  validateBody(occluder);
  const double d = glm::length(pointM - occluder.centreM);
  std::array<double, 2> u{1.0, 0.0};
  if (!(d > occluder.radiusM) || !addDistances(sun, occluder, d, d, darkUmbra, height, u)) return std::nullopt;
  return rangeForU(u, darkUmbra, height);
}

int rangedLutWidth(const eclipse::LutRange& range, int width) {
  const int w = static_cast<int>(std::ceil(width * (range.uMax - range.uMin))) + 1;
  return std::clamp(w, 2, std::max(width, 2));
}

bool EclipseTableRequest::operator==(const EclipseTableRequest& o) const {
  const auto name = [](const atmosphere::AtmosphereModelPtr& m) { return m ? m->name() : std::string(); };
  return occluder == o.occluder && name(model) == name(o.model) && occluderRadiusM == o.occluderRadiusM &&
         sunRadiusM == o.sunRadiusM && sunOccluderDistanceM == o.sunOccluderDistanceM && width == o.width &&
         height == o.height && range == o.range;
}

bool AtmosphereShadowRequest::operator==(const AtmosphereShadowRequest& o) const {
  return EclipseTableRequest::operator==(o) && extent == o.extent;
}

std::optional<AtmosphereShadowRequest> sceneAtmosphereShadowRequest(const SceneInputs& in, int width, int height) {
  if (!in.atmosphere) return std::nullopt;
  AtmosphereShadowRequest r;
  static_cast<EclipseTableRequest&>(r) = tableRequest(in, width, height);
  const SphereBody& occ = atmosphereBody(in);
  std::vector<SphereBody> others;
  for (const SphereBody& b : in.bodies)
    if (b.name != occ.name) others.push_back(b);
  r.range = sceneLutRange(in.sun, {occ}, others, /*darkUmbra=*/false, height);
  r.extent = {0, 0, 0, height - 1, 0, 0};
  if (r.range) {
    r.extent[1] = rangedLutWidth(*r.range, width) - 1;  // all of the ranged table
    return r;
  }
  int first = width, last = -1;
  for (const SphereBody& b : others) {
    const auto cols = shadowLutColumns(in.sun, occluderSeenBy(occ, b), b, width);
    first = std::min(first, cols[0]);
    last = std::max(last, cols[1]);
  }
  if (last < first) return std::nullopt;  // nothing else to shade
  if (last == first) {  // at least 2 columns (a texture of >= 2x2 texels)
    if (last + 1 < width) ++last;
    else --first;
  }
  r.extent[0] = first, r.extent[1] = last;
  return r;
}

vtkAlgorithm* setUpAtmosphereShadow(vtkEclipseShadowLutSource* source, const AtmosphereShadowRequest& r) {
  return setUpTable(source, r, "shadow through the atmosphere");
}

void updateAtmosphereShadow(vtkEclipseShadowLutSource* source, const AtmosphereShadowRequest& r) {
  int extent[6];
  std::copy(r.extent.begin(), r.extent.end(), extent);
  updateTable(source, r, "shadow through the atmosphere", [&] { source->UpdateExtent(extent); },
              [](vtkImageData* lut) {
                int got[6];
                lut->GetExtent(got);
                return got[1] >= got[0] + 1 && got[3] >= got[2] + 1;
              });
}

void applySceneAtmosphereShadow(EclipseShading& shading, const SceneInputs& in, vtkEclipseShadowLutSource* source) {
  if (!source) throw std::invalid_argument("no eclipse table source for the atmosphere");
  const auto request = sceneAtmosphereShadowRequest(in, source->GetWidth(), source->GetHeight());
  if (!request) {
    shading.SetAtmosphereShadowLut("", nullptr);
    return;
  }
  updateAtmosphereShadow(source, *request);
  shading.SetAtmosphereShadowLut(request->occluder, source->GetOutput());
}

std::optional<LimbLuminanceRequest> sceneLimbLuminanceRequest(const SceneInputs& in, int width, int height,
                                                              double ringThresholdPx) {
  if (!in.atmosphere || !(ringThresholdPx > 0.0)) return std::nullopt;
  // Only a camera in the shadow, outside the atmosphere, can use it (AtmosphereRendering).
  const SphereBody& occ = atmosphereBody(in);
  const glm::dvec3 cam = in.camera.positionM;
  const auto angles = eclipse::shadowAngles(cam, in.sun.positionM, in.sun.radiusM, occ.centreM, occ.radiusM);
  const bool inShadow = eclipse::occluderInFront(cam, in.sun.positionM, occ.centreM) && eclipse::lutCoords(angles).v < 1.0;
  if (!inShadow) return std::nullopt;
  const double topM =
      in.atmosphere->topRadiusM > 0.0 ? in.atmosphere->topRadiusM : in.atmosphere->model->rgb().topRadiusM;
  if (glm::length(cam - occ.centreM) <= topM) return std::nullopt;
  LimbLuminanceRequest r;
  static_cast<EclipseTableRequest&>(r) = tableRequest(in, width, height);
  // Near the occluder (Phobos by Mars) the whole LuT's v rows are too coarse: one around
  // the camera's distance.
  r.range = pointLutRange(in.sun, occ, cam, /*darkUmbra=*/false, height);
  return r;
}

vtkAlgorithm* setUpLimbLuminance(vtkLimbLuminanceSource* source, const LimbLuminanceRequest& r) {
  return setUpTable(source, r, "limb luminance of the atmosphere");
}

void updateLimbLuminance(vtkLimbLuminanceSource* source, const LimbLuminanceRequest& r) {
  updateTable(source, r, "limb luminance of the atmosphere", [&] { source->Update(); },
              [](vtkImageData* lut) { return lut && lut->GetNumberOfPoints() > 0; });
}

void applySceneLimbLuminance(AtmosphereRendering& atmosphere, const SceneInputs& in, vtkLimbLuminanceSource* source) {
  if (!source) throw std::invalid_argument("no source for the limb luminance of the atmosphere");
  const auto request = sceneLimbLuminanceRequest(in, source->GetWidth(), source->GetHeight(),
                                                 atmosphere.GetLimbRingThresholdPixels());
  if (!request) {
    atmosphere.SetLimbLuminance(nullptr);
    return;
  }
  updateLimbLuminance(source, *request);
  atmosphere.SetLimbLuminance(source->GetOutput());
}

void useSmallEclipseShadowTables(vtkEclipseShadowLutSource* s) {
  useSmallEclipseAtmosphere(s);
  s->SetWidth(64);
  s->SetHeight(32);
  s->SetLimbSize(32);
  s->SetScatteringCells(4);
}

void useSmallLimbLuminanceTables(vtkLimbLuminanceSource* s) {
  useSmallEclipseAtmosphere(s);
  s->SetWidth(8);
  s->SetHeight(32);
  s->SetColumns(16);
  s->SetLimbRows(32);
  s->SetScatteringCells(4);
}

} // namespace umbra::pipeline
