#include "EclipsedDisc.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace umbra::terrain {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// 16-point Gauss-Legendre nodes and weights on [-1, 1] (the positive half).
constexpr std::array<double, 8> kNodes{0.0950125098376374, 0.2816035507792589, 0.4580167776572274, 0.6178762444026438,
                                       0.7554044083550030, 0.8656312023878318, 0.9445750230732326, 0.9894009349916499};
constexpr std::array<double, 8> kWeights{0.1894506104550685, 0.1826034150449236, 0.1691565193950025, 0.1495959888165767,
                                         0.1246289712555339, 0.0951585116824928, 0.0622535239386479, 0.0271524594117541};

/// The integral over x in [a, b] (inside the chord |x| <= c) of 1 - u + u sqrt(c^2 - x^2).
double chordIntegral(double a, double b, double c, double u) {
  if (!(b > a)) return 0.0;
  auto F = [&](double x) {
    const double s = std::sqrt(std::max(0.0, c * c - x * x));
    return 0.5 * (x * s + c * c * std::asin(std::clamp(x / c, -1.0, 1.0)));
  };
  return (1.0 - u) * (b - a) + u * (F(b) - F(a));
}

/// The luminance of the disc's visible part along the chord at height y.
double visibleChord(double y, const OccluderOnDisc& o, double u) {
  const double c = std::sqrt(std::max(0.0, 1.0 - y * y));
  if (c <= 0.0) return 0.0;
  const double dy = y - o.y;
  if (std::abs(dy) >= o.radius) return chordIntegral(-c, c, c, u);
  const double co = std::sqrt(o.radius * o.radius - dy * dy);
  const double lo = std::clamp(o.x - co, -c, c), hi = std::clamp(o.x + co, -c, c);
  return chordIntegral(-c, lo, c, u) + chordIntegral(hi, c, c, u);
}

} // namespace

OccluderOnDisc occluderOnDisc(const glm::dvec3& sunDir, double sunRadiusRad, const glm::dvec3& occluderDir,
                              double occluderRadiusRad, const glm::dvec3& up) {
  const glm::dvec3 s = glm::normalize(sunDir), e = glm::normalize(occluderDir);
  glm::dvec3 yAxis = up - glm::dot(up, s) * s;
  if (glm::length(yAxis) < 1e-12) yAxis = glm::abs(s.z) < 0.9 ? glm::dvec3(0, 0, 1) - s.z * s : glm::dvec3(1, 0, 0) - s.x * s;
  yAxis = glm::normalize(yAxis);
  const glm::dvec3 xAxis = glm::cross(yAxis, s);
  // The occluder's offset from the Sun's centre on the sky, as an angle along each axis.
  const double sep = std::acos(std::clamp(glm::dot(s, e), -1.0, 1.0));
  glm::dvec3 towards = e - glm::dot(e, s) * s;
  const double len = glm::length(towards);
  towards = len > 0.0 ? towards / len : glm::dvec3(0.0);
  return {sep * glm::dot(towards, xAxis) / sunRadiusRad, sep * glm::dot(towards, yAxis) / sunRadiusRad,
          occluderRadiusRad / sunRadiusRad};
}

double visibleFractionAboveHorizonOutside(double d, const OccluderOnDisc& o, double u) {
  const double low = std::max(-1.0, -d);
  if (!(low < 1.0)) return 0.0;
  std::vector<double> cuts{low, 1.0};
  // Where the chord's visible stretches change form: the occluder's top and bottom, and
  // the heights where its edge crosses the disc's.
  std::vector<double> heights{o.y - o.radius, o.y + o.radius};
  const double D = std::hypot(o.x, o.y);
  if (D > 0.0 && D < 1.0 + o.radius && D > std::abs(1.0 - o.radius)) {
    const double a = (1.0 - o.radius * o.radius + D * D) / (2.0 * D), h = std::sqrt(std::max(0.0, 1.0 - a * a));
    heights.push_back((a * o.y + h * o.x) / D);
    heights.push_back((a * o.y - h * o.x) / D);
  }
  for (double y : heights)
    if (o.radius > 0.0 && y > low && y < 1.0) cuts.push_back(y);
  std::sort(cuts.begin(), cuts.end());
  double sum = 0.0;
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double mid = 0.5 * (cuts[k] + cuts[k + 1]), half = 0.5 * (cuts[k + 1] - cuts[k]);
    if (!(half > 0.0)) continue;
    for (std::size_t n = 0; n < kNodes.size(); ++n)
      for (const double sign : {-1.0, 1.0}) {
        const double phi = sign * kNodes[n] * 0.5 * kPi;  // y = mid + half sin(phi), phi in [-pi/2, pi/2]
        sum += kWeights[n] * 0.5 * kPi * half * std::cos(phi) * visibleChord(mid + half * std::sin(phi), o, u);
      }
  }
  return std::clamp(sum / (kPi * (1.0 - u / 3.0)), 0.0, 1.0);
}

double visibleFractionAboveHorizonOutsideSampled(double d, const OccluderOnDisc& o, double u, int n) {
  double visible = 0.0, all = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = -1.0 + (i + 0.5) * 2.0 / n, y = -1.0 + (j + 0.5) * 2.0 / n;
      const double rho2 = x * x + y * y;
      if (rho2 >= 1.0) continue;
      const double w = 1.0 - u + u * std::sqrt(1.0 - rho2);
      all += w;
      const double ox = x - o.x, oy = y - o.y;
      if (y > -d && ox * ox + oy * oy >= o.radius * o.radius) visible += w;
    }
  return all > 0.0 ? visible / all : 0.0;
}

} // namespace umbra::terrain
