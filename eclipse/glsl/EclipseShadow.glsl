// GLSL twin of eclipse/ShadowLut.cpp (eclipseFactor) and eclipse/ShadowMapping.cpp.
// Keep the two side by side: tests/render compares them pixel by pixel.
// Positions are relative to any common origin (the renderer uses the camera), so that
// single precision keeps the angles accurate.

uniform sampler2D umbraShadowLut;
// The u and v ranges the LuT's width and height cover (eclipse::ShadowLut::uMin, uMax,
// vMin, vMax) and the fraction of the rows for v in [0, vMin] (vLowFraction: a split v
// axis); [0, 1] and 0 unless set.
uniform vec2 umbraShadowLutURange = vec2(0.0, 1.0);
uniform vec2 umbraShadowLutVRange = vec2(0.0, 1.0);
uniform float umbraShadowLutVLowFraction = 0.0;

// Angle between two directions without acos, accurate for tiny angles.
float umbraAngleBetween(vec3 a, vec3 b) {
  vec3 na = normalize(a);
  vec3 nb = normalize(b);
  return 2.0 * atan(length(na - nb), length(na + nb));
}

// Angular radius of a sphere (Eq. 3); pi/2 from inside it. asin(r / d) as an atan: GLSL's
// asin may be a coarse polynomial (Mesa: ~1e-4 rad near 0.4 rad, i.e. close to an occluder).
float umbraAngularRadius(float radius, float dist) {
  return dist <= radius ? 1.5707963 : atan(radius, sqrt((dist - radius) * (dist + radius)));
}

// Fraction of sunlight per channel reaching p past one occluder (Eq. 3-4 + LuT lookup).
vec3 umbraEclipseFactor(vec3 p, vec3 sunPos, float sunRadius, vec3 occPos, float occRadius) {
  vec3 toSun = sunPos - p;
  vec3 toOcc = occPos - p;
  if (length(toOcc) >= length(toSun)) return vec3(1.0);   // occluder behind the Sun
  float phiSun = umbraAngularRadius(sunRadius, length(toSun));
  float phiOcc = umbraAngularRadius(occRadius, length(toOcc));
  float delta = umbraAngleBetween(toSun, toOcc);
  float u = phiSun / (phiOcc + phiSun);
  float v = delta / (phiOcc + phiSun);
  if (v >= 1.0) return vec3(1.0);
  u = (u - umbraShadowLutURange.x) / (umbraShadowLutURange.y - umbraShadowLutURange.x);
  float f = umbraShadowLutVLowFraction;
  v = (f > 0.0 && v < umbraShadowLutVRange.x)
      ? f * v / umbraShadowLutVRange.x
      : f + (1.0 - f) * (v - umbraShadowLutVRange.x) / (umbraShadowLutVRange.y - umbraShadowLutVRange.x);
  return texture(umbraShadowLut, vec2(u, v)).rgb;
}
