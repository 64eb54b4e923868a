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

// Eq. 3-4: the LuT coordinates (u, v) of p for one occluder; v >= 1 where p gets all the
// light (outside the penumbra, or the occluder behind the Sun).
vec2 umbraShadowUv(vec3 p, vec3 sunPos, float sunRadius, vec3 occPos, float occRadius) {
  vec3 toSun = sunPos - p;
  vec3 toOcc = occPos - p;
  if (length(toOcc) >= length(toSun)) return vec2(0.0, 2.0);   // occluder behind the Sun
  float phiSun = umbraAngularRadius(sunRadius, length(toSun));
  float phiOcc = umbraAngularRadius(occRadius, length(toOcc));
  float delta = umbraAngleBetween(toSun, toOcc);
  return vec2(phiSun / (phiOcc + phiSun), delta / (phiOcc + phiSun));
}

// (u, v) -> the coordinate in a LuT's texture, through its u and v ranges and low-v
// fraction (identity at [0, 1], [0, 1], 0).
vec2 umbraShadowLutCoordIn(vec2 uv, vec2 uRange, vec2 vRange, float vLowFraction) {
  float u = (uv.x - uRange.x) / (uRange.y - uRange.x);
  float f = vLowFraction;
  float v = (f > 0.0 && uv.y < vRange.x)
      ? f * uv.y / vRange.x
      : f + (1.0 - f) * (uv.y - vRange.x) / (vRange.y - vRange.x);
  return vec2(u, v);
}

// The same for umbraShadowLut (its umbraShadowLutURange, VRange, VLowFraction).
vec2 umbraShadowLutCoord(vec2 uv) {
  return umbraShadowLutCoordIn(uv, umbraShadowLutURange, umbraShadowLutVRange, umbraShadowLutVLowFraction);
}

// umbraShadowLut at (u, v) (v < 1: in the shadow).
vec3 umbraShadowLutAt(vec2 uv) { return texture(umbraShadowLut, umbraShadowLutCoord(uv)).rgb; }

// Fraction of sunlight per channel reaching p past one occluder (Eq. 3-4 + LuT lookup).
vec3 umbraEclipseFactor(vec3 p, vec3 sunPos, float sunRadius, vec3 occPos, float occRadius) {
  vec2 uv = umbraShadowUv(p, sunPos, sunRadius, occPos, occRadius);
  if (uv.y >= 1.0) return vec3(1.0);
  return umbraShadowLutAt(uv);
}

// The same lookup in `lut`, a part of a table (an update extent, e.g. the u range a
// receiver can be in): `map` = (coordinate of its first texel, step, the same in v) in the
// whole table's texture coordinates, whose texel centres are at (i + 0.5) * step. Outside
// the part the edge texels are used (clamp to edge). The whole table's u and v ranges
// (uRange, vRange, vLowFraction: umbraShadowLutCoordIn) are its own, not umbraShadowLut's.
// With the whole table, the texture coordinate is umbraShadowLutCoordIn(u, v, ...) itself.
// umbraShadowLutAtIn: the lookup alone at (u, v) (v < 1).
vec3 umbraShadowLutAtIn(sampler2D lut, vec4 map, vec2 uRange, vec2 vRange, float vLowFraction, vec2 uv) {
  vec2 texel = (umbraShadowLutCoordIn(uv, uRange, vRange, vLowFraction) - map.xz) / map.yw + 0.5;
  return texture(lut, texel / vec2(textureSize(lut, 0))).rgb;
}
vec3 umbraEclipseFactorIn(sampler2D lut, vec4 map, vec2 uRange, vec2 vRange, float vLowFraction, vec3 p,
                          vec3 sunPos, float sunRadius, vec3 occPos, float occRadius) {
  vec2 uv = umbraShadowUv(p, sunPos, sunRadius, occPos, occRadius);
  if (uv.y >= 1.0) return vec3(1.0);
  return umbraShadowLutAtIn(lut, map, uRange, vRange, vLowFraction, uv);
}
