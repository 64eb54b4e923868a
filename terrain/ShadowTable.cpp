#include "ShadowTable.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace umbra::terrain {

SunDisc roundedSun(const SunDisc& sun, double stepRad) {
  if (!(stepRad > 0.0 && stepRad <= 0.1)) throw std::invalid_argument("the Sun's rounding step must be in (0, 0.1] rad");
  const double len = glm::length(sun.direction);
  if (!(len > 0.0) || !std::isfinite(len)) throw std::invalid_argument("sun direction must be a finite non-zero vector");
  const glm::dvec3 s = sun.direction / len;
  const double elevation = std::asin(std::clamp(s.z, -1.0, 1.0)), azimuth = std::atan2(s.x, s.y);
  SunDisc out = sun;
  out.direction = sunDirectionFromElevationAzimuth(std::round(elevation / stepRad) * stepRad,
                                                   std::round(azimuth / stepRad) * stepRad);
  const double radiusStep = stepRad / 20.0;
  out.angularRadiusRad = std::max(1.0, std::round(sun.angularRadiusRad / radiusStep)) * radiusStep;
  return out;
}

double ShadowTable::farOffsetAt(glm::dvec2 g) const {
  g = glm::clamp(g, glm::dvec2(0.0), glm::dvec2(width - 1, height - 1));
  const int i = std::min(static_cast<int>(g.x), std::max(0, width - 2));
  const int j = std::min(static_cast<int>(g.y), std::max(0, height - 2));
  const int i1 = std::min(i + 1, width - 1), j1 = std::min(j + 1, height - 1);
  const double fx = g.x - i, fy = g.y - j;
  auto at = [&](int a, int b) { return double(offsets[static_cast<std::size_t>(b) * width + a]); };
  return (1.0 - fy) * ((1.0 - fx) * at(i, j) + fx * at(i1, j)) + fy * ((1.0 - fx) * at(i, j1) + fx * at(i1, j1));
}

ShadowOptions ShadowTable::nearSearch() const {
  ShadowOptions near;
  near.method = ShadowMethod::Cells;
  near.toTexels = nearTexels + 1.0;
  return near;
}

double ShadowTable::fractionAt(const HeightField& f, const MaximumMipmap& mip, glm::dvec2 g) const {
  const double far = farOffsetAt(g);
  if (far <= -1.0) return 0.0;  // the disc is behind the far horizon whatever is near: no search
  const Horizon h = horizonTowardsSunAt(f, mip, g, f.bilinear(g.x, g.y), sun, nearSearch());
  if (h.degenerate) return discFractionAboveHorizon(h, sun);
  const double d = (h.sunElevationRad - h.horizonElevationRad) / sun.angularRadiusRad;
  return discFractionForOffset(std::min(d, far), sun);
}

ShadowTable makeShadowTable(const HeightField& f, const MaximumMipmap& mip, const SunDisc& sun,
                            const ShadowOptions& options, double nearTexels,
                            const std::function<void(double)>& progress) {
  if (!(nearTexels >= 0.0 && nearTexels <= 1024.0)) throw std::invalid_argument("the near stretch must be 0..1024 texels");
  ShadowOptions o = options;
  o.windowRadii = kShadowTableOffsetLimit;  // the offsets up to the limit, not only on the disc
  o.fromTexels = std::max(nearTexels, o.fromTexels);
  const std::vector<Horizon> horizons = horizonMap(f, mip, sun, o, progress);
  ShadowTable t;
  t.width = f.width;
  t.height = f.height;
  t.sun = sun;
  t.nearTexels = nearTexels;
  t.offsets.resize(horizons.size());
  constexpr double limit = kShadowTableOffsetLimit;
  for (std::size_t k = 0; k < horizons.size(); ++k) {
    const Horizon& h = horizons[k];
    // A Sun at the zenith (nadir) is up (down) whatever the terrain; no horizon: lit.
    const double d = h.degenerate ? (h.sunElevationRad > 0.0 ? limit : -limit)
                                  : (h.sunElevationRad - h.horizonElevationRad) / sun.angularRadiusRad;
    t.offsets[k] = static_cast<float>(std::clamp(std::isnan(d) ? limit : d, -limit, limit));
  }
  return t;
}

std::string heightFieldDigest(const HeightField& f) {
  std::uint64_t hash = 1469598103934665603ull;
  auto add = [&](const void* data, std::size_t n) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < n; ++k) hash = (hash ^ bytes[k]) * 1099511628211ull;
  };
  const int size[2] = {f.width, f.height};
  const double scale[2] = {f.spacingM, f.bodyRadiusM};
  add(size, sizeof size);
  add(scale, sizeof scale);
  const double nan = std::nan("");
  for (double h : f.heightsM) add(std::isnan(h) ? &nan : &h, sizeof h);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
  return hex;
}

std::map<std::string, std::string> shadowTableKey(const HeightField& f, const SunDisc& sun, double stepRad,
                                                  const ShadowOptions& o, double nearTexels) {
  const glm::dvec3 s = glm::normalize(sun.direction);
  auto steps = [](double value, double step) { return std::to_string(std::llround(value / step)); };
  char number[32];
  auto exact = [&](double v) {
    std::snprintf(number, sizeof number, "%.17g", v);
    return std::string(number);
  };
  return {{"heights", heightFieldDigest(f)},
          {"size", std::to_string(f.width) + "x" + std::to_string(f.height)},
          {"spacingM", exact(f.spacingM)},
          {"bodyRadiusM", exact(f.bodyRadiusM)},
          {"sunStepRad", exact(stepRad)},
          {"sunElevationSteps", steps(std::asin(std::clamp(s.z, -1.0, 1.0)), stepRad)},
          {"sunAzimuthSteps", steps(std::atan2(s.x, s.y), stepRad)},
          {"sunRadiusSteps", steps(sun.angularRadiusRad, stepRad / 20.0)},
          {"limbDarkening", exact(sun.limbDarkening)},
          {"method", shadowMethodName(o.method)},
          {"levels", std::to_string(o.levels)},
          {"uniformSteps", std::to_string(o.uniformSteps)},
          {"offsetLimit", exact(kShadowTableOffsetLimit)},
          {"nearTexels", exact(nearTexels)},
          {"quantity", "the Sun's centre above the horizon, solar radii"}};
}

} // namespace umbra::terrain
