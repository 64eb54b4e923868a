#pragma once
// Small height fields for the terrain tests.
#include "HeightField.hpp"
#include "MaximumMipmap.hpp"
#include "SoftShadow.hpp"

#include <cmath>

namespace umbra::test {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kDeg = kPi / 180.0;

/// Bare sphere of the Moon's radius: every height 0.
inline terrain::HeightField flatField(int size, double spacingM = 30.0) {
  terrain::HeightField f;
  f.width = f.height = size;
  f.spacingM = spacingM;
  f.heightsM.assign(static_cast<std::size_t>(size) * size, 0.0);
  return f;
}

/// The circular segment of a unit disc above a chord d radii below its centre, as a
/// fraction of the disc (textbook form, written independently of eclipse/).
inline double segmentFraction(double d) {
  if (d >= 1.0) return 1.0;
  if (d <= -1.0) return 0.0;
  return (kPi - std::acos(d) + d * std::sqrt(1.0 - d * d)) / kPi;
}

/// The Sun's elevation at receiver (i, j) of the field (its own horizontal).
inline double localElevation(const terrain::HeightField& f, int i, int j, const glm::dvec3& sun) {
  return std::asin(glm::dot(glm::normalize(sun), f.direction(i, j)));
}

/// The Sun at an elevation and azimuth (degrees) of the tangent frame, 1 au away.
inline terrain::SunDisc sunAt(double elevationDeg, double azimuthDeg) {
  terrain::SunDisc s;
  s.direction = terrain::sunDirectionFromElevationAzimuth(elevationDeg * kDeg, azimuthDeg * kDeg);
  return s;
}

inline terrain::ShadowOptions method(terrain::ShadowMethod m) {
  terrain::ShadowOptions o;
  o.method = m;
  return o;
}

} // namespace umbra::test
