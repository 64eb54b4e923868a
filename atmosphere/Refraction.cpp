#include "Refraction.hpp"
#include "ParallelErrors.hpp"

#include <algorithm>
#include <atomic>
#include <climits>
#include <cmath>
#include <stdexcept>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace umbra::atmosphere {

// ---- the medium ---------------------------------------------------------------------------

double RefractiveMedium::refractiveIndex(double radiusM) const {
  if (!refractivity) return 1.0;
  const double h = std::clamp(radiusM - bottomRadiusM, 0.0, topRadiusM - bottomRadiusM);
  return 1.0 + refractivity(h);
}

double RefractiveMedium::refractiveIndexGradientPerM(double radiusM) const {
  if (!refractivity || radiusM < bottomRadiusM || radiusM > topRadiusM) return 0.0;
  const double h = radiusM - bottomRadiusM;  // the ground itself belongs to the atmosphere
  if (refractivityDerivativePerM) return refractivityDerivativePerM(h);
  // Fourth-order finite differences, one-sided within two spacings of a boundary so that
  // the profile is only evaluated inside the shell.
  const double thickness = topRadiusM - bottomRadiusM;
  const double dh = std::min(10.0, thickness / 8.0);
  const auto& f = refractivity;
  if (h < 2.0 * dh) {
    return (-25.0 * f(h) + 48.0 * f(h + dh) - 36.0 * f(h + 2 * dh) + 16.0 * f(h + 3 * dh) -
            3.0 * f(h + 4 * dh)) / (12.0 * dh);
  }
  if (h > thickness - 2.0 * dh) {
    return (25.0 * f(h) - 48.0 * f(h - dh) + 36.0 * f(h - 2 * dh) - 16.0 * f(h - 3 * dh) +
            3.0 * f(h - 4 * dh)) / (12.0 * dh);
  }
  return (f(h - 2 * dh) - 8.0 * f(h - dh) + 8.0 * f(h + dh) - f(h + 2 * dh)) / (12.0 * dh);
}

RefractiveMedium exponentialRefractiveMedium(double bottomRadiusM, double topRadiusM,
                                             double surfaceRefractivity, double scaleHeightM) {
  RefractiveMedium m;
  m.bottomRadiusM = bottomRadiusM;
  m.topRadiusM = topRadiusM;
  m.refractivity = [=](double h) { return surfaceRefractivity * std::exp(-h / scaleHeightM); };
  m.refractivityDerivativePerM = [=](double h) {
    return -surfaceRefractivity / scaleHeightM * std::exp(-h / scaleHeightM);
  };
  return m;
}

RefractiveMedium scaledRefractiveMedium(const RefractiveMedium& medium, double factor) {
  RefractiveMedium m = medium;
  if (medium.refractivity) {
    m.refractivity = [f = medium.refractivity, factor](double h) { return factor * f(h); };
  }
  if (medium.refractivityDerivativePerM) {
    m.refractivityDerivativePerM = [f = medium.refractivityDerivativePerM, factor](double h) {
      return factor * f(h);
    };
  }
  return m;
}

double edlenStandardAirRefractivity(double wavelengthM) {
  const double sigma = 1e-6 / wavelengthM;  // vacuum wavenumber in 1/um
  const double s2 = sigma * sigma;
  return (8342.13 + 2406030.0 / (130.0 - s2) + 15997.0 / (38.9 - s2)) * 1e-8;
}

double bouguerInvariantM(const RefractiveMedium& medium, const RayPoint& p) {
  const double r = std::sqrt(p.xM * p.xM + p.yM * p.yM);
  return medium.refractiveIndex(r) * std::abs(p.xM * p.dirY - p.yM * p.dirX);
}

// ---- the ray ------------------------------------------------------------------------------

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Ray state in its plane: position p and v = n t (the "optical direction").
struct State {
  double px, py, vx, vy;
};

/// The ray equation with the path length s as the variable: dp/ds = t = v / |v|,
/// dv/ds = grad n = dn/dr p / |p|. In a spherically symmetric medium p x v = n r sin(z)
/// is a first integral (Bouguer); |v| = n along the exact solution.
class RayIntegrator {
public:
  explicit RayIntegrator(const RefractiveMedium& m)
      : m_(m), bottom_(m.bottomRadiusM), top_(m.topRadiusM) {}

  State derivative(const State& s) const {
    const double vn = std::sqrt(s.vx * s.vx + s.vy * s.vy);
    const double r = std::sqrt(s.px * s.px + s.py * s.py);
    // The atmosphere's gradient, continued (as a constant) past its boundaries: the
    // integration always ends a step exactly on the ground or the top, so only RK4 stages
    // of such a last step fall (slightly) outside, and they must not see a jump; the
    // straight path under ground and above the top is handled outside the integrator.
    const double g = m_.refractiveIndexGradientPerM(std::clamp(r, bottom_, top_));
    if (g == 0.0) return {s.vx / vn, s.vy / vn, 0.0, 0.0};
    return {s.vx / vn, s.vy / vn, g * s.px / r, g * s.py / r};
  }

  /// One classical RK4 step of length h.
  State step(const State& s, double h) const {
    const State k1 = derivative(s);
    const State k2 = derivative(axpy(s, 0.5 * h, k1));
    const State k3 = derivative(axpy(s, 0.5 * h, k2));
    const State k4 = derivative(axpy(s, h, k3));
    const double w = h / 6.0;
    return {s.px + w * (k1.px + 2.0 * k2.px + 2.0 * k3.px + k4.px),
            s.py + w * (k1.py + 2.0 * k2.py + 2.0 * k3.py + k4.py),
            s.vx + w * (k1.vx + 2.0 * k2.vx + 2.0 * k3.vx + k4.vx),
            s.vy + w * (k1.vy + 2.0 * k2.vy + 2.0 * k3.vy + k4.vy)};
  }

private:
  static State axpy(const State& s, double a, const State& k) {
    return {s.px + a * k.px, s.py + a * k.py, s.vx + a * k.vx, s.vy + a * k.vy};
  }
  const RefractiveMedium& m_;
  double bottom_, top_;
};

double radius2(const State& s) { return s.px * s.px + s.py * s.py; }
double radius(const State& s) { return std::sqrt(radius2(s)); }
double speed(const State& s) { return std::sqrt(s.vx * s.vx + s.vy * s.vy); }
/// d(r^2)/ds = 2 p . t
double radius2Rate(const State& s) { return 2.0 * (s.px * s.vx + s.py * s.vy) / speed(s); }

/// Cubic Hermite interpolant of r^2(s) over one step of length L, from r^2 and d(r^2)/ds
/// at both ends. Exact for straight lines (r^2 is quadratic in s there).
struct Radius2Hermite {
  double a0, d0, a1, d1, L;

  Radius2Hermite(const State& s0, const State& s1, double length)
      : a0(radius2(s0)), d0(radius2Rate(s0)), a1(radius2(s1)), d1(radius2Rate(s1)), L(length) {}

  double at(double sigma) const {
    const double t = sigma / L, t2 = t * t, t3 = t2 * t;
    return (2 * t3 - 3 * t2 + 1) * a0 + (t3 - 2 * t2 + t) * L * d0 + (-2 * t3 + 3 * t2) * a1 +
           (t3 - t2) * L * d1;
  }

  /// Where r^2 has its interior minimum in (0, L) (the turning point), or -1.
  double interiorMinimum() const {
    if (!(L > 0.0)) return -1.0;
    // d/ds f = (A t^2 + B t + C) with t = s / L.
    const double slope = (a0 - a1) / L;
    const double A = 6.0 * slope + 3.0 * d0 + 3.0 * d1;
    const double B = -6.0 * slope - 4.0 * d0 - 2.0 * d1;
    const double C = d0;
    double best = -1.0, bestValue = std::min(a0, a1);
    auto consider = [&](double t) {
      if (!(t > 0.0 && t < 1.0)) return;
      const double v = at(t * L);
      if (v < bestValue) best = t * L, bestValue = v;
    };
    const double disc = B * B - 4.0 * A * C;
    if (disc < 0.0) return -1.0;
    const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
    if (q != 0.0) consider(C / q);
    if (A != 0.0) consider(q / A);
    return best;
  }
};

/// Finds where the radius of the RK4 path from `s` crosses `boundaryM` between lo and hi
/// (g = r - boundary has opposite signs there): safeguarded Newton with dr/ds = t . p / r.
double findCrossing(const RayIntegrator& ray, const State& s, double lo, double hi,
                    double boundaryM) {
  auto g = [&](double sigma, double* rate) {
    const State e = ray.step(s, sigma);
    const double r = radius(e);
    if (rate) *rate = (e.px * e.vx + e.py * e.vy) / (r * speed(e));
    return r - boundaryM;
  };
  double gLo = g(lo, nullptr), gHi = g(hi, nullptr);
  if (gLo == 0.0) return lo;
  if (gHi == 0.0 || (gLo > 0.0) == (gHi > 0.0)) return hi;
  double x = lo + (hi - lo) * gLo / (gLo - gHi);
  for (int i = 0; i < 100 && hi - lo > 1e-6; ++i) {
    double rate = 0.0;
    const double gx = g(x, &rate);
    if (std::abs(gx) < 1e-9) return x;
    if ((gx > 0.0) == (gLo > 0.0)) lo = x, gLo = gx; else hi = x, gHi = gx;
    double next = rate != 0.0 ? x - gx / rate : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    x = next;
  }
  return x;
}

RayPoint toPoint(const State& s, double pathLengthM, bool underGround) {
  const double vn = speed(s);
  return {s.px, s.py, s.vx / vn, s.vy / vn, pathLengthM, underGround};
}

// A ray from at or above the top (radius r, direction mu, sin z): straight to its entry
// point, where r, mu and sinZ are moved (true); or past the atmosphere, when `out` is
// finished with its straight contact (false).
bool enterFromAbove(double b, double t, double& r, double& mu, double& sinZ, RayPath& out) {
  if (mu >= 0.0) {
    out.contactAltitudeM = r - b;
    return false;
  }
  const double p = r * sinZ;  // impact parameter
  if (p >= t) {
    out.contactAltitudeM = p - b;
    return false;
  }
  r = t;
  mu = -std::sqrt((t - p) * (t + p)) / t;
  sinZ = p / t;
  return true;
}

// Where a step of length h from s (ending at next) first goes under the ground (radius b):
// h when it ends under it, the path's lowest point when it dips under and comes back up;
// -1 when it stays above.
double groundWithinStep(const RayIntegrator& ray, const State& s, const State& next, double h, double b) {
  if (radius(next) < b) return h;
  const double turn = Radius2Hermite(s, next, h).interiorMinimum();
  if (turn > 0.0 && Radius2Hermite(s, next, h).at(turn) < b * b && radius(ray.step(s, turn)) < b) return turn;
  return -1.0;
}

// The path's results from its last state s: the deviation, a signed angle from the initial
// direction (sin z, mu) to the final one (towards the planet is clockwise in this frame, the
// planet's centre lying to the right of +x), the exit direction and central angle, the
// contact and the length.
void finishPath(const State& s, double sinZ, double mu, double contactAltitudeM, double lengthM, RayPath& out) {
  const double vn = speed(s), tx = s.vx / vn, ty = s.vy / vn;
  const double cross = sinZ * ty - mu * tx, dot = sinZ * tx + mu * ty;
  out.deviationRad = -std::atan2(cross, dot);
  const double re = radius(s);
  out.exitMu = clampCosine((s.px * tx + s.py * ty) / re);
  out.centralAngleRad = std::atan2(s.px, s.py);
  out.contactAltitudeM = contactAltitudeM;
  out.hitGround = out.contactAltitudeM < 0.0;
  out.pathLengthM = lengthM;
}

} // namespace

RayPath traceRay(const RefractiveMedium& medium, double radiusM, double mu, double stepM,
                 const SegmentCallback& segment) {
  TraceOptions options;
  options.stepM = stepM;
  options.segment = segment;
  return traceRay(medium, radiusM, mu, options);
}

RayPath traceRay(const RefractiveMedium& medium, double radiusM, double mu,
                 const TraceOptions& options) {
  RayPath out;
  const double b = medium.bottomRadiusM, t = medium.topRadiusM;
  if (!std::isfinite(radiusM) || !std::isfinite(mu) || !(t > b) || !(b > 0.0)) {
    out.completed = false;
    return out;
  }
  const double h = options.stepM > 0.0 ? options.stepM : 10e3;
  double r = std::max(radiusM, b);
  mu = clampCosine(mu);
  double sinZ = std::sqrt((1.0 - mu) * (1.0 + mu));
  out.exitMu = mu;

  if (r >= t && !enterFromAbove(b, t, r, mu, sinZ, out)) return out;

  const RayIntegrator ray(medium);
  const double n0 = medium.refractiveIndex(r);
  State s{0.0, r, n0 * sinZ, n0 * mu};
  double minRadius = r, length = 0.0;
  const double stepsForAnyRay = 4.0 * kPi * t / h + 64.0;
  const int maxSteps = options.maxSteps > 0
                           ? options.maxSteps
                           : static_cast<int>(std::min<double>(stepsForAnyRay, INT_MAX / 2));
  const int pieces = std::max(1, options.segmentsPerStep);

  auto emit = [&](const State& st, bool underGround) {
    if (options.point) options.point(toPoint(st, length, underGround));
  };
  // Report the path from s0 to s1 (one RK4 step of length L) and track the contact.
  auto advance = [&](const State& s0, const State& s1, double L) {
    const Radius2Hermite f(s0, s1, L);
    if (options.segment) {
      for (int i = 0; i < pieces; ++i) {
        const double mid = std::sqrt(std::max(0.0, f.at((i + 0.5) * L / pieces)));
        options.segment(std::clamp(mid - b, 0.0, t - b), L / pieces);
      }
    }
    const double turn = f.interiorMinimum();
    minRadius = std::min({minRadius, radius(s1),
                          turn > 0.0 ? std::sqrt(std::max(0.0, f.at(turn))) : minRadius});
    length += L;
    ++out.steps;
    emit(s1, false);
  };
  // Straight through the ground (constant n) from a point on it heading down.
  auto chord = [&](State& st) {
    const double vn = speed(st), tx = st.vx / vn, ty = st.vy / vn;
    const double along = st.px * tx + st.py * ty;  // p . t, normally < 0
    const double rs = radius(st), c = (rs - b) * (rs + b);
    const double u = std::max(0.0, -along + std::sqrt(std::max(0.0, along * along - c)));
    // Closest approach to the centre: ahead on the line, or here if already past it.
    minRadius = std::min(minRadius, along < 0.0 ? std::abs(st.px * ty - st.py * tx) : rs);
    st.px += u * tx;
    st.py += u * ty;
    const double scale = b / radius(st);  // back onto the sphere (rounding only)
    st.px *= scale;
    st.py *= scale;
    if (options.segment && u > 0.0) options.segment(0.0, u);
    length += u;
    emit(st, true);
  };

  emit(s, false);
  bool exited = false;
  for (int iteration = 0; iteration < maxSteps; ++iteration) {
    const double rs = radius(s);
    if (rs <= b && s.px * s.vx + s.py * s.vy < 0.0) {  // on the ground, heading down
      chord(s);
      continue;
    }
    const State next = ray.step(s, h);

    if (const double groundHi = groundWithinStep(ray, s, next, h, b); groundHi > 0.0) {
      const double sigma = findCrossing(ray, s, 0.0, groundHi, b);
      const State at = ray.step(s, sigma);
      advance(s, at, sigma);
      s = at;
      chord(s);
      continue;
    }

    // The top: the step ends above it (the path is straight from there on).
    if (radius(next) >= t) {
      const double turn = Radius2Hermite(s, next, h).interiorMinimum();
      const double lo = turn > 0.0 ? turn : 0.0;
      const double sigma = radius(ray.step(s, lo)) >= t ? lo : findCrossing(ray, s, lo, h, t);
      const State at = ray.step(s, sigma);
      advance(s, at, sigma);
      s = at;
      exited = true;
      break;
    }
    advance(s, next, h);
    s = next;
  }
  out.completed = exited;
  finishPath(s, sinZ, mu, minRadius - b, length, out);
  return out;
}

// ---- the table ----------------------------------------------------------------------------

RefractionSample RefractionTable::sample(double radiusM, double mu) const {
  if (deviationRad.empty() || width < 2 || height < 2) return {};
  const double b = bottomRadiusM, t = topRadiusM;
  double r = std::max(radiusM, b);
  mu = clampCosine(mu);
  double sinZ = std::sqrt((1.0 - mu) * (1.0 + mu));
  if (r > t) {
    if (mu >= 0.0) return {0.0, r - b};
    const double p = r * sinZ;
    if (p >= t) return {0.0, p - b};
    r = t;
    mu = -std::sqrt((t - p) * (t + p)) / t;
    sinZ = p / t;
  }
  const double muHorizon = horizonCosine(b, r);
  const double muLookup = std::max(mu, muHorizon);
  const TransmittanceCoords c = transmittanceCoordsFromRMu(shell(), r, muLookup);
  const double fx = c.xMu * (width - 1), fy = c.xR * (height - 1);
  if (!(std::isfinite(fx) && std::isfinite(fy)))
    throw std::domain_error("refraction table lookup at a non-finite coordinate (r " + std::to_string(r) + " m, mu " +
                            std::to_string(mu) + ")");
  const int x0 = std::clamp(static_cast<int>(std::floor(fx)), 0, width - 2);
  const int y0 = std::clamp(static_cast<int>(std::floor(fy)), 0, height - 2);
  if (y0 < firstRow)
    throw std::domain_error("refraction table lookup at r " + std::to_string(r) + " m: below the rows traced (from " +
                            std::to_string(firstRow) + " of " + std::to_string(height) + ")");
  const double wx = std::clamp(fx - x0, 0.0, 1.0), wy = std::clamp(fy - y0, 0.0, 1.0);
  auto lerp2 = [&](auto&& value) {
    return (1 - wy) * ((1 - wx) * value(x0, y0) + wx * value(x0 + 1, y0)) +
           wy * ((1 - wx) * value(x0, y0 + 1) + wx * value(x0 + 1, y0 + 1));
  };
  // Near the zenith the deviation grows like tan(z), i.e. like sqrt(x_mu): interpolating
  // it linearly would underestimate it between the first columns. Delta-theta / sin(z)
  // is smooth there (about (n - 1) / mu, Laplace), so interpolate that and multiply back;
  // on the zenith column (sin z = 0) it is extrapolated linearly from the next two.
  auto perSinZ = [&](int x, int y) -> double {
    if (x == 0) {
      const int x2 = std::min(2, width - 1);
      auto ratio = [&](int xx) {
        const RadiusMu ray = texelRay(xx, y);
        return deviationRad[index(xx, y)] / std::sqrt((1.0 - ray.mu) * (1.0 + ray.mu));
      };
      return x2 == 2 ? 2.0 * ratio(1) - ratio(2) : ratio(1);
    }
    const RadiusMu ray = texelRay(x, y);
    return deviationRad[index(x, y)] / std::sqrt((1.0 - ray.mu) * (1.0 + ray.mu));
  };
  const double sinLookup = std::sqrt((1.0 - muLookup) * (1.0 + muLookup));
  RefractionSample s{sinLookup * lerp2(perSinZ),
                     lerp2([&](int x, int y) { return double(contactAltitudeM[index(x, y)]); })};
  if (mu < muHorizon) s.contactAltitudeM = std::min(s.contactAltitudeM, r * sinZ - b);
  return s;
}

RefractionTable buildRefractionTable(const RefractiveMedium& medium, int width, int height,
                                     double stepM, const std::function<void(double)>& progress, int firstRow) {
  if (width < 2 || height < 2) throw std::invalid_argument("refraction table: size below 2x2");
  if (firstRow < 0 || firstRow > height - 2)
    throw std::invalid_argument("refraction table: first row " + std::to_string(firstRow) + " outside 0.." +
                                std::to_string(height - 2));
  if (!(stepM > 0.0)) throw std::invalid_argument("refraction table: step must be positive");
  if (!(medium.bottomRadiusM > 0.0) || !(medium.topRadiusM > medium.bottomRadiusM)) {
    throw std::invalid_argument("refraction table: need 0 < bottom radius < top radius");
  }
  if (!medium.refractivity) throw std::invalid_argument("refraction table: no refractivity");

  RefractionTable table;
  table.width = width;
  table.height = height;
  table.bottomRadiusM = medium.bottomRadiusM;
  table.topRadiusM = medium.topRadiusM;
  table.stepM = stepM;
  table.firstRow = firstRow;
  table.deviationRad.assign(static_cast<std::size_t>(width) * height, 0.0f);
  table.contactAltitudeM.assign(static_cast<std::size_t>(width) * height, 0.0f);

  std::atomic<int> rowsDone{0};
  ParallelErrors errors;
  const int rows = height - firstRow;
#pragma omp parallel for schedule(dynamic, 1)
  for (int y = firstRow; y < height; ++y) {
    errors.run([&] {
      for (int x = 0; x < width; ++x) {
        const RadiusMu ray = table.texelRay(x, y);
        const RayPath path = traceRay(medium, ray.radiusM, ray.mu, stepM);
        table.deviationRad[table.index(x, y)] = static_cast<float>(path.deviationRad);
        table.contactAltitudeM[table.index(x, y)] = static_cast<float>(path.contactAltitudeM);
      }
    });
    const int done = ++rowsDone;
#ifdef _OPENMP
    const bool callingThread = omp_get_thread_num() == 0;
#else
    const bool callingThread = true;
#endif
    if (progress && callingThread) progress(static_cast<double>(done) / rows);
  }
  errors.rethrow();
  if (progress) progress(1.0);
  return table;
}

} // namespace umbra::atmosphere
