#include "Profiles.hpp"

#include "Quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace umbra::atmosphere {

namespace {

std::string number(double x) {
  std::ostringstream out;
  out.precision(10);
  out << x;
  return out.str();
}

/// Piecewise-linear function through (x[i], y[i]), zero outside [x.front(), x.back()].
double piecewiseLinearAt(const std::vector<double>& x, const std::vector<double>& y, double t) {
  if (x.empty() || !(t >= x.front()) || !(t <= x.back())) return 0.0;
  const auto upper = std::upper_bound(x.begin(), x.end(), t);
  if (upper == x.end()) return y.back();  // t == x.back()
  const std::size_t i = static_cast<std::size_t>(upper - x.begin());
  if (i == 0) return y.front();
  const double f = (t - x[i - 1]) / (x[i] - x[i - 1]);
  return y[i - 1] + f * (y[i] - y[i - 1]);
}

/// Exact integral of the piecewise-linear function over [a, b], a <= b.
double piecewiseLinearIntegral(const std::vector<double>& x, const std::vector<double>& y,
                               double a, double b) {
  if (x.size() < 2) return 0.0;
  a = std::max(a, x.front());
  b = std::min(b, x.back());
  if (!(b > a)) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    const double lo = std::max(a, x[i]), hi = std::min(b, x[i + 1]);
    if (!(hi > lo)) continue;
    sum += 0.5 * (hi - lo) * (piecewiseLinearAt(x, y, lo) + piecewiseLinearAt(x, y, hi));
  }
  return sum;
}

/// int_a^b exp(-(h - base) / H) dh, a <= b, written to keep thin layers accurate.
double exponentialIntegral(double base, double H, double a, double b) {
  return -H * std::exp(-(a - base) / H) * std::expm1(-(b - a) / H);
}

/// E1(x) = int_x^inf e^-t / t dt for x > 0.
double exponentialIntegralE1(double x) {
  if (x > 700.0) return 0.0;  // < e^-700 / 700: below double range
  return -std::expint(-x);
}

}  // namespace

const char* kindName(DensityProfile::Kind kind) {
  switch (kind) {
    case DensityProfile::Kind::Exponential: return "exponential";
    case DensityProfile::Kind::DoubleExponential: return "double-exponential";
    case DensityProfile::Kind::Tent: return "tent";
    case DensityProfile::Kind::BoundaryLayer: return "boundary-layer";
    case DensityProfile::Kind::Tabulated: return "tabulated";
  }
  return "?";
}

DensityProfile DensityProfile::exponential(double scaleHeightM) {
  DensityProfile p;
  p.kind = Kind::Exponential;
  p.scaleHeightM = scaleHeightM;
  p.check();
  return p;
}

DensityProfile DensityProfile::doubleExponential(double scaleHeightM) {
  DensityProfile p;
  p.kind = Kind::DoubleExponential;
  p.scaleHeightM = scaleHeightM;
  p.check();
  return p;
}

DensityProfile DensityProfile::tent(double centreM, double halfWidthM) {
  DensityProfile p;
  p.kind = Kind::Tent;
  p.centreM = centreM;
  p.halfWidthM = halfWidthM;
  p.check();
  return p;
}

DensityProfile DensityProfile::tabulated(std::vector<double> altitudesM, std::vector<double> values) {
  DensityProfile p;
  p.kind = Kind::Tabulated;
  p.altitudesM = std::move(altitudesM);
  p.values = std::move(values);
  p.check();
  return p;
}

DensityProfile DensityProfile::boundaryLayer(double topM, double scaleHeightM, double freeDensity,
                                             double freeScaleHeightM, double freeTopM, double transitionM) {
  DensityProfile p;
  p.kind = Kind::BoundaryLayer;
  p.boundaryLayerTopM = topM;
  p.scaleHeightM = scaleHeightM;
  p.freeTroposphereDensity = freeDensity;
  p.freeTroposphereScaleHeightM = freeScaleHeightM;
  p.freeTroposphereTopM = freeTopM;
  p.transitionM = transitionM;
  p.check();
  return p;
}

std::vector<double> DensityProfile::kinksM() const {
  switch (kind) {
    case Kind::Tent: return {centreM - halfWidthM, centreM, centreM + halfWidthM};
    case Kind::Tabulated: return altitudesM;
    case Kind::BoundaryLayer: {
      const double half = 0.5 * transitionM;
      // (B itself: the free troposphere's part turns flat below it)
      std::vector<double> at{boundaryLayerTopM - half, boundaryLayerTopM, boundaryLayerTopM + half};
      if (freeTroposphereTopM > boundaryLayerTopM) at.insert(at.end(), {freeTroposphereTopM - half, freeTroposphereTopM + half});
      at.erase(std::unique(at.begin(), at.end()), at.end());
      return at;
    }
    default: return {};
  }
}

double DensityProfile::at(double altitudeM) const {
  switch (kind) {
    case Kind::Exponential: return std::exp(-altitudeM / scaleHeightM);
    case Kind::DoubleExponential: return std::exp(1.0 - std::exp(altitudeM / scaleHeightM));
    case Kind::Tent: return std::max(0.0, 1.0 - std::abs(altitudeM - centreM) / halfWidthM);
    case Kind::Tabulated: return piecewiseLinearAt(altitudesM, values, altitudeM);
    case Kind::BoundaryLayer: {
      // smoothstep from 0 below c - w/2 to 1 above c + w/2 (a step at c when w = 0)
      const auto blend = [&](double c) {
        if (!(transitionM > 0.0)) return altitudeM >= c ? 1.0 : 0.0;
        const double x = std::clamp((altitudeM - (c - 0.5 * transitionM)) / transitionM, 0.0, 1.0);
        return x * x * (3.0 - 2.0 * x);
      };
      const double up = blend(boundaryLayerTopM);
      const double top = freeTroposphereTopM > boundaryLayerTopM ? blend(freeTroposphereTopM) : 1.0;
      double rho = 0.0;
      if (up < 1.0) rho += (1.0 - up) * std::exp(-altitudeM / scaleHeightM);
      if (up > 0.0 && top < 1.0)  // below B (in the blend) the free troposphere's value at B
        rho += up * (1.0 - top) * freeTroposphereDensity *
               std::exp(-std::max(altitudeM - boundaryLayerTopM, 0.0) / freeTroposphereScaleHeightM);
      return rho;
    }
  }
  return 0.0;
}

double DensityProfile::integral(double fromM, double toM) const {
  if (toM < fromM) return -integral(toM, fromM);
  if (toM == fromM) return 0.0;
  switch (kind) {
    case Kind::Exponential: return exponentialIntegral(0.0, scaleHeightM, fromM, toM);
    case Kind::DoubleExponential: {
      // u = e^{h/H}: int exp(1 - u) H du / u = H e [E1(u_a) - E1(u_b)].
      const double H = scaleHeightM;
      const double ua = std::exp(fromM / H), ub = std::exp(toM / H);
      return H * std::exp(1.0) * (exponentialIntegralE1(ua) - exponentialIntegralE1(ub));
    }
    case Kind::Tent: {
      const std::vector<double> x{centreM - halfWidthM, centreM, centreM + halfWidthM};
      const std::vector<double> y{0.0, 1.0, 0.0};
      return piecewiseLinearIntegral(x, y, fromM, toM);
    }
    case Kind::Tabulated: return piecewiseLinearIntegral(altitudesM, values, fromM, toM);
    case Kind::BoundaryLayer: {
      // Between the blending zones' edges: each layer's exponential in closed form; across a
      // zone, Gauss-Legendre on the blend.
      static const GaussLegendreRule rule(24);
      const double B = boundaryLayerTopM, T = freeTroposphereTopM;
      std::vector<double> cuts = kinksM();
      cuts.insert(cuts.begin(), fromM);
      cuts.push_back(toM);
      for (double& c : cuts) c = std::clamp(c, fromM, toM);
      std::sort(cuts.begin(), cuts.end());
      double sum = 0.0;
      for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
        const double lo = cuts[i], hi = cuts[i + 1];
        if (!(hi > lo)) continue;
        const double mid = 0.5 * (lo + hi), half = 0.5 * transitionM;
        const bool inZone = std::abs(mid - B) < half || (T > B && std::abs(mid - T) < half);
        if (inZone) {
          for (std::size_t k = 0; k < rule.x.size(); ++k) sum += 0.5 * (hi - lo) * rule.w[k] * at(mid + 0.5 * (hi - lo) * rule.x[k]);
        } else if (mid < B) {
          sum += exponentialIntegral(0.0, scaleHeightM, lo, hi);
        } else if (mid < T) {
          sum += freeTroposphereDensity * exponentialIntegral(B, freeTroposphereScaleHeightM, lo, hi);
        }
      }
      return sum;
    }
  }
  return 0.0;
}

std::string DensityProfile::validate() const {
  switch (kind) {
    case Kind::Exponential:
    case Kind::DoubleExponential:
      if (!std::isfinite(scaleHeightM) || !(scaleHeightM > 0.0))
        return "scaleHeightM: expected a positive length in metres, got " + number(scaleHeightM);
      return {};
    case Kind::Tent:
      if (!std::isfinite(centreM)) return "centreM: expected a finite altitude in metres, got " + number(centreM);
      if (!std::isfinite(halfWidthM) || !(halfWidthM > 0.0))
        return "halfWidthM: expected a positive length in metres, got " + number(halfWidthM);
      return {};
    case Kind::BoundaryLayer:
      if (!std::isfinite(scaleHeightM) || !(scaleHeightM > 0.0))
        return "scaleHeightM: expected a positive length in metres, got " + number(scaleHeightM);
      if (!std::isfinite(boundaryLayerTopM) || !(boundaryLayerTopM > 0.0))
        return "boundaryLayerHeightM: expected a positive height in metres, got " + number(boundaryLayerTopM);
      if (!std::isfinite(freeTroposphereDensity) || freeTroposphereDensity < 0.0)
        return "freeTroposphere.relativeDensity: expected a finite relative density >= 0, got " +
               number(freeTroposphereDensity);
      if (!std::isfinite(freeTroposphereScaleHeightM) || !(freeTroposphereScaleHeightM > 0.0))
        return "freeTroposphere.scaleHeightM: expected a positive length in metres, got " +
               number(freeTroposphereScaleHeightM);
      if (!std::isfinite(freeTroposphereTopM) || !(freeTroposphereTopM >= boundaryLayerTopM))
        return "freeTroposphere.topM: expected an altitude at or above the boundary layer's top (" +
               number(boundaryLayerTopM) + " m), got " + number(freeTroposphereTopM);
      if (!std::isfinite(transitionM) || transitionM < 0.0 || !(transitionM < 2.0 * boundaryLayerTopM) ||
          (freeTroposphereTopM > boundaryLayerTopM && transitionM > freeTroposphereTopM - boundaryLayerTopM))
        return "transitionM: expected a width >= 0, below twice the boundary layer's top (" + number(boundaryLayerTopM) +
               " m) and at most the free troposphere's depth (" + number(freeTroposphereTopM - boundaryLayerTopM) +
               " m), got " + number(transitionM);
      return {};
    case Kind::Tabulated:
      if (altitudesM.size() != values.size())
        return "values: expected as many values as altitudes (" + std::to_string(altitudesM.size()) +
               "), got " + std::to_string(values.size());
      if (altitudesM.size() < 2)
        return "altitudesM: expected at least 2 altitudes, got " + std::to_string(altitudesM.size());
      for (std::size_t i = 0; i < altitudesM.size(); ++i) {
        if (!std::isfinite(altitudesM[i]))
          return "altitudesM[" + std::to_string(i) + "]: expected a finite altitude, got " +
                 number(altitudesM[i]);
        if (i > 0 && !(altitudesM[i] > altitudesM[i - 1]))
          return "altitudesM[" + std::to_string(i) + "]: expected strictly increasing altitudes, got " +
                 number(altitudesM[i]) + " after " + number(altitudesM[i - 1]);
        if (!std::isfinite(values[i]) || values[i] < 0.0)
          return "values[" + std::to_string(i) + "]: expected a finite relative density >= 0, got " +
                 number(values[i]);
      }
      return {};
  }
  return "unknown profile kind";
}

void DensityProfile::check() const {
  const std::string problem = validate();
  if (!problem.empty())
    throw std::invalid_argument(std::string(kindName(kind)) + " profile: " + problem);
}

}  // namespace umbra::atmosphere
