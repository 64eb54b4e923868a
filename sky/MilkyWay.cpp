#include "MilkyWay.hpp"

#include "Colour.hpp"
#include "StarLight.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace umbra::sky {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// The sines and cosines of the map's texel centres: per row (declination) and per column
// (right ascension), so that a texel's direction is (cd cr, cd sr, sd).
struct TexelAngles {
  std::vector<double> sinDec, cosDec, sinRa, cosRa;
  explicit TexelAngles(const MilkyWayMap& map)
      : sinDec(map.height), cosDec(map.height), sinRa(map.width), cosRa(map.width) {
    for (int j = 0; j < map.height; ++j) {
      const double dec = ((j + 0.5) * 180.0 / map.height - 90.0) * kDeg;
      sinDec[j] = std::sin(dec);
      cosDec[j] = std::cos(dec);
    }
    for (int i = 0; i < map.width; ++i) {
      const double ra = (kMilkyWayMapLeftRaDeg - (i + 0.5) * 360.0 / map.width) * kDeg;
      sinRa[i] = std::sin(ra);
      cosRa[i] = std::cos(ra);
    }
  }
  double dot(int column, int row, const glm::dvec3& d) const {
    return cosDec[row] * (cosRa[column] * d.x + sinRa[column] * d.y) + sinDec[row] * d.z;
  }
};

int wrapColumn(int i, int width) { return ((i % width) + width) % width; }

// Calls f(column, row, cosine of the angle to `centre`) for every texel within `radiusRad`
// of it (the bounding rows, and the columns those rows span at their declination).
template <class F>
void forEachTexelNear(const MilkyWayMap& map, const TexelAngles& a, const glm::dvec3& centre, double radiusRad, F f) {
  const glm::dvec2 uv = milkyWayMapCoord(centre);
  const double rowsPerRad = map.height / kPi, columnsPerRad = map.width / (2.0 * kPi);
  const int row0 = std::max(0, static_cast<int>(std::floor(uv.y * map.height - radiusRad * rowsPerRad - 1.0)));
  const int row1 = std::min(map.height - 1, static_cast<int>(std::ceil(uv.y * map.height + radiusRad * rowsPerRad + 1.0)));
  const double decRad = std::asin(std::clamp(centre.z, -1.0, 1.0));
  const double cosLimit = std::cos(radiusRad);
  // Across the columns: the widest span is at the cap's row nearest a pole.
  const double nearPole = std::min(kPi / 2.0, std::abs(decRad) + radiusRad);
  const double span = nearPole >= kPi / 2.0 - 1e-9 ? kPi : std::min(kPi, radiusRad / std::cos(nearPole) + 1e-9);
  const int half = std::min(map.width / 2, static_cast<int>(std::ceil(span * columnsPerRad)) + 1);
  const int c = static_cast<int>(std::floor(uv.x * map.width));
  for (int j = row0; j <= row1; ++j)
    for (int k = -half; k <= half - (2 * half >= map.width ? 1 : 0); ++k) {
      const int i = wrapColumn(c + k, map.width);
      const double cosAngle = a.dot(i, j, centre);
      if (cosAngle >= cosLimit) f(i, j, cosAngle);
    }
}

std::vector<double> luminances(const MilkyWayMap& map) {
  std::vector<double> y(static_cast<std::size_t>(map.width) * map.height);
  for (std::size_t k = 0; k < y.size(); ++k)
    y[k] = frameLuminance(glm::dvec3(map.rgb[3 * k], map.rgb[3 * k + 1], map.rgb[3 * k + 2]));
  return y;
}

double capMean(const MilkyWayMap& map, const TexelAngles& a, const std::vector<double>& y, const glm::dvec3& d,
               double capRadiusRad) {
  double sum = 0.0, weight = 0.0;
  forEachTexelNear(map, a, d, capRadiusRad, [&](int i, int j, double) {
    sum += a.cosDec[j] * y[static_cast<std::size_t>(j) * map.width + i];
    weight += a.cosDec[j];
  });
  return weight > 0.0 ? sum / weight : 0.0;
}

}  // namespace

glm::vec3 MilkyWayMap::at(int column, int row) const {
  const std::size_t k = 3 * (static_cast<std::size_t>(row) * width + column);
  return {rgb[k], rgb[k + 1], rgb[k + 2]};
}

glm::dvec3 icrsDirection(double raRad, double decRad) {
  return {std::cos(decRad) * std::cos(raRad), std::cos(decRad) * std::sin(raRad), std::sin(decRad)};
}

glm::dvec2 milkyWayMapCoord(const glm::dvec3& icrsDirection) {
  const glm::dvec3 d = glm::normalize(icrsDirection);
  const double raDeg = std::atan2(d.y, d.x) / kDeg;
  double u = (kMilkyWayMapLeftRaDeg - raDeg) / 360.0;
  u -= std::floor(u);
  const double decDeg = std::asin(std::clamp(d.z, -1.0, 1.0)) / kDeg;
  return {u, (90.0 + decDeg) / 180.0};
}

glm::dvec3 milkyWayDirection(const glm::dvec2& uv) {
  return icrsDirection((kMilkyWayMapLeftRaDeg - 360.0 * uv.x) * kDeg, (180.0 * uv.y - 90.0) * kDeg);
}

double s10ToVMagPerArcsec2(double s10) { return 10.0 + 5.0 * std::log10(3600.0) - 2.5 * std::log10(s10); }

void removeStars(MilkyWayMap& map, const std::vector<glm::dvec3>& icrsDirections, const std::vector<double>& vMags) {
  if (icrsDirections.size() != vMags.size())
    throw std::invalid_argument("removeStars: " + std::to_string(icrsDirections.size()) + " directions but " +
                                std::to_string(vMags.size()) + " magnitudes");
  const TexelAngles a(map);
  const double texelRad = kPi / map.height;
  std::vector<std::size_t> inside;  // the dot's texels
  std::vector<float> ring[3];
  for (std::size_t s = 0; s < vMags.size(); ++s) {
    if (!(vMags[s] <= kMilkyWayStarsShownToV)) continue;
    const double radius = (vMags[s] >= 3.0 ? 1.5 : vMags[s] >= 1.0 ? 2.5 : 3.5) * texelRad;
    const double cosInside = std::cos(radius), cosRingInside = std::cos(radius + texelRad);
    inside.clear();
    for (auto& r : ring) r.clear();
    forEachTexelNear(map, a, icrsDirections[s], radius + 2.0 * texelRad, [&](int i, int j, double cosAngle) {
      const std::size_t k = static_cast<std::size_t>(j) * map.width + i;
      if (cosAngle >= cosInside) inside.push_back(k);
      else if (cosAngle <= cosRingInside)
        for (int c = 0; c < 3; ++c) ring[c].push_back(map.rgb[3 * k + c]);
    });
    if (ring[0].empty()) continue;
    float median[3];
    for (int c = 0; c < 3; ++c) {
      std::nth_element(ring[c].begin(), ring[c].begin() + ring[c].size() / 2, ring[c].end());
      median[c] = ring[c][ring[c].size() / 2];
    }
    for (std::size_t k : inside)
      for (int c = 0; c < 3; ++c) map.rgb[3 * k + c] = median[c];
  }
}

double frameLuminance(const glm::dvec3& rgb) { return colour::luminance(rgb * sunLinearSrgb()); }

BrightestCap brightestCap(const MilkyWayMap& map, double capRadiusRad) {
  const TexelAngles a(map);
  const std::vector<double> y = luminances(map);
  // A grid of the cap's radius; then texel by texel within a grid step of its best eight.
  const double step = capRadiusRad;
  std::vector<BrightestCap> coarse;
  for (double dec = -kPi / 2.0; dec <= kPi / 2.0 + 1e-12; dec += step) {
    const int n = std::max(1, static_cast<int>(std::ceil(2.0 * kPi * std::cos(dec) / step)));
    for (int k = 0; k < n; ++k) {
      const glm::dvec3 d = icrsDirection(2.0 * kPi * k / n, dec);
      coarse.push_back({d, capMean(map, a, y, d, capRadiusRad)});
    }
  }
  const std::size_t keep = std::min<std::size_t>(8, coarse.size());
  std::partial_sort(coarse.begin(), coarse.begin() + keep, coarse.end(),
                    [](const BrightestCap& p, const BrightestCap& q) { return p.meanLuminance > q.meanLuminance; });
  BrightestCap best = coarse.front();
  for (std::size_t c = 0; c < keep; ++c)
    forEachTexelNear(map, a, coarse[c].direction, step, [&](int i, int j, double) {
      const glm::dvec3 d = icrsDirection(std::atan2(a.sinRa[i], a.cosRa[i]), std::asin(a.sinDec[j]));
      const double m = capMean(map, a, y, d, capRadiusRad);
      if (m > best.meanLuminance) best = {d, m};
    });
  return best;
}

double capMeanLuminance(const MilkyWayMap& map, const glm::dvec3& direction, double capRadiusRad) {
  const TexelAngles a(map);
  return capMean(map, a, luminances(map), glm::normalize(direction), capRadiusRad);
}

double sphereMeanLuminance(const MilkyWayMap& map) {
  const TexelAngles a(map);
  double sum = 0.0, weight = 0.0;
  for (int j = 0; j < map.height; ++j)
    for (int i = 0; i < map.width; ++i) {
      sum += a.cosDec[j] * frameLuminance(glm::dvec3(map.at(i, j)));
      weight += a.cosDec[j];
    }
  return sum / weight;
}

double milkyWayRadianceScale(const MilkyWayMap& map, double sunIrradianceAt1AuWm2) {
  const BrightestCap cap = brightestCap(map, kMilkyWayCalibrationCapRad);
  if (!(cap.meanLuminance > 0.0)) throw std::invalid_argument("black everywhere");
  return radianceOfSurfaceBrightnessWm2Sr(s10ToVMagPerArcsec2(kMilkyWayBrightestS10), sunIrradianceAt1AuWm2) /
         cap.meanLuminance;
}

}  // namespace umbra::sky
