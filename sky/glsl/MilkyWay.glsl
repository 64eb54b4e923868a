// Where the Milky Way map lies on the sky: the GLSL twin of sky::milkyWayMapCoord
// (sky/MilkyWay.hpp). u = frac((90 deg - RA) / 360 deg), v = (90 deg + Dec) / 180 deg, for a
// unit direction in ICRS axes (the scene's).
vec2 umbraMilkyWayCoord(vec3 d) {
  float ra = atan(d.y, d.x);
  float u = fract((1.5707963267949 - ra) / 6.28318530717959);
  float v = 0.5 + asin(clamp(d.z, -1.0, 1.0)) / 3.14159265358979;
  return vec2(u, v);
}
