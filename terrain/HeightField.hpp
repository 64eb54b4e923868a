#pragma once
// A height field on a sphere, sampled on a gnomonic (central-projection) tangent-plane grid,
// the geometry of the terrain paper's texture plane (section 3.2: R_tex = R_xy / R_z).
//
// Frame ("tangent frame"): origin at the body's centre, z through the tangent point at
// the middle of the grid, x along increasing column index i (east for a north-up DEM),
// y along increasing row index j (north). Sample (i, j) lies on the plane z = R at
// x = (i - (W-1)/2) * spacing, y = (j - (H-1)/2) * spacing; its surface point is
// (R + h(i, j)) times the unit vector towards that plane point. Straight lines of the grid
// are great circles, so a shadow ray's footprint on the grid is a straight line.
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace umbra::terrain {

/// Mean radius of the Moon [m] (IAU WGCCRE).
inline constexpr double kMoonRadiusM = 1737.4e3;

struct HeightField {
  int width = 0;               ///< samples along x (columns i)
  int height = 0;              ///< samples along y (rows j)
  double spacingM = 30.0;      ///< sample spacing on the tangent plane [m]
  double bodyRadiusM = kMoonRadiusM;
  std::vector<double> heightsM;  ///< row-major (j * width + i), above the sphere [m]; NaN = no data

  /// Throws std::invalid_argument with a one-line reason if the field cannot be used
  /// (fewer than 2 x 2 samples, spacing or radius not positive, +-inf heights, no valid sample).
  void validate() const;

  double at(int i, int j) const { return heightsM[static_cast<std::size_t>(j) * width + i]; }
  bool valid(int i, int j) const { return !std::isnan(at(i, j)); }

  /// Tangent-plane position [m] of grid coordinates (gx, gy) (sample units, may be fractional).
  glm::dvec2 planeM(double gx, double gy) const {
    return {(gx - 0.5 * (width - 1)) * spacingM, (gy - 0.5 * (height - 1)) * spacingM};
  }
  /// Unit vector from the body's centre through grid coordinates (gx, gy).
  glm::dvec3 direction(double gx, double gy) const {
    const glm::dvec2 p = planeM(gx, gy);
    return glm::normalize(glm::dvec3(p.x, p.y, bodyRadiusM));
  }
  /// Bilinear height at grid coordinates, clamped to the grid; no-data corners are left
  /// out (weights renormalised); NaN when all four are no data. (Inline: the searches'
  /// inner loops; no data goes to bilinearOverNoData.)
  double bilinear(double gx, double gy) const {
    gx = std::clamp(gx, 0.0, width - 1.0);
    gy = std::clamp(gy, 0.0, height - 1.0);
    const int i = std::min(static_cast<int>(gx), width - 2), j = std::min(static_cast<int>(gy), height - 2);
    const double fx = gx - i, fy = gy - j;
    const double* r0 = &heightsM[static_cast<std::size_t>(j) * width + i];
    const double* r1 = r0 + width;
    const double v = (1.0 - fy) * ((1.0 - fx) * r0[0] + fx * r0[1]) + fy * ((1.0 - fx) * r1[0] + fx * r1[1]);
    return std::isnan(v) ? bilinearOverNoData(i, j, fx, fy) : v;
  }
  /// bilinear in cell (i, j) at (fx, fy) when a corner has no data.
  double bilinearOverNoData(int i, int j, double fx, double fy) const;

  /// Height to put a receiver at sample (i, j): its own, or for a no-data sample the mean
  /// of its valid 3 x 3 neighbours, else the lowest valid height of the field.
  double receiverHeight(int i, int j) const;
  double minValidHeight() const;
};

/// Direction towards the Sun in the tangent frame from its elevation above the tangent
/// plane and its azimuth from +y (north) towards +x (east), both in radians.
glm::dvec3 sunDirectionFromElevationAzimuth(double elevationRad, double azimuthRad);

/// Rotation from body-fixed coordinates (z = north pole, x = prime meridian) to the
/// tangent frame of a grid centred at planetocentric (latitude, longitude): x east,
/// y north, z up. At a pole (|lat| = 90 deg) "north" is taken as the direction of the
/// meridian lonDeg + 180 (lonDeg) at the north (south) pole, the polar-stereographic
/// convention of a DEM whose +y axis points along that meridian.
glm::dmat3 bodyFixedToTangent(double latitudeDeg, double longitudeDeg);

} // namespace umbra::terrain
