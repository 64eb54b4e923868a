// Cloud layers: the GLSL twin of sky/Clouds.cpp (the formulas and their sources are in
// sky/Clouds.hpp): light through a layer, and its seeded coverage noise.

const float umbraCloudAsymmetry = 0.85;
const float umbraCloudDiffuseCosine = 0.6;
const float umbraCloudMinCosine = 1.0e-3;
const float umbraCloudLogisticScale = 0.066;
const float umbraCloudEdge = 0.08;

float umbraCloudDirect(float tau, float mu) { return exp(-max(tau, 0.0) / max(abs(mu), umbraCloudMinCosine)); }

float umbraCloudReflectance(float tau, float mu0) {
  float g = umbraCloudAsymmetry;
  float t = (1.0 - g * g) * max(tau, 0.0), gs = g / (1.0 + g);
  float m = max(abs(mu0), umbraCloudMinCosine);
  float scattered = 1.0 - exp(-t / m);
  float r = ((1.0 - gs) * t + (2.0 / 3.0 - m) * scattered) / (4.0 / 3.0 + (1.0 - gs) * t);
  return clamp(r, 0.0, scattered);
}

float umbraCloudDiffuseTransmittance(float tau, float mu0) {
  return max(1.0 - umbraCloudReflectance(tau, mu0) - umbraCloudDirect(tau, mu0), 0.0);
}

uint umbraCloudHash(uint x) {
  x ^= x >> 16u;
  x *= 0x7feb352du;
  x ^= x >> 15u;
  x *= 0x846ca68bu;
  x ^= x >> 16u;
  return x;
}

float umbraCloudLattice(ivec3 c, uint seedHash) {
  uint h = umbraCloudHash(uint(c.x) * 73856093u ^ uint(c.y) * 19349663u ^ uint(c.z) * 83492791u ^ seedHash);
  return float(h >> 8u) * (1.0 / 16777216.0);
}

float umbraCloudValueNoise(vec3 p, uint seedHash) {
  vec3 f = floor(p);
  ivec3 c = ivec3(f);
  vec3 t = p - f;
  vec3 u = t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
  float v00 = mix(umbraCloudLattice(c, seedHash), umbraCloudLattice(c + ivec3(1, 0, 0), seedHash), u.x);
  float v01 = mix(umbraCloudLattice(c + ivec3(0, 1, 0), seedHash), umbraCloudLattice(c + ivec3(1, 1, 0), seedHash), u.x);
  float v10 = mix(umbraCloudLattice(c + ivec3(0, 0, 1), seedHash), umbraCloudLattice(c + ivec3(1, 0, 1), seedHash), u.x);
  float v11 = mix(umbraCloudLattice(c + ivec3(0, 1, 1), seedHash), umbraCloudLattice(c + ivec3(1, 1, 1), seedHash), u.x);
  return mix(mix(v00, v01, u.y), mix(v10, v11, u.y), u.z);
}

float umbraCloudNoise(vec3 p, uint seed) {
  float sum = 0.0, amplitude = 1.0, total = 0.0, scale = 1.0;
  for (int o = 0; o < 5; ++o) {
    sum += amplitude * umbraCloudValueNoise(p * scale, umbraCloudHash(seed + uint(o)));
    total += amplitude;
    amplitude *= 0.5;
    scale *= 2.0;
  }
  return sum / total;
}

float umbraCloudDensity(float noise, float coverage) {
  float c = clamp(coverage, 0.0, 1.0);
  float uniform01 = 1.0 / (1.0 + exp(-(noise - 0.5) / umbraCloudLogisticScale));
  float threshold = (1.0 - c) * (1.0 + 2.0 * umbraCloudEdge) - umbraCloudEdge;
  float t = clamp((uniform01 - threshold + umbraCloudEdge) / (2.0 * umbraCloudEdge), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}
