#include "HeightField.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace umbra::terrain {

void HeightField::validate() const {
  if (width < 2 || height < 2)
    throw std::invalid_argument("height field: needs at least 2 x 2 samples, got " + std::to_string(width) + " x " +
                                std::to_string(height));
  if (heightsM.size() != static_cast<std::size_t>(width) * height)
    throw std::invalid_argument("height field: " + std::to_string(heightsM.size()) + " heights for " +
                                std::to_string(width) + " x " + std::to_string(height) + " samples");
  if (!(spacingM > 0.0) || !std::isfinite(spacingM)) throw std::invalid_argument("height field: spacing must be > 0 m");
  if (!(bodyRadiusM > 0.0) || !std::isfinite(bodyRadiusM))
    throw std::invalid_argument("height field: body radius must be > 0 m");
  if (0.5 * std::max(width, height) * spacingM > 0.5 * bodyRadiusM)
    throw std::invalid_argument("height field: the grid spans more than a body radius; the tangent-plane grid "
                                "covers a local patch only");
  bool any = false;
  for (double h : heightsM) {
    if (std::isinf(h)) throw std::invalid_argument("height field: infinite height (use NaN for no data)");
    if (!std::isnan(h)) {
      any = true;
      if (std::abs(h) > 0.1 * bodyRadiusM) throw std::invalid_argument("height field: height beyond 10% of the radius");
    }
  }
  if (!any) throw std::invalid_argument("height field: every sample is no data");
}

double HeightField::bilinearOverNoData(int i, int j, double fx, double fy) const {
  const double h00 = at(i, j), h10 = at(i + 1, j), h01 = at(i, j + 1), h11 = at(i + 1, j + 1);
  const double w00 = (1 - fx) * (1 - fy), w10 = fx * (1 - fy), w01 = (1 - fx) * fy, w11 = fx * fy;
  double sum = 0.0, weight = 0.0;
  auto add = [&](double h, double w) {
    if (!std::isnan(h)) sum += w * h, weight += w;
  };
  add(h00, w00), add(h10, w10), add(h01, w01), add(h11, w11);
  if (weight > 0.0) return sum / weight;
  // On a corner's edge the weights of the valid corners can all be zero.
  weight = 0.0, sum = 0.0;
  for (double h : {h00, h10, h01, h11})
    if (!std::isnan(h)) sum += h, weight += 1.0;
  return weight > 0.0 ? sum / weight : std::numeric_limits<double>::quiet_NaN();
}

double HeightField::minValidHeight() const {
  double m = std::numeric_limits<double>::infinity();
  for (double h : heightsM)
    if (!std::isnan(h)) m = std::min(m, h);
  return m;
}

double HeightField::receiverHeight(int i, int j) const {
  if (valid(i, j)) return at(i, j);
  double sum = 0.0;
  int n = 0;
  for (int dj = -1; dj <= 1; ++dj)
    for (int di = -1; di <= 1; ++di) {
      const int a = i + di, b = j + dj;
      if (a >= 0 && b >= 0 && a < width && b < height && valid(a, b)) sum += at(a, b), ++n;
    }
  return n > 0 ? sum / n : minValidHeight();
}

glm::dvec3 sunDirectionFromElevationAzimuth(double e, double a) {
  return {std::cos(e) * std::sin(a), std::cos(e) * std::cos(a), std::sin(e)};
}

glm::dmat3 bodyFixedToTangent(double latDeg, double lonDeg) {
  constexpr double deg = 3.14159265358979323846 / 180.0;
  const double lat = latDeg * deg, lon = lonDeg * deg;
  const glm::dvec3 up(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
  glm::dvec3 east(-std::sin(lon), std::cos(lon), 0.0);
  glm::dvec3 north = glm::cross(up, east);
  if (std::abs(latDeg) >= 90.0 - 1e-9) {
    // At a pole: +y along the meridian lon + 180 (north pole) or lon (south pole).
    const glm::dvec3 meridian(std::cos(lon), std::sin(lon), 0.0);
    north = latDeg > 0.0 ? -meridian : meridian;
    const glm::dvec3 z(0.0, 0.0, latDeg > 0.0 ? 1.0 : -1.0);
    east = glm::cross(north, z);
    return glm::transpose(glm::dmat3(east, north, z));
  }
  // Rows of the result are the tangent axes in body-fixed coordinates.
  return glm::transpose(glm::dmat3(east, north, up));
}

} // namespace umbra::terrain
