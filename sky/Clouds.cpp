#include "Clouds.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace umbra::sky {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMinCosine = 1.0e-3;
// The octaves' noise values spread about 0.5 with a standard deviation of 0.12: a logistic
// law of that spread (scale sigma sqrt(3) / pi) makes them near-uniform, so that the mean
// density follows the coverage (within 0.06, tests/sky).
constexpr double kNoiseLogisticScale = 0.066;
// Half the width of the noise-to-density ramp (in uniform units): the clouds' soft edges.
constexpr double kEdge = 0.08;

// A 32-bit integer hash (Wellons' "lowbias32"); GLSL has the same in sky/glsl/Clouds.glsl.
std::uint32_t mix(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

// The lattice value at (i, j, k) in [0, 1): the corner's spatial hash (Teschner et al.'s
// primes) mixed once with the octave's seed.
double latticeValue(int i, int j, int k, std::uint32_t seedHash) {
  const std::uint32_t h = mix(static_cast<std::uint32_t>(i) * 73856093u ^ static_cast<std::uint32_t>(j) * 19349663u ^
                              static_cast<std::uint32_t>(k) * 83492791u ^ seedHash);
  return static_cast<double>(h >> 8) * (1.0 / 16777216.0);
}

double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

double valueNoise(const glm::dvec3& p, std::uint32_t seedHash) {
  const glm::dvec3 f = glm::floor(p);
  const int i = static_cast<int>(f.x), j = static_cast<int>(f.y), k = static_cast<int>(f.z);
  const glm::dvec3 u(fade(p.x - f.x), fade(p.y - f.y), fade(p.z - f.z));
  double v[2][2];
  for (int dz = 0; dz < 2; ++dz)
    for (int dy = 0; dy < 2; ++dy) {
      const double a = latticeValue(i, j + dy, k + dz, seedHash), b = latticeValue(i + 1, j + dy, k + dz, seedHash);
      v[dz][dy] = a + (b - a) * u.x;
    }
  const double y0 = v[0][0] + (v[0][1] - v[0][0]) * u.y, y1 = v[1][0] + (v[1][1] - v[1][0]) * u.y;
  return y0 + (y1 - y0) * u.z;
}

double cosineOf(double mu) { return std::max(std::abs(mu), kMinCosine); }

}  // namespace

double cloudDirectTransmittance(double opticalDepth, double mu) {
  return std::exp(-std::max(opticalDepth, 0.0) / cosineOf(mu));
}

double cloudReflectance(double opticalDepth, double mu0) {
  const double g = kCloudAsymmetry;
  const double tau = (1.0 - g * g) * std::max(opticalDepth, 0.0), gs = g / (1.0 + g);
  const double m = cosineOf(mu0);
  const double scattered = 1.0 - std::exp(-tau / m);
  const double r = ((1.0 - gs) * tau + (2.0 / 3.0 - m) * scattered) / (4.0 / 3.0 + (1.0 - gs) * tau);
  return std::clamp(r, 0.0, scattered);
}

double cloudDiffuseTransmittance(double opticalDepth, double mu0) {
  return std::max(1.0 - cloudReflectance(opticalDepth, mu0) - cloudDirectTransmittance(opticalDepth, mu0), 0.0);
}

double cloudRadiance(double opticalDepth, double mu0, bool litSide) {
  const double share = litSide ? cloudReflectance(opticalDepth, mu0) : cloudDiffuseTransmittance(opticalDepth, mu0);
  return share * cosineOf(mu0) / kPi;
}

double cloudNoise(const glm::dvec3& p, std::uint32_t seed) {
  double sum = 0.0, amplitude = 1.0, total = 0.0, scale = 1.0;
  for (int o = 0; o < kCloudOctaves; ++o) {
    sum += amplitude * valueNoise(p * scale, mix(seed + static_cast<std::uint32_t>(o)));
    total += amplitude;
    amplitude *= 0.5;
    scale *= 2.0;
  }
  return sum / total;
}

double cloudDensity(double noise, double coverage) {
  const double c = std::clamp(coverage, 0.0, 1.0);
  const double uniform = 1.0 / (1.0 + std::exp(-(noise - 0.5) / kNoiseLogisticScale));
  // The threshold moves from above every value (c = 0) to below every value (c = 1).
  const double threshold = (1.0 - c) * (1.0 + 2.0 * kEdge) - kEdge;
  const double t = std::clamp((uniform - threshold + kEdge) / (2.0 * kEdge), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

glm::dmat3 cloudDrift(const CloudLayer& layer, const glm::dvec3& footBodyFixed, double layerRadiusM,
                      double epochSeconds, double timeSeconds) {
  const glm::dvec3 up = glm::normalize(footBodyFixed);
  glm::dvec3 east = glm::cross(glm::dvec3(0.0, 0.0, 1.0), up);
  if (glm::length(east) < 1e-12) east = glm::dvec3(0.0, 1.0, 0.0);  // at a pole: +y stands for east
  east = glm::normalize(east);
  const glm::dvec3 north = glm::cross(up, east);
  const glm::dvec3 wind = layer.windEastMs * east + layer.windNorthMs * north;
  const double speed = glm::length(wind);
  if (!(speed > 0.0) || !(layerRadiusM > 0.0)) return glm::dmat3(1.0);
  // Points move by angle w t about the axis a: the noise is looked up at the point turned
  // back by that angle.
  const glm::dvec3 a = glm::normalize(glm::cross(up, wind));
  const double angle = -std::fmod(speed / layerRadiusM * (timeSeconds - epochSeconds), 2.0 * kPi);
  const double c = std::cos(angle), s = std::sin(angle);
  glm::dmat3 k(0.0);  // cross-product matrix of a (column-major)
  k[1][0] = -a.z;
  k[2][0] = a.y;
  k[0][1] = a.z;
  k[2][1] = -a.x;
  k[0][2] = -a.y;
  k[1][2] = a.x;
  return glm::dmat3(1.0) + s * k + (1.0 - c) * (k * k);
}

}  // namespace umbra::sky
