#pragma once
// Shared scenes and helpers of the rendering tests.
#include "BodyView.h"
#include "ShadowLut.hpp"
#include "ShadowLutData.h"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <vtkImageData.h>
#include <vtkRenderWindow.h>
#include <vtkSmartPointer.h>

#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace umbra::render::test {

constexpr double kAu = 1.495978707e11;
constexpr double kPi = 3.14159265358979323846;
constexpr double kEarthRadius = 6.371e6;
constexpr double kMoonDistance = 3.844e8;

/// One X connection for every window of the test process, opened once (with retries).
/// Each VTK window otherwise opens its own; under `xvfb-run -a` on a machine where other
/// jobs start and stop X servers too, a later connection to the same display can fail
/// ("bad X server connection") while an open one keeps working. (RenderTestSupport.cpp)
void useSharedDisplay(vtkRenderWindow* window);

/// Writes an 8-bit RGB equirectangular PNG of width x height texels (row 0 southernmost, as
/// the maps lie: sky/AlbedoMap.hpp) into a temporary folder of the process, texel(i, j)
/// giving each one's RGB in 0..1 (clamped), and returns its path.
std::string writeRgbPng(int width, int height, const std::function<glm::dvec3(int, int)>& texel,
                        const std::string& name);

/// `view` rendered from `camera` at exposure 0: its linear radiance, 3 floats a pixel, row 0
/// at the top (BodyView::ReadHdr).
inline std::vector<float> renderHdr(BodyView& view, const ViewCamera& camera) {
  view.SetCamera(camera);
  view.SetExposureEV(0.0);
  view.Render();
  std::vector<float> hdr;
  int w = 0, h = 0;
  view.ReadHdr(hdr, w, h);
  return hdr;
}

/// The 64x64 airless LuT of the tests (built once).
inline const eclipse::ShadowLut& testLut() {
  static const eclipse::ShadowLut lut = eclipse::buildAirlessShadowLut({64, 64});
  return lut;
}
inline vtkSmartPointer<vtkImageData> testLutImage() { return umbra::filters::toImageData(testLut()); }

/// The view ray through the centre of pixel (i, j), j counted from the top row, as
/// vtkCamera builds it (right = view x up, vertical field of view).
struct Ray {
  glm::dvec3 origin, dir;
};
inline Ray pixelRay(const ViewCamera& c, int width, int height, int i, int j) {
  const glm::dvec3 fwd = glm::normalize(c.targetM - c.positionM);
  const glm::dvec3 right = glm::normalize(glm::cross(fwd, c.up));
  const glm::dvec3 up = glm::cross(right, fwd);
  const double aspect = double(width) / height;
  const double x = (i + 0.5) / width * 2.0 - 1.0;
  const double y = 1.0 - (j + 0.5) / height * 2.0;
  if (c.parallel) {
    return {c.positionM + x * c.parallelScaleM * aspect * right + y * c.parallelScaleM * up, fwd};
  }
  const double t = std::tan(0.5 * c.fovDeg * kPi / 180.0);
  return {c.positionM, glm::normalize(fwd + x * t * aspect * right + y * t * up)};
}

/// First intersection of a ray with a sphere (double precision).
inline std::optional<glm::dvec3> hitSphere(const Ray& r, const glm::dvec3& centre, double radius) {
  const glm::dvec3 oc = r.origin - centre;
  const double b = glm::dot(oc, r.dir);
  const glm::dvec3 perp = oc - b * r.dir;
  const double h2 = glm::dot(perp, perp);
  if (h2 > radius * radius) return std::nullopt;
  const double t = -b - std::sqrt(radius * radius - h2);
  return r.origin + t * r.dir;
}

/// Unshadowed Lambertian radiance of a sphere point lit by the Sun (W m^-2 sr^-1), and cos i.
inline double unshadowedRadiance(const glm::dvec3& p, const glm::dvec3& centre, double albedo,
                                 const SunLight& sun, double* cosOut = nullptr) {
  const glm::dvec3 n = glm::normalize(p - centre);
  const glm::dvec3 toSun = sun.positionM - p;
  const double d = glm::length(toSun);
  const double cosi = std::max(0.0, glm::dot(n, toSun / d));
  if (cosOut) *cosOut = cosi;
  const double e = sun.irradianceAt1AuWm2 * (kAu / d) * (kAu / d);
  return albedo / kPi * e * cosi;
}

} // namespace umbra::render::test
