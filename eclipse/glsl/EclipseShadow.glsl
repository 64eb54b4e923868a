// GLSL twin of eclipse/ShadowLut.cpp (eclipseFactor) and eclipse/ShadowMapping.cpp.
// Keep the two side by side: tests/render compares them pixel by pixel.
// Positions are relative to any common origin (the renderer uses the camera), so that
// single precision keeps the angles accurate.

uniform sampler2D umbraShadowLut;
// umbraShadowLut's texture coordinates from (u, v) (eclipse::LutRange::textureMap, set
// from the LuT's u and v ranges and low-v fraction): (u - map.x) map.y; (v - map.z) map.w
// for v >= mapLow.x, (v - mapLow.y) mapLow.z below (a split v axis). Identity unless set.
uniform vec4 umbraShadowLutMap = vec4(0.0, 1.0, 0.0, 1.0);
uniform vec3 umbraShadowLutMapLow = vec3(0.0, 0.0, 1.0);

// Angular radius of a sphere (Eq. 3); pi/2 from inside it. asin(r / d) as an atan: GLSL's
// asin may be a coarse polynomial (Mesa: ~1e-4 rad near 0.4 rad, i.e. close to an occluder).
float umbraAngularRadius(float radius, float dist) {
  return dist <= radius ? 1.5707963 : atan(radius, sqrt((dist - radius) * (dist + radius)));
}

// The same near a reference distance d0, from the inverse distance w = 1 / d:
// eclipse::AngularRadiusExpansion x = (d0, phi0, c1, c2), a quadratic in e = d0 w - 1.
// Exact to float precision where its maxErrorRad says so (the renderer checks it).
float umbraAngularRadiusNear(vec4 x, float invDist) {
  float e = x.x * invDist - 1.0;
  return x.y + e * (x.z + e * x.w);
}

// Eq. 4 from the directions to the Sun and to the occluder as unit vectors and their
// angular radii. The angle between the directions as atan(|a x b|, a . b), accurate for
// tiny angles but for the atan itself: Mesa's errs by -2e-5 of small angles, as does
// umbraAngularRadius' one, so that the ratios of Eq. 4 cancel it (use the two together).
vec2 umbraShadowUvFrom(vec3 sunDir, float phiSun, vec3 occDir, float phiOcc) {
  float delta = atan(length(cross(sunDir, occDir)), dot(sunDir, occDir));
  return vec2(phiSun, delta) * (1.0 / (phiOcc + phiSun));
}

// Eq. 3-4: the LuT coordinates (u, v) of p for one occluder; v >= 1 where p gets all the
// light (outside the penumbra, or the occluder behind the Sun).
vec2 umbraShadowUv(vec3 p, vec3 sunPos, float sunRadius, vec3 occPos, float occRadius) {
  vec3 toSun = sunPos - p;
  vec3 toOcc = occPos - p;
  float dSun = length(toSun), dOcc = length(toOcc);
  if (dOcc >= dSun) return vec2(0.0, 2.0);   // occluder behind the Sun
  return umbraShadowUvFrom(toSun / dSun, umbraAngularRadius(sunRadius, dSun), toOcc / dOcc,
                           umbraAngularRadius(occRadius, dOcc));
}

// The angle between two unit vectors where it is below eclipse::kSmallAngleSeriesMaxRad:
// asin |a x b| by its series to s^7 (exact to float there, without an arctangent; Mesa's
// atan errs by 2e-5 of small angles). From pi/2 on (a . b <= 0) it gives 4.
float umbraSmallAngleBetween(vec3 a, vec3 b) {
  vec3 c = cross(a, b);
  float s2 = dot(c, c);
  float delta = sqrt(s2) * (1.0 + s2 * (1.0 / 6.0 + s2 * (3.0 / 40.0 + s2 * (5.0 / 112.0))));
  return dot(a, b) > 0.0 ? delta : 4.0;
}

// eclipse::outlineRadiusFactor: a spheroid seen along viewDir (unit) shows an ellipse; its
// radius towards `towards` over the equatorial radius. figure: the pole (unit) and e^2 =
// f (2 - f).
float umbraOutlineRadiusFactor(vec3 viewDir, vec3 towards, vec4 figure) {
  float cosView = dot(viewDir, figure.xyz);
  float q2 = 1.0 - figure.w * (1.0 - cosView * cosView);
  vec3 across = towards - dot(towards, viewDir) * viewDir;
  float acrossSq = dot(across, across);
  float tp = dot(across, figure.xyz);
  float alongPoleSq = acrossSq > 0.0 ? tp * tp / acrossSq : 0.0;
  return sqrt(q2 / (q2 + figure.w * alongPoleSq));
}

// Eq. 3-4 at a point of a receiver, as the receiver's shader has it: toOcc from the point
// to the occluder; sunDir and invSun the unit vector and inverse distance to the Sun.
// Unless `exact` (a constant: the other branch compiles away; eclipse::
// receiverShadowExpands false): the angular radii from their expansions about the
// receiver's centre (umbraAngularRadiusNear: sunX of the Sun, x of the occluder) and the
// angle between the directions from umbraSmallAngleBetween. With `exact`: Eq. 3-4 as
// umbraShadowUv (the Sun's radius sunRadius, the occluder's radius), where the atan's
// errors cancel in the ratios. v >= 1 where the point gets all the light (the occluder
// behind the Sun too). With `oblate` (a constant too) the occluder is a spheroid of
// `figure` (umbraOutlineRadiusFactor) and equatorial radius `radius` (x expands that
// sphere's angular radius): its angular radius is scaled to its outline's towards the Sun
// (eclipse::outlineRadiusTowardsSunM).
vec2 umbraReceiverShadowUv(vec3 sunDir, float invSun, vec4 sunX, float sunRadius, vec3 toOcc, vec4 x, float radius,
                           bool exact, vec4 figure, bool oblate) {
  float invOcc = inversesqrt(dot(toOcc, toOcc));
  vec3 occDir = toOcc * invOcc;
  float outline = oblate ? umbraOutlineRadiusFactor(occDir, sunDir, figure) : 1.0;
  vec2 uv;
  if (exact) {
    uv = umbraShadowUvFrom(sunDir, umbraAngularRadius(sunRadius, 1.0 / invSun), occDir,
                           umbraAngularRadius(outline * radius, 1.0 / invOcc));
  } else {
    float phiSun = umbraAngularRadiusNear(sunX, invSun);
    uv = vec2(phiSun, umbraSmallAngleBetween(sunDir, occDir)) *
         (1.0 / (phiSun + outline * umbraAngularRadiusNear(x, invOcc)));
  }
  return invOcc <= invSun ? vec2(0.0, 2.0) : uv;
}

// (u, v) -> the texture coordinate of a LuT whose map is (map, mapLow) (umbraShadowLutMap):
// a subtraction and a multiplication per axis, the split a selection.
vec2 umbraShadowLutCoordIn(vec2 uv, vec4 map, vec3 mapLow) {
  vec2 v = uv.y < mapLow.x ? mapLow.yz : map.zw;
  return vec2((uv.x - map.x) * map.y, (uv.y - v.x) * v.y);
}

// The same for umbraShadowLut.
vec2 umbraShadowLutCoord(vec2 uv) { return umbraShadowLutCoordIn(uv, umbraShadowLutMap, umbraShadowLutMapLow); }

// umbraShadowLut at (u, v) (v < 1: in the shadow).
vec3 umbraShadowLutAt(vec2 uv) { return texture(umbraShadowLut, umbraShadowLutCoord(uv)).rgb; }

// Fraction of sunlight per channel reaching p past one occluder (Eq. 3-4 + LuT lookup).
vec3 umbraEclipseFactor(vec3 p, vec3 sunPos, float sunRadius, vec3 occPos, float occRadius) {
  vec2 uv = umbraShadowUv(p, sunPos, sunRadius, occPos, occRadius);
  if (uv.y >= 1.0) return vec3(1.0);
  return umbraShadowLutAt(uv);
}
