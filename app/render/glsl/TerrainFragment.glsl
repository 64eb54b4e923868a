// Fragment stage of a terrain patch (TerrainRendering): the view ray through the
// pre-displaced mesh is refined onto the bilinear height field (terrain paper, section 4),
// the visible fraction of the Sun is found there, and the point is shaded Lambertian:
// albedo / pi * E_sun * max(0, n . l) * fraction, linear radiance in W m^-2 sr^-1 like
// the eclipse receivers (ReceiverFragment.glsl). The fraction: with a shadow table
// (terrain/ShadowTable.hpp) the cell-by-cell search of terrain/glsl/TerrainShadow.glsl
// (which comes before this file) over the first umbraSearchToTexels of the footprint and
// the table's far horizon, bilinear; without one, the DP search over the whole footprint.
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
const int umbraBisections = 12;  // where the crossing has no closed form: then one step of false position

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
  vec4 h = umbraCellCorners(c);
  if (min(min(h.x, h.y), min(h.z, h.w)) > umbraNoData) return mix(mix(h.x, h.y, f.x), mix(h.z, h.w, f.x), f.y);
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

// The view ray's crossing of the bilinear surface between ta (above it) and tb (below), at
// most half a sample apart across the ground. The ray projects on the grid along a straight
// line (a central projection of a straight line): over it each cell's height is a
// quadratic in v, the fraction of the way from ta's grid point to tb's, and so, closely
// (to ~1e-7 of the stretch), is the ray's altitude, fitted at v = 0, 1/2, 1 (the ray's
// parameter follows v by the perspective division). The first root from ta, cell by cell,
// in closed form: the crossing's t, grid point and height. False where the stretch leaves
// the grid or touches no data (the caller bisects).
bool umbraCrossing(vec3 p0, vec3 dir, float ta, float tb, out float t, out vec2 g, out float h) {
  vec3 qa = p0 + ta * dir, qb = p0 + tb * dir;
  vec2 ga = umbraGridOf(qa), gb = umbraGridOf(qb), dg = gb - ga;
  vec2 top = vec2(umbraGridSize - 1);
  if (any(lessThan(min(ga, gb), vec2(0.0))) || any(greaterThan(max(ga, gb), top))) return false;
  // lambda(v): the ray's parameter (0 at ta, 1 at tb) where its grid point is ga + v dg.
  float wa = umbraRadiusM + qa.z, wb = umbraRadiusM + qb.z;
  float lambdaMid = wa / (wa + wb);
  float aa = umbraAltitudeOf(qa), ab = umbraAltitudeOf(qb), am = umbraAltitudeOf(mix(qa, qb, lambdaMid));
  float A2 = 2.0 * (aa + ab - 2.0 * am), A1 = ab - aa - A2;  // altitude(v) = aa + A1 v + A2 v^2
  float v = 0.0;
  for (int k = 0; k < 4 && v < 1.0; ++k) {
    float next = max(min(1.0, v + umbraToNextLine(ga + v * dg, dg)), v + 1e-6);
    ivec2 c = clamp(ivec2(floor(ga + 0.5 * (v + next) * dg)), ivec2(0), umbraGridSize - 2);
    vec4 corners = umbraCellCorners(c);
    float h00 = corners.x, h10 = corners.y, h01 = corners.z, h11 = corners.w;
    if (min(min(h00, h10), min(h01, h11)) <= umbraNoData) return false;
    // Height over the stretch: h00 + ax fx + ay fy + x fx fy, (fx, fy) = f0 + v dg.
    float ax = h10 - h00, ay = h01 - h00, x = (h00 - h10) - (h01 - h11);
    vec2 f0 = ga - vec2(c);
    float c0 = aa - (h00 + ax * f0.x + ay * f0.y + x * f0.x * f0.y);
    float c1 = A1 - (ax * dg.x + ay * dg.y + x * (f0.x * dg.y + f0.y * dg.x));
    float c2 = A2 - x * dg.x * dg.y;
    // The smallest root of c0 + c1 v + c2 v^2 in [v, next].
    float root = 2.0;
    float fv = c0 + (c1 + c2 * v) * v;
    if (fv <= 0.0) {
      root = v;
    } else if (abs(c2) < 1e-12 * (abs(c1) + abs(c0))) {
      if (c1 != 0.0) root = -c0 / c1;
    } else {
      float disc = c1 * c1 - 4.0 * c2 * c0;
      if (disc >= 0.0) {
        float q = -0.5 * (c1 + (c1 >= 0.0 ? sqrt(disc) : -sqrt(disc)));
        float r1 = q / c2, r2 = q != 0.0 ? c0 / q : r1;
        float lo = min(r1, r2), hi = max(r1, r2);
        root = lo >= v ? lo : hi;
      }
    }
    if (root >= v && root <= next) {
      g = ga + root * dg;
      vec2 f = f0 + root * dg;
      h = h00 + ax * f.x + ay * f.y + x * f.x * f.y;
      float lambda = root * wa / ((1.0 - root) * wb + root * wa);
      t = ta + lambda * (tb - ta);
      return true;
    }
    v = next;
  }
  return false;
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
// `far`: the table's far offset there (umbraFarOffsetAt; above -1: the disc is not wholly
// behind it).
float umbraTerrainFraction(vec2 g, float h, float far) {
  UmbraProfile p;
  if (!umbraMakeProfileAt(g, h, p)) return p.e > 0.0 ? 1.0 : 0.0;
#if UMBRA_TERRAIN_TABLE
  return umbraDiscFraction(min((p.e - umbraHorizonCells(p)) / umbraSunRadius, far), umbraLimbDarkening);
#else
  return umbraDiscFraction((p.e - umbraHorizonDP(p)) / umbraSunRadius, umbraLimbDarkening);
#endif
}

void umbraTerrainShade() {
  // (umbraEyeMC, from the inverse of VTK's float matrix, is off by ~1e-4 m a kilometre
  // from the patch's centre: too much 2 m above the ground.)
  vec3 eye = umbraTerrainEye;
  vec3 dir = umbraParallel == 1 ? umbraViewDirMC : normalize(umbraPosMC - eye);
  vec3 up = normalize(umbraPosMC + vec3(0.0, 0.0, umbraRadiusM));
  // View-ray refinement: from the facet point (on the mesh, just below the surface) step
  // back along the ray towards the eye (away from it should the point be above), half a
  // sample at a time across the ground, until the surface is crossed; then close in. The
  // crossing nearest the facet: the mesh's depth test orders the rest.
  float horizontal = sqrt(max(0.0, 1.0 - dot(dir, up) * dot(dir, up)));
  float step = 0.5 * umbraSpacingM / max(horizontal, 0.05);
  float tEye = umbraParallel == 0 ? -0.999 * length(umbraPosMC - eye) : -1e30;
  vec2 g;
  float h;
  float ta = 0.0, tb = 0.0, fa = 0.0, fb = 0.0;  // above, below the surface, and how far
  float tPrev = 0.0, fPrev = umbraAboveTerrain(umbraPosMC, g, h);
  bool above = fPrev > 0.0;
  bool hit = false;
  for (int k = 1; k <= umbraMarchSteps && !hit; ++k) {
    float t = above ? float(k) * step : max(-float(k) * step, tEye);
    float f = umbraAboveTerrain(umbraPosMC + t * dir, g, h);
    if (above && !(f > 0.0)) { hit = true; ta = tPrev; fa = fPrev; tb = t; fb = f; }
    else if (!above && f > 0.0) { hit = true; ta = t; fa = f; tb = tPrev; fb = fPrev; }
    else if (!above && t <= tEye) break;
    tPrev = t;
    fPrev = f;
  }
  if (!hit) discard;  // the ray misses the surface here (a silhouette)
  // The crossing in closed form (umbraCrossing); where it cannot be had, bisection.
  float tHit;
  if (!umbraCrossing(umbraPosMC, dir, ta, tb, tHit, g, h)) {
    for (int k = 0; k < umbraBisections; ++k) {
      float tm = 0.5 * (ta + tb);
      float fm = umbraAboveTerrain(umbraPosMC + tm * dir, g, h);
      if (fm > 0.0) { ta = tm; fa = fm; } else { tb = tm; fb = fm; }
    }
    tHit = fa - fb > 0.0 && fa < 1e29 ? ta + (tb - ta) * fa / (fa - fb) : 0.5 * (ta + tb);
    if (umbraAboveTerrain(umbraPosMC + tHit * dir, g, h) >= 1e29) discard;  // no data
  }
  tb = tHit;
  vec3 q = umbraPosMC + tb * dir;

  // Behind the table's far horizon the point is dark whatever its slope: no normal, no
  // search. Else the bilinear surface's normal, by central differences over a texel; a
  // slope turned away from the Sun is dark whatever the horizon: no search.
  float cosi = 0.0, fraction = 0.0, far = umbraFarOffsetAt(g);
  if (far > -1.0) {
    vec3 dx = umbraSurfacePoint(g + vec2(0.5, 0.0)) - umbraSurfacePoint(g - vec2(0.5, 0.0));
    vec3 dy = umbraSurfacePoint(g + vec2(0.0, 0.5)) - umbraSurfacePoint(g - vec2(0.0, 0.5));
    cosi = max(dot(normalize(cross(dx, dy)), umbraTerrainLight), 0.0);
    fraction = cosi > 0.0 || umbraTerrainOutput == 1 ? umbraTerrainFraction(g, h, far) : 0.0;
  }
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
