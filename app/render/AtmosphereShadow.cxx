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

namespace umbra::render {
namespace {
// Eq. 4's u for the given distances to the occluder and the Sun.
double lutU(double sunRadiusM, double sunDistanceM, double occRadiusM, double occDistanceM) {
  const double phiSun = eclipse::angularRadiusRad(sunRadiusM, sunDistanceM);
  const double phiOcc = eclipse::angularRadiusRad(occRadiusM, occDistanceM);
  return phiSun / (phiOcc + phiSun);
}

// The body with the scene's atmosphere, and `source` set up for it (bodies, Sun, model).
const SphereBody& setUpFor(vtkEclipseAtmosphereSource* source, const SceneInputs& in) {
  if (!source) throw std::invalid_argument("no eclipse table source for the atmosphere");
  const auto occ = std::find_if(in.bodies.begin(), in.bodies.end(),
                                [&](const SphereBody& b) { return b.name == in.atmosphere->body; });
  if (occ == in.bodies.end()) throw std::invalid_argument("atmosphere of '" + in.atmosphere->body + "': no such body");
  source->SetOccluderName(occ->name.c_str());
  source->SetOccluderRadiusM(occ->radiusM);
  source->SetSunRadiusM(in.sun.radiusM);
  source->SetSunOccluderDistanceM(glm::length(occ->centreM - in.sun.positionM));
  source->SetAtmosphere(in.atmosphere->model.c_str());
  return *occ;
}

// The tables of the atmosphere shared by the small shadow and limb-luminance LuTs.
void useSmallEclipseAtmosphere(vtkEclipseAtmosphereSource* s) {
  s->SetOrders(2);
  s->SetTransmittanceSize(64, 16);
  s->SetScatteringSize(8, 32, 8, 4);
  s->SetIrradianceSize(16, 4);
  s->SetRefractionSize(128, 64);
}
} // namespace

std::array<int, 2> shadowLutColumns(const SunLight& sun, const SphereBody& occluder, const SphereBody& receiver,
                                    int width) {
  validateSun(sun);
  validateBody(occluder);
  validateBody(receiver);
  if (width < 1) throw std::invalid_argument("shadow LuT width must be >= 1");
  const double dOcc = glm::length(receiver.centreM - occluder.centreM);
  const double dSun = glm::length(receiver.centreM - sun.positionM);
  const double r = receiver.radiusM;
  const double uMin = lutU(sun.radiusM, dSun + r, occluder.radiusM, std::max(dOcc - r, 0.0));
  const double uMax = lutU(sun.radiusM, std::max(dSun - r, sun.radiusM), occluder.radiusM, dOcc + r);
  // Texel i's centre is at (i + 0.5) / width; a lookup at u reads floor(u w - 0.5) and the next.
  const int first = static_cast<int>(std::floor(uMin * width - 0.5));
  const int last = static_cast<int>(std::floor(uMax * width - 0.5)) + 1;
  return {std::clamp(first, 0, width - 1), std::clamp(last, 0, width - 1)};
}

void applySceneAtmosphereShadow(EclipseShading& shading, const SceneInputs& in, vtkEclipseShadowLutSource* source) {
  if (!in.atmosphere) {
    shading.SetAtmosphereShadowLut("", nullptr);
    return;
  }
  const SphereBody* occ = &setUpFor(source, in);
  int first = source->GetWidth(), last = -1;
  for (const SphereBody& b : in.bodies) {
    if (b.name == occ->name) continue;
    const auto cols = shadowLutColumns(in.sun, *occ, b, source->GetWidth());
    first = std::min(first, cols[0]);
    last = std::max(last, cols[1]);
  }
  if (last < first) {  // nothing else to shade
    shading.SetAtmosphereShadowLut("", nullptr);
    return;
  }
  if (last == first) {  // at least 2 columns (a texture of >= 2x2 texels)
    if (last + 1 < source->GetWidth()) ++last;
    else --first;
  }
  const int extent[6] = {first, last, 0, source->GetHeight() - 1, 0, 0};
  try {
    source->ConnectAtmosphereTables();  // the atmosphere tables from their cache
    source->UpdateExtent(extent);
  } catch (const std::exception& e) {
    throw std::runtime_error("shadow through the atmosphere of '" + occ->name + "': " + e.what());
  }
  vtkImageData* lut = source->GetOutput();
  int got[6];
  lut->GetExtent(got);
  if (got[1] < got[0] + 1 || got[3] < got[2] + 1) {
    throw std::runtime_error("shadow through the atmosphere of '" + occ->name + "': the table could not be made");
  }
  shading.SetAtmosphereShadowLut(occ->name, lut);
}

void applySceneLimbLuminance(AtmosphereRendering& atmosphere, const SceneInputs& in, vtkLimbLuminanceSource* source) {
  if (!in.atmosphere) {
    atmosphere.SetLimbLuminance(nullptr);
    return;
  }
  // Only a camera in the shadow, outside the atmosphere, can use it (AtmosphereRendering).
  const SphereBody& body = *std::find_if(in.bodies.begin(), in.bodies.end(),
                                         [&](const SphereBody& b) { return b.name == in.atmosphere->body; });
  const double topM =
      atmosphere::loadAtmosphere(in.atmosphere->model, atmosphere::WavelengthSet::rgb().nm).topRadiusM;
  const glm::dvec3 cam = in.camera.positionM;
  const bool inShadow =
      eclipse::occluderInFront(cam, in.sun.positionM, body.centreM) &&
      eclipse::lutCoords(eclipse::shadowAngles(cam, in.sun.positionM, in.sun.radiusM, body.centreM, body.radiusM)).v < 1.0;
  if (glm::length(cam - body.centreM) <= topM || !inShadow) {
    atmosphere.SetLimbLuminance(nullptr);
    return;
  }
  const SphereBody& occ = setUpFor(source, in);
  try {
    source->ConnectAtmosphereTables();
    source->Update();
  } catch (const std::exception& e) {
    throw std::runtime_error("limb luminance of the atmosphere of '" + occ.name + "': " + e.what());
  }
  vtkImageData* lut = source->GetOutput();
  if (!lut || lut->GetNumberOfPoints() == 0)
    throw std::runtime_error("limb luminance of the atmosphere of '" + occ.name + "': the table could not be made");
  atmosphere.SetLimbLuminance(lut);
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
  s->SetHeight(8);
  s->SetColumns(16);
  s->SetLimbRows(32);
  s->SetScatteringCells(4);
}

} // namespace umbra::render
