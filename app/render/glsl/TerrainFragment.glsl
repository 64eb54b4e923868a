// Fragment stage of a terrain patch (TerrainRendering): the view ray through the
// pre-displaced mesh is refined onto the bilinear height field (terrain paper, section 4),
// the visible fraction of the Sun is found there, and the point is shaded Lambertian:
// albedo / pi * E_sun * max(0, n . l) * fraction, linear radiance in W m^-2 sr^-1 like
// the eclipse receivers (ReceiverFragment.glsl). The fraction: with a shadow table
// (terrain/ShadowTable.hpp) uniform steps of terrain/glsl/TerrainShadow.glsl (which comes
// before this file) over the first umbraSearchToTexels of the footprint and the table's
// far horizon, bilinear; without one, the DP search over the whole footprint.
//
// Patch coordinates: the tangent frame of the height field (HeightField.hpp) shifted by
// -(0, 0, R), so the grid's tangent point is the origin and every position near the
// patch is a small number (full float precision from orbit and from 2 m). Needs the
// vertex stage of ReceiverVertex.glsl (umbraPosMC, umbraEyeMC ... in patch coordinates).

in vec3 umbraPosMC;
flat in vec3 umbraEyeMC;
flat in vec3 umbraViewDirMC;
flat in int umbraParallel;

uniform vec3 umbraTerrainAlbedo;       // linear RGB
uniform float umbraTerrainIrradiance;  // W m^-2 of the Sun at the patch
uniform int umbraTerrainOutput;        // 0: radiance; 1: (grid x, grid y, visible fraction)
uniform vec3 umbraTerrainEye;          // the camera (the origin), patch coordinates from doubles
uniform vec3 umbraTerrainLight;        // towards the Sun, tangent frame (the table's Sun may be rounded)
// UMBRA_TERRAIN_TABLE (defined before this file) 1: umbraFarOffsets (declared by VTK) holds
// the table's far horizon per sample (its R channel).

const float umbraInvPi = 0.31830988618;
const float umbraLogDepthMinM = 1.0e-3;          // as ReceiverFragment.glsl
const float umbraLogDepthOctaves = 53.150849518;
const int umbraMarchSteps = 64;     // half a sample each: 32 samples from the facet at most
const int umbraBisections = 12;   // then one step of false position

vec2 umbraGridOf(vec3 q) {
  return umbraRadiusM * q.xy / (umbraRadiusM + q.z) / umbraSpacingM + 0.5 * vec2(umbraGridSize - 1);
}

// Height of q above the sphere, from differences of small numbers.
float umbraAltitudeOf(vec3 q) {
  return (dot(q, q) + 2.0 * umbraRadiusM * q.z) / (length(q + vec3(0.0, 0.0, umbraRadiusM)) + umbraRadiusM);
}

// The bilinear height at grid coordinates g (clamped to the grid), as HeightField::bilinear;
// no-data corners are left out (umbraHeightAt); umbraNoData if all four are.
float umbraBilinearHeight(vec2 g) {
  g = clamp(g, vec2(0.0), vec2(umbraGridSize - 1));
  ivec2 c = min(ivec2(floor(g)), umbraGridSize - 2);
  vec2 f = g - vec2(c);
  float h00 = texelFetch(umbraHeights, c, 0).r, h10 = texelFetch(umbraHeights, c + ivec2(1, 0), 0).r;
  float h01 = texelFetch(umbraHeights, c + ivec2(0, 1), 0).r, h11 = texelFetch(umbraHeights, c + ivec2(1, 1), 0).r;
  if (min(min(h00, h10), min(h01, h11)) > umbraNoData) return mix(mix(h00, h10, f.x), mix(h01, h11, f.x), f.y);
  return umbraHeightAt(g, vec2(0.0), 0.0, 0.0);
}

// Height of q above the bilinear terrain (1e30 over no data); g, h: the grid point below.
float umbraAboveTerrain(vec3 q, out vec2 g, out float h) {
  g = umbraGridOf(q);
  h = umbraBilinearHeight(g);
  return h <= umbraNoData ? 1e30 : umbraAltitudeOf(q) - h;
}

// The surface point at grid coordinates g, height h, in patch coordinates.
vec3 umbraSurfacePoint(vec2 g) {
  float h = umbraBilinearHeight(g);
  h = h <= umbraNoData ? 0.0 : h;
  vec2 pl = (g - 0.5 * vec2(umbraGridSize - 1)) * umbraSpacingM;
  float pl2 = dot(pl, pl);
  float n = sqrt(pl2 + umbraRadiusM * umbraRadiusM);
  return vec3((umbraRadiusM + h) / n * pl, (h * umbraRadiusM - umbraRadiusM * pl2 / (n + umbraRadiusM)) / n);
}

// The table's far horizon at grid coordinates g, bilinear (ShadowTable::farOffsetAt).
float umbraFarOffsetAt(vec2 g) {
#if UMBRA_TERRAIN_TABLE
  g = clamp(g, vec2(0.0), vec2(umbraGridSize - 1));
  ivec2 c = min(ivec2(floor(g)), umbraGridSize - 2);
  vec2 f = g - vec2(c);
  float d00 = texelFetch(umbraFarOffsets, c, 0).r, d10 = texelFetch(umbraFarOffsets, c + ivec2(1, 0), 0).r;
  float d01 = texelFetch(umbraFarOffsets, c + ivec2(0, 1), 0).r, d11 = texelFetch(umbraFarOffsets, c + ivec2(1, 1), 0).r;
  return mix(mix(d00, d10, f.x), mix(d01, d11, f.x), f.y);
#else
  return 1e30;
#endif
}

// The visible fraction of the Sun at grid coordinates g, height h (ShadowTable::fractionAt
// with a table, else the whole search as terrain::visibleFraction).
uniform int umbraNearSteps;  // with a table: the near search's uniform steps
float umbraTerrainFraction(vec2 g, float h) {
  UmbraProfile p;
  if (!umbraMakeProfileAt(g, h, p)) return p.e > 0.0 ? 1.0 : 0.0;
#if UMBRA_TERRAIN_TABLE
  float horizon = umbraHorizonUniform(p, umbraNearSteps);
#else
  float horizon = umbraHorizonDP(p);
#endif
  return umbraDiscFraction(min((p.e - horizon) / umbraSunRadius, umbraFarOffsetAt(g)), umbraLimbDarkening);
}

void umbraTerrainShade() {
  // (umbraEyeMC, from the inverse of VTK's float matrix, is off by ~1e-4 m a kilometre
  // from the patch's centre: too much 2 m above the ground.)
  vec3 eye = umbraTerrainEye;
  vec3 dir = umbraParallel == 1 ? umbraViewDirMC : normalize(umbraPosMC - eye);
  vec3 up = normalize(umbraPosMC + vec3(0.0, 0.0, umbraRadiusM));
  // View-ray refinement: from the facet point (on the mesh, just below the surface) step
  // back along the ray towards the eye (away from it should the point be above), half a
  // sample at a time across the ground, until the surface is crossed; then bisect. The
  // crossing nearest the facet: the mesh's depth test orders the rest.
  float horizontal = sqrt(max(0.0, 1.0 - dot(dir, up) * dot(dir, up)));
  float step = 0.5 * umbraSpacingM / max(horizontal, 0.05);
  float tEye = umbraParallel == 0 ? -0.999 * length(umbraPosMC - eye) : -1e30;
  vec2 g;
  float h;
  float ta = 0.0, tb = 0.0;  // above, below the surface
  bool above = umbraAboveTerrain(umbraPosMC, g, h) > 0.0;
  bool hit = false;
  float tPrev = 0.0;
  for (int k = 1; k <= umbraMarchSteps && !hit; ++k) {
    float t = above ? float(k) * step : max(-float(k) * step, tEye);
    bool over = umbraAboveTerrain(umbraPosMC + t * dir, g, h) > 0.0;
    if (above && !over) { hit = true; ta = tPrev; tb = t; }
    else if (!above && over) { hit = true; ta = t; tb = tPrev; }
    else if (!above && t <= tEye) break;
    tPrev = t;
  }
  if (!hit) discard;  // the ray misses the surface here (a silhouette)
  float fa = umbraAboveTerrain(umbraPosMC + ta * dir, g, h), fb = umbraAboveTerrain(umbraPosMC + tb * dir, g, h);
  for (int k = 0; k < umbraBisections; ++k) {
    float tm = 0.5 * (ta + tb);
    float fm = umbraAboveTerrain(umbraPosMC + tm * dir, g, h);
    if (fm > 0.0) { ta = tm; fa = fm; } else { tb = tm; fb = fm; }
  }
  // Within the last bracket (1/4096 of a step) the height along the ray is as good as straight.
  tb = fa - fb > 0.0 && fa < 1e29 && fb > -1e29 ? ta + (tb - ta) * fa / (fa - fb) : 0.5 * (ta + tb);
  if (umbraAboveTerrain(umbraPosMC + tb * dir, g, h) >= 1e29) discard;  // no data
  vec3 q = umbraPosMC + tb * dir;

  // The bilinear surface's normal, by central differences over a texel.
  vec3 dx = umbraSurfacePoint(g + vec2(0.5, 0.0)) - umbraSurfacePoint(g - vec2(0.5, 0.0));
  vec3 dy = umbraSurfacePoint(g + vec2(0.0, 0.5)) - umbraSurfacePoint(g - vec2(0.0, 0.5));
  vec3 n = normalize(cross(dx, dy));
  float cosi = max(dot(n, umbraTerrainLight), 0.0);
  // A slope turned away from the Sun is dark whatever the horizon: no search.
  float fraction = cosi > 0.0 || umbraTerrainOutput == 1 ? umbraTerrainFraction(g, h) : 0.0;
  vec3 radiance = umbraTerrainAlbedo * (umbraInvPi * umbraTerrainIrradiance * cosi * fraction);
  fragOutput0 = umbraTerrainOutput == 1 ? vec4(g, fraction, 1.0) : vec4(radiance, 1.0);

  if (umbraParallel == 1) {
    gl_FragDepth = gl_FragCoord.z;
  } else {
    float dist = max(length(q - eye), umbraLogDepthMinM);
    float depth = log2(dist / umbraLogDepthMinM) / umbraLogDepthOctaves;
    // The body's sphere (radius R, drawn by EclipseShading) would hide terrain below it:
    // such points go just in front of where the ray enters the sphere, in their order.
    vec3 e = eye;
    float b = dot(e, dir) + umbraRadiusM * dir.z;
    float c = dot(e, e) + 2.0 * umbraRadiusM * e.z;
    float disc = b * b - c;
    if (umbraParallel == 0 && c > 0.0 && b < 0.0 && disc >= 0.0) {
      float tS = c / (-b + sqrt(disc));
      if (dist > tS) depth = log2(max(tS, umbraLogDepthMinM) / umbraLogDepthMinM) / umbraLogDepthOctaves - 1e-5 * tS / dist;
    }
    gl_FragDepth = clamp(depth, 0.0, 1.0);
  }
}
