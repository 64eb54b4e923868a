#pragma once
// Shared atmosphere of the rendering tests: Earth's preset at 3 wavelengths with small
// tables (made once per test process by vtkAtmosphereTablesSource, no cache), and a
// BodyView showing Earth (at the origin) with it, the Sun 1 au away.
#include "AtmosphereRendering.h"
#include "AtmosphereTablesBlocks.h"
#include "RenderTestSupport.hpp"
#include "SceneInputs.h"

#include "Spectrum.hpp"
#include "vtkAtmosphereTablesSource.h"

#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <stdexcept>

namespace umbra::render::test {

/// Solar irradiance at the planet (the Sun exactly 1 au from its centre), W m^-2.
inline constexpr double kSolarIrradiance = 1361.0;

struct AtmosphereFixture {
  atmosphere::Atmosphere model;
  atmosphere::AtmosphereTables tables;
};

inline const AtmosphereFixture& atmosphereFixture() {
  static const AtmosphereFixture f = [] {
    vtkNew<vtkAtmosphereTablesSource> source;
    source->SetAtmosphere("earth");
    pipeline::useSmallAtmosphereTables(source);
    source->UseCacheOff();
    source->Update();
    if (!source->GetLastError().empty()) throw std::runtime_error(source->GetLastError());
    AtmosphereFixture out;
    out.model = atmosphere::loadAtmosphere("earth", atmosphere::WavelengthSet::rgb().nm);
    out.tables = umbra::filters::tablesFromBlocks(source->GetOutput(), out.model);
    return out;
  }();
  return f;
}

/// Unit vector elevationDeg above the xy plane, azimuthDeg from +x towards +y.
inline glm::dvec3 directionFromAngles(double elevationDeg, double azimuthDeg) {
  const double e = elevationDeg * kPi / 180.0, a = azimuthDeg * kPi / 180.0;
  return {std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
}

/// A camera altitudeM above the north pole of the fixture's planet, looking towards +x,
/// elevationDeg above the horizontal.
inline ViewCamera groundCamera(double altitudeM, double elevationDeg, double fovDeg) {
  ViewCamera cam;
  cam.positionM = {0.0, 0.0, atmosphereFixture().tables.bottomRadiusM + altitudeM};
  cam.targetM = cam.positionM + directionFromAngles(elevationDeg, 0.0);
  cam.up = {0.0, 0.0, 1.0};
  cam.fovDeg = fovDeg;
  return cam;
}

/// Earth (ground albedo 0.1, grey) with its atmosphere, the Sun 1 au away along sunDir.
struct AtmosphereScene {
  BodyView view;
  SunLight sun;
  SphereBody earth;

  AtmosphereScene(int size, const ViewCamera& camera, const glm::dvec3& sunDir, bool withAtmosphere = true)
      : view(size, size, true) {
    useSharedDisplay(view.GetRenderWindow());
    const AtmosphereFixture& f = atmosphereFixture();
    sun.positionM = glm::normalize(sunDir) * kAu;
    earth = {"Earth", {0.0, 0.0, 0.0}, f.tables.bottomRadiusM, {0.1, 0.1, 0.1}};
    view.SetBodies(sun, {earth}, testLutImage());
    if (withAtmosphere) view.GetAtmosphere().SetAtmosphere(f.model, f.tables, earth.centreM, earth.albedoRgb);
    view.SetCamera(camera);
    view.SetExposureEV(0.0);
  }
};

} // namespace umbra::render::test
