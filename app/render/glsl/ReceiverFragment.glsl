// Fragment stage of an eclipse receiver (EclipseShading): the reflection of the eclipsed
// Sun by a sphere, written as linear radiance (W m^-2 sr^-1) into the HDR buffer. Needs
// eclipse/glsl/EclipseShadow.glsl (umbraEclipseFactor) and sky/glsl/Photometry.glsl
// (umbraHapkeReflectanceOf) before it.
//
// EclipseShading #defines the receiver's photometry before this file:
//   UMBRA_PHOTOMETRY   0: Lambert's law; 1: the Hapke–Lommel–Seeliger reflectance (umbraHapke)
//   UMBRA_ALBEDO_MAP   1: the albedo times umbraAlbedoMap (declared by VTK) at the point's
//                      body-fixed longitude and latitude (sky/AlbedoMap.hpp), its grey value;
//                      2: the same, its colour (a reflectance map: linear values, MapTexels)
//   UMBRA_EARTHSHINE   1: the Earth's light too (Hapke only), umbraEarthshine from umbraEarthPos
//   UMBRA_NORMAL_MAP   1: the relief of umbraNormalMap (declared by VTK) tilts the normal that
//                      the light's and the eye's angles take (sky/NormalMap.hpp)
//
// All positions are relative to the receiver's centre (computed in double on the CPU,
// handed over as floats), so the angles keep float precision at any distance.

in vec3 umbraPosMC;
flat in vec3 umbraEyeMC;
flat in vec3 umbraViewDirMC;
flat in int umbraParallel;
flat in vec3 umbraEyeLon;

uniform float umbraBodyRadius;     // m
uniform vec3 umbraAlbedo;          // linear RGB
uniform vec3 umbraSunPos;          // m, relative to the body's centre
uniform float umbraSunRadius;      // m
uniform float umbraSunIrradiance;  // W m^-2 at 1 au
uniform vec3 umbraHapke;           // g, w, c (sky/Photometry.hpp)
uniform mat3 umbraInertialToBodyFixed;
uniform vec3 umbraEarthPos;        // m, relative to the body's centre
uniform vec3 umbraEarthshine;      // W m^-2 on the body, R, G, B
// The receiver's occluders: UMBRA_OCCLUDER_COUNT (0..4) of them, #defined before this file
// by EclipseShading with UMBRA_ATMOSPHERE_OCCLUDER, the one whose shadow comes from the
// atmospheric shadow LuT (umbraAtmosphereShadowLut, declared by VTK; RGB through its
// atmosphere), -1: none. Constants, so that the shadow loop unrolls to exactly the
// occluders present with one lookup each: a SIMD rasteriser (Mesa's llvmpipe) runs both
// sides of a branch and one more, masked, iteration of a loop whose count is a uniform.
uniform vec4 umbraOccluders[4];    // xyz: centre relative to the body's centre (m), w: radius (m)
// The angular radii (Eq. 3) of the Sun and of each occluder over the receiver, as
// expansions about its centre (eclipse::AngularRadiusExpansion: umbraAngularRadiusNear).
// UMBRA_EXACT_SHADOW (#defined by EclipseShading) has bit i set for an occluder whose
// shadow needs Eq. 3-4 exactly (eclipse::receiverShadowExpands false: umbraReceiverShadowUv).
uniform vec4 umbraSunAngularRadius;
uniform vec4 umbraOccluderAngularRadius[4];
// UMBRA_OBLATE_SHADOW (#defined by EclipseShading) has bit i set for an oblate occluder:
// its umbraOccluders[i].w and umbraOccluderAngularRadius[i] are then its equatorial
// radius', and umbraOccluderFigure[i] its pole and e^2 (umbraOutlineRadiusFactor).
uniform vec4 umbraOccluderFigure[4];
// The atmospheric table's texture coordinates from (u, v) (umbraShadowLutCoordIn), with
// the part of the table held folded in.
uniform vec4 umbraAtmosphereLutMap;
uniform vec3 umbraAtmosphereLutMapLow;

const float umbraAuM = 1.495978707e11;
const float umbraInvPi = 0.31830988618;
// Logarithmic depth for perspective views: 1 mm .. 1e13 m over [0, 1], so that bodies
// 1 m and 1e11 m away keep their order with any near/far planes.
const float umbraLogDepthMinM = 1.0e-3;
const float umbraLogDepthOctaves = 53.150849518;  // log2(1e13 / 1e-3)

// The point of the sphere (centre 0, radius r) seen through this fragment: the view ray
// through the rasterised facet point, intersected with the true sphere. The mesh is
// inscribed in the sphere, so the facet point is inside it and the ray always hits.
vec3 umbraSphereHit(vec3 facet, vec3 dir, float r) {
  float b = dot(facet, dir);
  float c = (length(facet) - r) * (length(facet) + r);  // <= 0 inside the sphere
  float disc = max(b * b - c, 0.0);
  return facet + (-b - sqrt(disc)) * dir;
}

#if UMBRA_ALBEDO_MAP || UMBRA_NORMAL_MAP
// The maps' texture coordinates at the body-fixed direction nb (both maps lie alike, so
// computed once): (east longitude + 180 deg, latitude + 90 deg) over (360, 180) deg. The
// longitude is counted from the eye's (umbraEyeLon) within +-180 deg: its one jump lies on
// the meridian behind the body, never seen, so that the derivatives of the coordinates (the
// mip level) are smooth wherever the body is drawn (the texture repeats, for the seam).
vec2 umbraMapCoord(vec3 nb) {
  vec3 c = umbraEyeLon;
  float fromEye = atan(c.x * nb.y - c.y * nb.x, c.x * nb.x + c.y * nb.y);
  return vec2((fromEye + c.z) / (2.0 * umbraSkyPi) + 0.5, asin(clamp(nb.z, -1.0, 1.0)) / umbraSkyPi + 0.5);
}
// The rows of the poles held half a texel (halfTexel, in texture coordinates) off the other pole.
vec2 umbraMapRowsHeld(vec2 uv, float halfTexel) { return vec2(uv.x, clamp(uv.y, halfTexel, 1.0 - halfTexel)); }
// The screen derivatives of map coordinates across the longitude's jump: seen from near a
// pole the meridian behind the eye runs through the view, and a pixel quad astride it
// would take a difference of a whole turn (the coarsest mip level: a line of the map's
// mean). A difference in longitude is taken within half a turn.
vec2 umbraMapWrapped(vec2 d) { return vec2(d.x - floor(d.x + 0.5), d.y); }
vec2 umbraMapDx(vec2 uv) { return umbraMapWrapped(dFdx(uv)); }
vec2 umbraMapDy(vec2 uv) { return umbraMapWrapped(dFdy(uv)); }
#endif

#if UMBRA_ALBEDO_MAP
uniform float umbraAlbedoMapHalfTexel;  // half a texel of the map's height, in texture coordinates
vec3 umbraAlbedoAt(vec2 uv) {
  vec3 t = textureGrad(umbraAlbedoMap, umbraMapRowsHeld(uv, umbraAlbedoMapHalfTexel), umbraMapDx(uv), umbraMapDy(uv)).rgb;
#if UMBRA_ALBEDO_MAP == 2
  return t;
#else
  return t.rrr;
#endif
}
#endif

#if UMBRA_NORMAL_MAP
uniform float umbraNormalMapHalfTexel;
uniform float umbraReliefStrength;      // 0: the sphere; 1: the map's slopes
// The relief at nb (its map coordinates uv) where the map resolves it on screen
// (sky/NormalMap.hpp, reliefFade): full strength while a texel spans at most 4 pixels
// across the footprint's short side, none from 16 on.
vec3 umbraReliefAt(vec3 nb, vec2 uv) {
  vec2 gx = umbraMapDx(uv), gy = umbraMapDy(uv);
  uv = umbraMapRowsHeld(uv, umbraNormalMapHalfTexel);
  // Texels counted at their size on the sphere: a row's shrink towards the poles.
  vec2 size = vec2(textureSize(umbraNormalMap, 0)) * vec2(length(nb.xy), 1.0);
  vec2 dx = gx * size, dy = gy * size;
  // The footprint's short side: a grazing view stretches the other one along the ray.
  float texelsPerPixel = sqrt(min(dot(dx, dx), dot(dy, dy)));
  float fade = clamp(0.5 * (log2(max(texelsPerPixel, 1.0e-6)) + 4.0), 0.0, 1.0);
  return umbraReliefNormal(nb, textureGrad(umbraNormalMap, uv, gx, gy).rgb, umbraReliefStrength * fade);
}
#endif

void umbraReceiverShade() {
  vec3 dir = umbraParallel == 1 ? umbraViewDirMC : normalize(umbraPosMC - umbraEyeMC);
  vec3 p = umbraSphereHit(umbraPosMC, dir, umbraBodyRadius);
  vec3 n = normalize(p);
  vec3 toSun = umbraSunPos - p;
  float dSun = length(toSun);
  float cosi = max(dot(n, toSun / dSun), 0.0);
  float dAu = dSun / umbraAuM;
  float eSun = umbraSunIrradiance / (dAu * dAu);
#if UMBRA_ALBEDO_MAP || UMBRA_NORMAL_MAP
  vec3 nb = umbraInertialToBodyFixed * n;
  vec2 mapUv = umbraMapCoord(nb);
#endif
#if UMBRA_ALBEDO_MAP
  vec3 albedo = umbraAlbedo * umbraAlbedoAt(mapUv);
#else
  vec3 albedo = umbraAlbedo;
#endif

  // umbraEclipseFactor of each occluder: Eq. 3-4 (umbraReceiverShadowUv: expanded about
  // the centre unless exact is needed), then one lookup in its LuT
  // (umbraAtmosphereShadowLut for the atmospheric occluder).
  vec3 shadow = vec3(1.0);
#if UMBRA_OCCLUDER_COUNT > 0
  float invSun = 1.0 / dSun;
  vec3 sunDir = toSun * invSun;
  for (int i = 0; i < UMBRA_OCCLUDER_COUNT; ++i) {
    vec2 uv = umbraReceiverShadowUv(sunDir, invSun, umbraSunAngularRadius, umbraSunRadius, umbraOccluders[i].xyz - p,
                                    umbraOccluderAngularRadius[i], umbraOccluders[i].w,
                                    (UMBRA_EXACT_SHADOW & (1 << i)) != 0, umbraOccluderFigure[i],
                                    (UMBRA_OBLATE_SHADOW & (1 << i)) != 0);
    vec3 lut = i == UMBRA_ATMOSPHERE_OCCLUDER
                   ? texture(umbraAtmosphereShadowLut,
                             umbraShadowLutCoordIn(uv, umbraAtmosphereLutMap, umbraAtmosphereLutMapLow)).rgb
                   : umbraShadowLutAt(uv);
    shadow *= uv.y >= 1.0 ? vec3(1.0) : lut;
  }
#endif
  // The normal the light's and the eye's angles take: the relief's (the sphere's own
  // terminator still bounds the light), else the sphere's.
#if UMBRA_NORMAL_MAP
  vec3 ns = transpose(umbraInertialToBodyFixed) * umbraReliefAt(nb, mapUv);
  float lit = cosi > 0.0 ? 1.0 : 0.0;
#else
  vec3 ns = n;
  float lit = 1.0;
#endif
#if UMBRA_PHOTOMETRY == 1
  vec3 toEye = umbraParallel == 1 ? -umbraViewDirMC : normalize(umbraEyeMC - p);
  vec3 radiance = albedo * (eSun * lit * umbraHapkeReflectanceOf(ns, toSun / dSun, toEye, umbraHapke)) * shadow;
#if UMBRA_EARTHSHINE
  float litByEarth = dot(n, umbraEarthPos - p) > 0.0 ? 1.0 : 0.0;
  radiance += albedo * umbraEarthshine * litByEarth *
              umbraHapkeReflectanceOf(ns, normalize(umbraEarthPos - p), toEye, umbraHapke);
#endif
#else
  vec3 radiance = albedo * (umbraInvPi * eSun * lit * max(dot(ns, toSun / dSun), 0.0)) * shadow;
#endif
  fragOutput0 = vec4(radiance, 1.0);

  if (umbraParallel == 1) {
    gl_FragDepth = gl_FragCoord.z;
  } else {
    float dist = max(length(p - umbraEyeMC), umbraLogDepthMinM);
    gl_FragDepth = clamp(log2(dist / umbraLogDepthMinM) / umbraLogDepthOctaves, 0.0, 1.0);
  }
}
