#include "SolarDisc.hpp"

#include <boost/math/quadrature/tanh_sinh.hpp>

#include <algorithm>
#include <cmath>

namespace umbra::eclipse {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Area of the cap of a circle of radius r cut off by a chord whose sagitta (cap height)
/// is h in [0, 2r]: r^2 (a - sin(a) cos(a)) with a the half angle at the centre. For thin
/// caps x - sin(x) is summed as a series to avoid cancellation.
double capArea(double r, double h) {
  h = std::clamp(h, 0.0, 2.0 * r);
  const double a = 2.0 * std::asin(std::sqrt(h / (2.0 * r)));
  const double x = 2.0 * a;  // area = r^2/2 (x - sin x)
  double xMinusSin;
  if (x < 1e-2) {
    const double x2 = x * x;
    xMinusSin = x * x2 / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0 * (1.0 - x2 / 72.0)));
  } else {
    xMinusSin = x - std::sin(x);
  }
  return 0.5 * r * r * xMinusSin;
}

/// The three cap heights of a partial overlap, from e = separation - occluderRadius so
/// that the small differences are formed once, exactly.
struct Caps {
  double sunNear;   // sagitta of the solar cap on the occluder's side (hidden part's arc)
  double sunFar;    // sagitta of the solar cap on the far side (2 - sunNear)
  double occluder;  // sagitta of the occluder cap inside the solar disc
};

Caps capsOf(double R, double d) {
  const double e = d - R;
  return {(1.0 - e) * (R + d - 1.0) / (2.0 * d), (1.0 + e) * (d + 1.0 + R) / (2.0 * d),
          (1.0 - e) * (1.0 + e) / (2.0 * d)};
}

} // namespace

double limbDarkenedLuminance(double rho, double u) { return limbDarkenedLuminanceAtSquare(rho * rho, u); }

double limbDarkenedFluxInside(double rho, double u) {
  rho = std::clamp(rho, 0.0, 1.0);
  // integral_0^rho 2 rho' L(rho') d rho' in closed form, divided by the disc's flux.
  const double s = 1.0 - rho * rho;
  const double ring = (1.0 - u) * rho * rho + (2.0 / 3.0) * u * (1.0 - s * std::sqrt(s));
  return ring / (1.0 - u / 3.0);
}

double discOverlapArea(double R, double d) {
  if (d >= 1.0 + R) return 0.0;
  if (d <= std::abs(R - 1.0)) return kPi * std::min(1.0, R) * std::min(1.0, R);
  const Caps c = capsOf(R, d);
  return capArea(1.0, c.sunNear) + capArea(R, c.occluder);
}

double visibleFractionUniform(double R, double d) {
  if (d >= 1.0 + R) return 1.0;
  if (d <= R - 1.0) return 0.0;                        // total eclipse
  if (d <= 1.0 - R) return 1.0 - R * R;                // annular: occluder inside the disc
  const Caps c = capsOf(R, d);
  if (c.sunNear <= 1.0) return 1.0 - (capArea(1.0, c.sunNear) + capArea(R, c.occluder)) / kPi;
  // More than half hidden: the visible crescent is the far cap minus the occluder cap.
  return std::max(0.0, capArea(1.0, c.sunFar) - capArea(R, c.occluder)) / kPi;
}

QuadratureResult visibleFractionLimbDarkened(double R, double d, double u, double tol) {
  if (d >= 1.0 + R) return {1.0, 0.0, 0};
  if (d <= R - 1.0) return {0.0, 0.0, 0};
  if (d == 0.0) return {1.0 - limbDarkenedFluxInside(R, u), 0.0, 0};

  // A ring of radius rho about the Sun's centre lies inside the occluder over the arc
  // where cos(theta) >= c(rho); its hidden angle is 2 acos(c).
  const double dMinusR = d - R, dPlusR = d + R;
  auto hiddenAngle = [&](double rho) {
    const double c = (rho * rho + dMinusR * dPlusR) / (2.0 * rho * d);
    return c <= -1.0 ? 2.0 * kPi : (c >= 1.0 ? 0.0 : 2.0 * std::acos(c));
  };
  // Rings below rhoStart are hidden whole (occluder over the centre) or untouched,
  // rings beyond rhoEnd are untouched; only [rhoStart, rhoEnd] needs the quadrature.
  const double rhoStart = std::abs(dMinusR);
  const double rhoEnd = std::min(1.0, dPlusR);
  const double inner = limbDarkenedFluxInside(rhoStart, u);
  const double hiddenInner = dMinusR < 0.0 ? inner : 0.0;
  const double visibleInner = dMinusR < 0.0 ? 0.0 : inner;

  // Integrate the smaller side (judged by the uniform disc) over the partial rings;
  // flux fraction = (1/pi) integral L(rho) rho angle(rho) d rho, since L has mean 1.
  const bool integrateVisible = visibleFractionUniform(R, d) < 0.5;
  auto integrand = [&](double rho) {
    const double angle = hiddenAngle(rho);
    return limbDarkenedLuminance(rho, u) * rho * (integrateVisible ? 2.0 * kPi - angle : angle);
  };
  double partial = 0.0, err = 0.0, l1 = 0.0;
  std::size_t levels = 0;
  if (rhoEnd > rhoStart) {
    boost::math::quadrature::tanh_sinh<double> integrator(15);
    partial = integrator.integrate(integrand, rhoStart, rhoEnd, tol, &err, &l1, &levels) / kPi;
    err /= kPi;
  }
  const double visible = integrateVisible
      ? visibleInner + partial + (1.0 - limbDarkenedFluxInside(rhoEnd, u))
      : 1.0 - hiddenInner - partial;
  return {std::clamp(visible, 0.0, 1.0), err, static_cast<int>(levels)};
}

namespace {
/// Flux fraction of the cap of sagitta h in [0, 1] of the limb-darkened unit disc: the
/// chords y in [1 - h, 1] integrate to (1-u) capArea + u (pi/2) (h^2 - h^3/3).
double limbDarkenedCapFraction(double h, double u) {
  return ((1.0 - u) * capArea(1.0, h) + 0.5 * kPi * u * h * h * (1.0 - h / 3.0)) / (kPi * (1.0 - u / 3.0));
}
} // namespace

double visibleFractionAboveHorizon(double d) { return visibleFractionAboveHorizonLimbDarkened(d, 0.0); }

double visibleFractionAboveHorizonLimbDarkened(double d, double u) {
  if (!(d > -1.0)) return 0.0;  // NaN reads as hidden
  if (d >= 1.0) return 1.0;
  // The visible cap has sagitta 1 + d; for more than half, 1 - the hidden cap.
  return d <= 0.0 ? limbDarkenedCapFraction(1.0 + d, u) : 1.0 - limbDarkenedCapFraction(1.0 - d, u);
}

} // namespace umbra::eclipse
