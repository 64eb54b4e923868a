#include "HorizonSweep.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace umbra::terrain {
namespace {

/// The stretch of footprint searched on the bilinear surface itself [samples], and its steps.
constexpr double kNearTexels = 2.0;
constexpr int kNearSteps = 4;

struct Sample {
  double a;  // along the strip [samples], towards the Sun
  int i, j;
};

/// The disc seen from a sample: the sine of its centre's elevation and the tangents of its
/// top's and bottom's (+-1e300 past the zenith and nadir).
struct DiscSlopes {
  double sinE, topSlope, bottomSlope;
  double elevationRad() const { return std::asin(std::clamp(sinE, -1.0, 1.0)); }
};

/// One Sun over one height field: the strips along its azimuth and each one's sweep.
class Sweep {
public:
  Sweep(const HeightField& f, const SunDisc& sun, const glm::dvec3& towardsSun, glm::dvec2 u, const OccluderOnDisc* occluder)
      : f(f), sun(sun), s(towardsSun), u(u), W(f.width), H(f.height), R(f.bodyRadiusM), dx(f.spacingM),
        occluder(occluder && overlaps(*occluder) ? occluder : nullptr) {
    // The disc clear of the horizon: what the occluder leaves of it.
    if (this->occluder) clearFraction = visibleFractionAboveHorizonOutside(2.0, *this->occluder, sun.limbDarkening);
    sinR = std::sin(sun.angularRadiusRad), cosR = std::cos(sun.angularRadiusRad);
    for (int n = 0; n < kNearSteps; ++n) {
      const double sTexels = kNearTexels * (n + 1) / kNearSteps, t = sTexels * dx;
      nearSteps[n] = sTexels * u;
      nearInverseM[n] = 1.0 / t;
      nearDropSlope[n] = t / (2.0 * R);
    }
    alongI = std::abs(u.x) >= std::abs(u.y);
  }

  /// The strips' indices: the lateral coordinate l = -u.y i + u.x j, rounded.
  std::pair<long long, long long> strips() const {
    double lMin = 1e300, lMax = -1e300;
    for (int cj : {0, H - 1})
      for (int ci : {0, W - 1}) {
        const double l = -u.y * ci + u.x * cj;
        lMin = std::min(lMin, l), lMax = std::max(lMax, l);
      }
    return {static_cast<long long>(std::floor(lMin + 0.5)), static_cast<long long>(std::floor(lMax + 0.5))};
  }

  /// The samples of strip k (round(l) == k), sunward first.
  void samples(long long k, std::vector<Sample>& strip) const {
    strip.clear();
    // For each step of the major axis m (columns, else rows), the minor range of the strip.
    const int majorCount = alongI ? W : H, minorCount = alongI ? H : W;
    const bool majorSunward = alongI ? u.x > 0.0 : u.y > 0.0;  // the Sun towards higher m
    for (int step = 0; step < majorCount; ++step) {
      const int m = majorSunward ? majorCount - 1 - step : step;
      // l in [k - 0.5, k + 0.5): l = u.x j - u.y m (minor j), or -u.y i + u.x m (minor i)
      const double base = alongI ? -u.y * m : u.x * m, scale = alongI ? u.x : -u.y;
      double lo = (k - 0.5 - base) / scale, hi = (k + 0.5 - base) / scale;
      if (lo > hi) std::swap(lo, hi);
      const int cEnd = std::min(minorCount - 1, static_cast<int>(std::floor(hi)));
      for (int c = std::max(0, static_cast<int>(std::ceil(lo - 1e-9))); c <= cEnd; ++c) {
        const int i = alongI ? m : c, j = alongI ? c : m;
        if (std::floor(-u.y * i + u.x * j + 0.5) != static_cast<double>(k)) continue;  // (the range's ends, rounded)
        strip.push_back({u.x * i + u.y * j, i, j});
      }
    }
    // Made a column (row) at a time, the strip is nearly in order already.
    for (std::size_t n = 1; n < strip.size(); ++n)
      for (std::size_t m = n; m > 0 && strip[m - 1].a < strip[m].a; --m) std::swap(strip[m - 1], strip[m]);
  }

  /// The visible fraction at every sample of a strip (sunward first) into `out`.
  void sweep(const std::vector<Sample>& strip, std::vector<glm::dvec2>& hull, std::vector<float>& out) const {
    hull.clear();  // (a [m], g [m]) of the far samples sunward: their upper convex hull
    std::size_t next = 0;  // strip[next...]: not yet on the hull
    for (std::size_t k = 0; k < strip.size(); ++k) {
      const Sample& p = strip[k];
      // The far terrain: the samples from kNearTexels sunward on, put on the hull as p reaches them.
      for (; next < k && strip[next].a >= p.a + kNearTexels; ++next)
        if (f.valid(strip[next].i, strip[next].j)) addToHull(hull, strip[next]);
      const double h = f.receiverHeight(p.i, p.j);
      const double nearSlope = nearSlopeAt(p, h);
      const DiscSlopes disc = discAt(p.i, p.j);
      float& value = out[static_cast<std::size_t>(p.j) * W + p.i];
      if (nearSlope >= disc.topSlope) {
        value = 0.0f;  // under the near terrain: no need of the far
        continue;
      }
      const double best = std::max(tangentSlope(hull, p.a * dx, h), nearSlope);
      // No terrain sunward within the grid: the receiver's own horizontal.
      value = fraction(best > -1e299 ? best : 0.0, disc);
    }
  }

  /// The zenith or nadir Sun: no azimuth, no terrain in the way.
  void overhead(std::vector<float>& out) const {
    for (int j = 0; j < H; ++j)
      for (int i = 0; i < W; ++i)
        out[static_cast<std::size_t>(j) * W + i] = discAt(i, j).sinE > 0.0 ? static_cast<float>(clearFraction) : 0.0f;
  }

private:
  /// A sample behind the hull's last vertex: keep the hull convex, drop what it hides.
  void addToHull(std::vector<glm::dvec2>& hull, const Sample& q) const {
    const double qa = q.a * dx, qg = f.at(q.i, q.j) - qa * qa / (2.0 * R);
    if (!hull.empty() && hull.back().x <= qa + 1e-9) {  // a sample beside the last: keep the higher
      if (hull.back().y >= qg) return;
      hull.pop_back();
    }
    while (hull.size() >= 2) {
      const glm::dvec2& b = hull.back();
      const glm::dvec2& c = hull[hull.size() - 2];
      if ((b.y - qg) * (c.x - qa) <= (c.y - qg) * (b.x - qa)) hull.pop_back();
      else break;
    }
    hull.emplace_back(qa, qg);
  }

  /// The far horizon's slope from a receiver at aM, height h: its tangent to the hull (the
  /// slopes seen from it rise along the hull from the nearest vertex to the tangent, then
  /// fall: a binary search), plus aM / R for the sphere's drop.
  double tangentSlope(const std::vector<glm::dvec2>& hull, double aM, double h) const {
    if (hull.empty()) return -1e300;
    const double g = h - aM * aM / (2.0 * R);
    auto slope = [&](const glm::dvec2& q) { return (q.y - g) / (q.x - aM); };
    std::size_t lo = 0, hi = hull.size() - 1;  // index 0: the farthest
    while (lo < hi) {
      const std::size_t mid = (lo + hi) / 2;
      if (slope(hull[mid]) >= slope(hull[mid + 1])) hi = mid;
      else lo = mid + 1;
    }
    return slope(hull[lo]) + aM / R;
  }

  /// The near horizon's slope: the bilinear surface along the footprint, in steps.
  double nearSlopeAt(const Sample& p, double h) const {
    double best = -1e300;
    for (int n = 0; n < kNearSteps; ++n) {
      const double gx = p.i + nearSteps[n].x, gy = p.j + nearSteps[n].y;
      if (gx < 0.0 || gy < 0.0 || gx > W - 1.0 || gy > H - 1.0) break;
      const double hq = f.bilinear(gx, gy);
      if (!std::isnan(hq)) best = std::max(best, (hq - h) * nearInverseM[n] - nearDropSlope[n]);
    }
    return best;
  }

  /// The disc from sample (i, j), without a trigonometric call.
  DiscSlopes discAt(int i, int j) const {
    const double sinE = std::clamp(glm::dot(s, f.direction(i, j)), -1.0, 1.0);
    const double cosE = std::sqrt(std::max(0.0, 1.0 - sinE * sinE));
    const double topCos = cosE * cosR - sinE * sinR, bottomCos = cosE * cosR + sinE * sinR;
    return {sinE, topCos > 0.0 ? (sinE * cosR + cosE * sinR) / topCos : 1e300,
            bottomCos > 0.0 ? (sinE * cosR - cosE * sinR) / bottomCos : -1e300};
  }

  /// The visible fraction under a horizon of slope `horizon` (Eq. 7 in the penumbra only).
  float fraction(double horizon, const DiscSlopes& disc) const {
    if (horizon >= disc.topSlope) return 0.0f;
    if (horizon <= disc.bottomSlope) return static_cast<float>(clearFraction);
    const double d = (disc.elevationRad() - std::atan(horizon)) / sun.angularRadiusRad;
    return static_cast<float>(occluder ? visibleFractionAboveHorizonOutside(d, *occluder, sun.limbDarkening)
                                       : discFractionForOffset(d, sun));
  }

  const HeightField& f;
  const SunDisc& sun;
  glm::dvec3 s;
  glm::dvec2 u;
  int W, H;
  double R, dx, sinR = 0.0, cosR = 1.0;
  bool alongI = true;
  const OccluderOnDisc* occluder;  ///< in front of the Sun, or null
  double clearFraction = 1.0;      ///< of the disc clear of the horizon
  glm::dvec2 nearSteps[kNearSteps];
  double nearInverseM[kNearSteps], nearDropSlope[kNearSteps];
};

} // namespace

std::vector<float> sweepVisibleFractionMap(const HeightField& f, const SunDisc& sun, const OccluderOnDisc* occluder) {
  f.validate();
  const double len = glm::length(sun.direction);
  if (!(len > 0.0) || !std::isfinite(len)) throw std::invalid_argument("sun direction must be a finite non-zero vector");
  if (!(sun.angularRadiusRad > 0.0) || sun.angularRadiusRad > 0.5)
    throw std::invalid_argument("sun angular radius must be in (0, 0.5] rad");
  const glm::dvec3 s = sun.direction / len;
  std::vector<float> out(static_cast<std::size_t>(f.width) * f.height);
  const double horizontal = std::hypot(s.x, s.y);
  const glm::dvec2 u = horizontal > 0.0 ? glm::dvec2(s.x, s.y) / horizontal : glm::dvec2(0.0, 1.0);
  const Sweep sweep(f, sun, s, u, occluder);  // u: towards the Sun on the grid
  if (horizontal < 1e-12) {
    sweep.overhead(out);
    return out;
  }
  const auto [first, last] = sweep.strips();
#pragma omp parallel
  {
    std::vector<Sample> strip;
    std::vector<glm::dvec2> hull;
#pragma omp for schedule(dynamic, 16)
    for (long long k = first; k <= last; ++k) {
      sweep.samples(k, strip);
      sweep.sweep(strip, hull, out);
    }
  }
  return out;
}

} // namespace umbra::terrain
