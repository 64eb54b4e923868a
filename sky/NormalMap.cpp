#include "NormalMap.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace umbra::sky {

glm::dvec3 reliefNormal(const glm::dvec3& nb, const glm::dvec3& texel, double strength) {
  glm::dvec3 east(-nb.y, nb.x, 0.0);
  const double l = glm::length(east);
  east = l > 1e-6 ? east / l : glm::dvec3(0.0, 1.0, 0.0);
  const glm::dvec3 north = glm::cross(nb, east);
  const glm::dvec3 d = 2.0 * texel - glm::dvec3(1.0);
  return glm::normalize(strength * (d.x * east - d.y * north) + std::max(d.z, 0.05) * nb);
}

double reliefFade(double pixelsPerTexel) {
  return std::clamp(0.5 * (4.0 - std::log2(std::max(pixelsPerTexel, 1e-6))), 0.0, 1.0);
}

}  // namespace umbra::sky
