#pragma once
// Astronomical refraction (eclipse paper, section 4.1; atmospheres paper, section 4.4):
// n - 1 proportional to the molecular density, rays traced through a spherically
// symmetric atmosphere with the path length s as the integration variable, the ray
// equation d/ds (n t) = grad n integrated with classical RK4 at a fixed step (10 km by
// default, [SGGC04, MP11]); Bouguer's invariant n r sin(z) holds along every ray. Rays
// that reach the ground continue through it in a straight line (constant n, the ground's).
// The table stores the deviation Delta-theta and the contact altitude ("contact radius",
// negative = the ray is blocked by the planet) in the transmittance parametrisation of
// Eq. 2 (TextureCoords.hpp), as in Figure 6.
#include "TableSizes.hpp"
#include "TextureCoords.hpp"

#include <functional>
#include <vector>

namespace umbra::atmosphere {

/// A spherically symmetric refracting atmosphere.
struct RefractiveMedium {
  double bottomRadiusM = 0.0;
  double topRadiusM = 0.0;
  /// n - 1 (>= 0) at an altitude above the bottom radius, e.g. 2.77e-4 exp(-h / 8 km).
  /// Called for altitudes in [0, top - bottom] only; outside the shell n is held at its
  /// value on the nearest boundary (constant n under ground, nothing changes above the top).
  std::function<double(double altitudeM)> refractivity;
  /// d(n - 1)/dh in 1/m. Optional: when empty it is differentiated numerically (fourth-
  /// order differences, 10 m apart, one-sided at the boundaries).
  std::function<double(double altitudeM)> refractivityDerivativePerM;

  ShellRadii shell() const { return {bottomRadiusM, topRadiusM}; }
  /// n at a radius (clamped to the shell).
  double refractiveIndex(double radiusM) const;
  /// dn/dr at a radius in [bottom, top] (one-sided at the ends); 0 outside.
  double refractiveIndexGradientPerM(double radiusM) const;
};

/// n - 1 = surfaceRefractivity * exp(-h / scaleHeightM), with its exact derivative.
/// Earth: 2.77e-4 (n = 1.000277 at sea level, eclipse paper 4.1), about 8 km; Mars:
/// 3.38e-6, about 11.1 km.
RefractiveMedium exponentialRefractiveMedium(double bottomRadiusM, double topRadiusM,
                                             double surfaceRefractivity, double scaleHeightM);

/// The same medium with n - 1 multiplied by `factor` (e.g. a dispersion ratio).
RefractiveMedium scaledRefractiveMedium(const RefractiveMedium& medium, double factor);

/// n - 1 of standard dry air (15 degC, 101 325 Pa, 300 ppm CO2) at a vacuum wavelength,
/// Edlen's 1966 dispersion formula (Metrologia 2, 71):
/// (n - 1) 1e8 = 8342.13 + 2406030 / (130 - s^2) + 15997 / (38.9 - s^2), s in 1/um.
/// 2.7714e-4 at 589 nm; use the ratio of two wavelengths to add dispersion to a medium.
double edlenStandardAirRefractivity(double wavelengthM);

/// A point on a traced ray, in the ray's plane: the planet's centre at the origin, the
/// start (or, from far away, the entry into the atmosphere) at (0, r), first heading
/// towards +x.
struct RayPoint {
  double xM = 0.0, yM = 0.0;      ///< position
  double dirX = 0.0, dirY = 0.0;  ///< unit tangent
  double pathLengthM = 0.0;       ///< from the start of the integration (the entry point from far away)
  bool underGround = false;       ///< the end of a straight chord through the ground
};

/// Bouguer's invariant n(r) r sin(z) = n(|p|) |p x t| at a ray point, in metres.
double bouguerInvariantM(const RefractiveMedium& medium, const RayPoint& point);

/// One ray traced from its origin all the way to the end of the atmosphere.
struct RayPath {
  /// Angle between the initial and the final direction, positive towards the planet.
  double deviationRad = 0.0;
  /// Minimum altitude (r - bottom) along the path from the origin to the end;
  /// negative: the ray went under ground (where it continued with constant n).
  double contactAltitudeM = 0.0;
  bool hitGround = false;
  /// Cosine of the zenith angle of the final direction at the exit point (r = top).
  double exitMu = 1.0;
  /// Angle at the planet's centre between the origin (entry point from above the top)
  /// and the exit point.
  double centralAngleRad = 0.0;
  /// Length of the path inside the shell, the straight chords under ground included.
  double pathLengthM = 0.0;
  int steps = 0;           ///< RK4 steps taken (partial steps at boundaries included)
  bool completed = true;   ///< false: stopped after the step limit (a ducted ray)
};

using SegmentCallback = std::function<void(double altitudeM, double lengthM)>;

struct TraceOptions {
  double stepM = 10e3;  ///< the fixed RK4 step
  /// Called for each piece of the path inside the atmosphere, with the altitude at the
  /// piece's midpoint (from the cubic Hermite interpolant of r^2 over the step) and the
  /// piece's length, so that optical depth can be integrated along the refracted path.
  /// Straight chords under ground are reported once, at altitude 0 (the medium there is
  /// the ground's, as for n).
  SegmentCallback segment;
  /// Each RK4 step is reported as this many equal pieces (midpoint rule per piece).
  int segmentsPerStep = 1;
  /// Called at the start, after every step, at the entry and exit of the ground and at
  /// the exit of the atmosphere.
  std::function<void(const RayPoint&)> point;
  /// Stop after this many steps (0: 4 pi top / step + 64, enough for any ray that is not
  /// ducted; RayPath::completed says when it was reached).
  int maxSteps = 0;
};

/// Trace a ray that starts at radius r (clamped to >= bottom; above the top it first
/// travels straight to the top, or misses the atmosphere) with view-zenith cosine mu.
/// Always finite: grazing rays, mu = 0 on the ground, r = top and r = 1e11 m included.
RayPath traceRay(const RefractiveMedium& medium, double radiusM, double mu,
                 const TraceOptions& options);
RayPath traceRay(const RefractiveMedium& medium, double radiusM, double mu, double stepM = 10e3,
                 const SegmentCallback& segment = {});

/// A looked-up (or traced) deviation and contact altitude.
struct RefractionSample {
  double deviationRad = 0.0;
  double contactAltitudeM = 0.0;
  bool hitsGround() const { return contactAltitudeM < 0.0; }
};

/// The deviation / contact table of Figure 6. Texel (x, y) holds the ray at
/// x_mu = x / (width - 1), x_r = y / (height - 1) (Eq. 2, texel centres on the ends), stored
/// row by row: index y * width + x, 32-bit floats as in the paper.
///
/// Which rays: like Bruneton's transmittance texture, whose by-product it is (4.1),
/// every observer inside the atmosphere (ground to top) and every view direction from the
/// zenith down to the geometric horizon. Rays below the geometric horizon are not stored:
/// refraction bends rays towards the planet, so they all hit the ground (their contact
/// comes from the straight line, see sample()). Rays near x_mu = 1 are bent into the
/// ground and have negative contact altitudes; the table still holds their deviation,
/// traced through the ground with constant n, so that it has no discontinuities.
/// Observers above the top use the point where their ray enters the atmosphere.
struct RefractionTable {
  int width = kDefaultTableSizes.refraction[0];
  int height = kDefaultTableSizes.refraction[1];
  double bottomRadiusM = 0.0;
  double topRadiusM = 0.0;
  double stepM = 10e3;
  std::vector<float> deviationRad;
  std::vector<float> contactAltitudeM;
  /// Rows below it were not traced (their texels are 0): a table of the top rows answers the
  /// lookups from the top of the atmosphere (r = topRadiusM needs rows height - 2 and
  /// height - 1), and sample() refuses the others.
  int firstRow = 0;

  ShellRadii shell() const { return {bottomRadiusM, topRadiusM}; }
  std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width + x; }
  /// The ray of texel (x, y).
  RadiusMu texelRay(int x, int y) const { return rMuAtTexel(shell(), x, y, width, height); }
  /// Bilinear lookup between texel centres (which lie on the ends of the ranges). The
  /// deviation is interpolated as Delta-theta / sin(z) and multiplied back: it grows like
  /// tan(z) ~ sqrt(x_mu) near the zenith, where plain bilinear filtering of Delta-theta (a
  /// GPU sampler's) underestimates it, by up to ~5" above 78 deg elevation at 512 columns.
  /// Above the top the ray's entry point is used (a ray that misses: deviation 0, contact
  /// from the straight line); below the horizon the horizon's deviation and the smaller of
  /// the horizon's contact and the straight line's.
  RefractionSample sample(double radiusM, double mu) const;
};

/// Build the table (OpenMP over rows), rows firstRow .. height - 1 of it (0: all; the rows
/// traced are the whole table's, to the bit). `progress` gets the fraction done, from the
/// calling thread only. Throws std::invalid_argument for sizes < 2, a step <= 0, radii
/// with top <= bottom, a medium without refractivity or firstRow outside 0 .. height - 2.
RefractionTable buildRefractionTable(const RefractiveMedium& medium, int width = kDefaultTableSizes.refraction[0],
                                     int height = kDefaultTableSizes.refraction[1], double stepM = 10e3,
                                     const std::function<void(double fraction)>& progress = {},
                                     int firstRow = 0);

} // namespace umbra::atmosphere
