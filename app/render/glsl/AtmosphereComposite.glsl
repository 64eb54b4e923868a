// The atmosphere over the HDR frame (AtmosphereRendering, Algorithm 1 of the atmospheres
// paper). Needs atmosphere/glsl/Atmosphere.glsl and SunDisc.glsl before it. Full-screen quad: texCoord in
// [0, 1]^2. Lengths in metres; every position relative to the camera (or to the ray's
// origin for parallel views), computed in double on the CPU.

uniform sampler2D umbraFrameColour;
uniform sampler2D umbraFrameDepth;
uniform vec3 umbraPlanetFromCamera;   // planet centre - camera
uniform vec3 umbraCameraUp;           // (camera - planet centre) / |.|
uniform float umbraCameraRadius;      // |camera - planet centre|
uniform vec3 umbraRayForward;         // perspective: dir = normalize(F + x X + y Y)
uniform vec3 umbraRayX;
uniform vec3 umbraRayY;
uniform vec3 umbraRayOriginX;         // parallel: origin = x OX + y OY, dir = F
uniform vec3 umbraRayOriginY;
uniform int umbraParallel;
uniform float umbraNear;              // parallel: window depth 0 .. 1 = near .. far
uniform float umbraFar;
uniform vec3 umbraSunDirection;       // unit, from the planet towards the Sun
uniform float umbraSunAngularRadius;  // rad
uniform float umbraSolarIrradiance;   // W m^-2 at the planet
uniform float umbraLimbDarkening;
uniform mat3 umbraAtmToDisplay;       // table channels -> frame colour
uniform vec3 umbraGroundAlbedo;       // per table channel: the planet's receiver's (the frame's ground)
uniform int umbraGroundMapOn;         // 1: the ground's albedo from umbraGroundAlbedoMap
uniform sampler2D umbraGroundAlbedoMap;  // reflectance map (MapTexels): linear values
uniform mat3 umbraGroundToBodyFixed;  // planet axes -> the map's body-fixed frame
uniform float umbraGroundMapTexelM;   // a texel's width at the equator, m
uniform int umbraRefraction;          // 1: bend the rays that leave the atmosphere
uniform sampler2D umbraRefractionTable;  // deviation (rad), contact altitude (m) over (x_mu, x_r)
uniform float umbraTerrainMeanElevation;  // m (eclipse::TerrainModel): rough land at the contact
uniform float umbraPixelAngle;        // rad per pixel (perspective)
uniform int umbraLimbSubsamples;      // sub-rays across a pixel for the Sun through the limb (>= 1)
uniform vec3 umbraMoonDirection;      // unit, from the planet towards the Moon (UMBRA_MOON_LIGHT)
uniform vec3 umbraMoonIrradiance;     // per table channel, W m^-2 (the Sun's light: E_sun each)
uniform float umbraNightGlow;         // zenith radiance of the glow above the air, W m^-2 sr^-1 (0: none)
uniform float umbraGlowLayerRatio;    // the camera's radius over the glow layer's (< 1)
uniform float umbraCameraSunVisible;  // the Sun's visible fraction at the camera past the eclipsing bodies
uniform int umbraEclipsedSkyOn;       // 1: the sky from the eclipsed-sky grid (AtmosphereRendering)
uniform sampler2D umbraEclipsedSky;   // per unit irradiance, table channels, over (azimuth, elevation)
uniform vec3 umbraEclipsedSkyE1;      // the grid's azimuth origin at the camera (horizontal, unit)
uniform vec3 umbraEclipsedSkyE2;      // umbraCameraUp x umbraEclipsedSkyE1
uniform vec3 umbraEclipsedSkyIrradiance;  // its irradiance on level ground at the camera, per unit solar irradiance
uniform float umbraSunCoronaRadii;    // the corona's reach in solar radii (StarRendering.h)
#ifdef UMBRA_CLOUDS
// Cloud layers (sky/Clouds.hpp; needs sky/glsl/Clouds.glsl before this file).
uniform int umbraCloudCount;
uniform float umbraCloudRadius[4];    // m, from the planet's centre, within the atmosphere
uniform float umbraCloudTau[4];       // vertical optical depth where whole
uniform float umbraCloudCoverage[4];
uniform float umbraCloudScale[4];     // the layer's radius over its feature size
uniform int umbraCloudSeed[4];
uniform mat3 umbraCloudFrame[4];      // planet axes -> the noise's (body-fixed, turned by the wind)
uniform vec3 umbraCloudSunFactor;     // the eclipse at the camera: the direct sunlight on the clouds
#endif

const float umbraLogDepthMinM = 1.0e-3;           // as ReceiverFragment.glsl
const float umbraLogDepthOctaves = 53.150849518;
const float umbraFarAway = 3.0e38;
const float umbraGroundTolerance = 0.01;
const float umbraGroundRadiusToleranceM = 3.0;

// Distance along the ray to what the frame holds at this pixel (umbraFarAway: nothing).
float umbraFrameDistance(float depth) {
  if (depth >= 1.0) return umbraFarAway;
  if (umbraParallel == 1) return umbraNear + depth * (umbraFar - umbraNear);
  return umbraLogDepthMinM * exp2(depth * umbraLogDepthOctaves);
}

// The Sun's disc (SunDisc.glsl: linear limb darkening, mean radiance E / (pi alpha^2))
// seen along dir.
float umbraSunDisc(vec3 dir) {
  float corona = umbraCorona(dir, umbraSunDirection, umbraSunAngularRadius, umbraSolarIrradiance);
  vec3 a = normalize(dir);
  bool near = 2.0 * atan(length(a - umbraSunDirection), length(a + umbraSunDirection)) <
              umbraSunCoronaRadii * umbraSunAngularRadius;
  return umbraLimbDarkenedSun(dir, umbraSunDirection, umbraSunAngularRadius, umbraSolarIrradiance, umbraLimbDarkening) +
         (near ? corona : 0.0);
}

// The eclipsed sky's radiance along dir seen from the camera (AtmosphereRendering::
// eclipsedSkyDirections: azimuth from E1 towards E2 across the width, elevation
// (pi / 2) sign(t) t^2 with t from -1 to 1 up the height).
vec3 umbraEclipsedSkyRadiance(vec3 dir) {
  float e = asin(clamp(dot(dir, umbraCameraUp), -1.0, 1.0));
  float t = sign(e) * sqrt(abs(e) / 1.57079633);
  float a = atan(dot(dir, umbraEclipsedSkyE2), dot(dir, umbraEclipsedSkyE1));
  return texture(umbraEclipsedSky, vec2(a / 6.28318531 + 0.5, 0.5 * (t + 1.0))).rgb;
}

// The view ray's direction at ndc (perspective: through the pixel; parallel: forward,
// umbraRayX and Y being zero).
vec3 umbraRayDirection(vec2 ndc) { return normalize(umbraRayForward + ndc.x * umbraRayX + ndc.y * umbraRayY); }

// What a ray that misses the atmosphere sees: the frame, plus the Sun's disc where the
// frame holds nothing.
vec3 umbraBackground(vec3 frame, float dFrame, vec3 dir) {
  return dFrame >= umbraFarAway ? frame + vec3(umbraSunDisc(dir)) : frame;
}

// umbraBackground at the pixel uv: AtmosphereRendering draws it, a cheap program, outside
// the atmosphere's rectangle on screen, where every ray misses the atmosphere.
vec3 umbraAtmosphereBackground(vec2 uv) {
  return umbraBackground(texture(umbraFrameColour, uv).rgb, umbraFrameDistance(texture(umbraFrameDepth, uv).r),
                         umbraRayDirection(2.0 * uv - vec2(1.0)));
}

// Where a direction meets the image (perspective), in texture coordinates.
vec2 umbraImageOf(vec3 d) {
  float f = dot(d, umbraRayForward);
  vec2 ndc = vec2(dot(d, umbraRayX) / dot(umbraRayX, umbraRayX), dot(d, umbraRayY) / dot(umbraRayY, umbraRayY)) / f;
  return 0.5 * ndc + vec2(0.5);
}

// eclipse::TerrainModel::transmission: a ray whose contact altitude is below the mean land
// elevation is partly blocked, linearly from 0 m (blocked) to twice the mean (free).
float umbraTerrainTransmission(float contactAltitudeM) {
  if (umbraTerrainMeanElevation <= 0.0) return contactAltitudeM >= 0.0 ? 1.0 : 0.0;
  return clamp(contactAltitudeM / (2.0 * umbraTerrainMeanElevation), 0.0, 1.0);
}

// eclipse::refractedTransmittanceToTop: T along the refracted ray from (r, mu) to the top;
// a descending ray passes its periapsis r_bottom + contact, T(r_p, 0)^2 / T(r, -mu).
vec3 umbraRefractedTransmittanceToTop(float r, float mu, float contactAltitudeM) {
  if (mu >= 0.0) return umbraAtmTransmittanceToTop(r, mu);
  if (contactAltitudeM < 0.0) return vec3(0.0);
  vec3 tp = umbraAtmTransmittanceToTop(min(umbraAtmBottom + contactAltitudeM, r), 0.0);
  return min(tp * tp / max(umbraAtmTransmittanceToTop(r, -mu), vec3(1e-30)), vec3(1.0));
}

// Deviation (rad) and contact altitude (m) of the ray (r, mu).
vec2 umbraRefractionOf(float r, float mu) {
  return texture(umbraRefractionTable, umbraAtmTransmittanceUvSized(r, mu, vec2(textureSize(umbraRefractionTable, 0)))).rg;
}

// The exit direction of the ray dir leaving the atmosphere from x (radius r) after the
// deviation: turned towards the planet's centre.
vec3 umbraExitDirection(vec3 x, float r, vec3 dir, float deviation) {
  vec3 toCentre = -x / r;
  vec3 across = toCentre - dot(toCentre, dir) * dir;
  float l = length(across);
  return l > 0.0 ? cos(deviation) * dir + sin(deviation) * (across / l) : dir;
}

// The Sun through the atmosphere along the refracted ray entering at x (radius r, view
// cosine mu) along dir: its disc along the exit ray, times T along the refracted path and
// the terrain at the contact (as the limb views of eclipse/atmospheric).
vec3 umbraRefractedSun(vec3 x, float r, float mu, vec3 dir) {
  vec2 dc = umbraRefractionOf(r, mu);
  float sun = umbraSunDisc(umbraExitDirection(x, r, dir, dc.x));
  if (sun <= 0.0 || dc.y < 0.0) return vec3(0.0);
  return sun * umbraTerrainTransmission(dc.y) * umbraRefractedTransmittanceToTop(r, mu, dc.y);
}

// From outside the atmosphere: the Sun through the limb averaged over umbraLimbSubsamples
// rays across the pixel of dir, spread towards the planet's centre (from the camera):
// sub-rays past the top see the bare Sun, those into the ground nothing.
vec3 umbraLimbSun(vec3 centre, vec3 dir) {
  int n = max(umbraLimbSubsamples, 1);
  vec3 across = centre - dot(centre, dir) * dir;
  vec3 radial = length(across) > 0.0 ? normalize(across) : vec3(0.0);
  vec3 sun = vec3(0.0);
  for (int k = 0; k < n; ++k) {
    vec3 d = normalize(dir + ((float(k) + 0.5) / float(n) - 0.5) * umbraPixelAngle * radial);
    vec3 perp = centre - dot(centre, d) * d;
    float h = length(perp);
    if (h >= umbraAtmTop) {
      sun += vec3(umbraSunDisc(d));
    } else if (h > umbraAtmBottom) {
      vec3 xk = -perp - sqrt((umbraAtmTop - h) * (umbraAtmTop + h)) * d;
      sun += umbraRefractedSun(xk, umbraAtmTop, dot(xk, d) / umbraAtmTop, d);
    }
  }
  return sun / float(n);
}

// The frame's mean radiance over a footprint: the box of half-widths halfTexels (texels,
// from 0.5 to 3.5: a longer box keeps its middle 7 texels) about at (texture coordinates),
// each texel weighted by its overlap (a box over texels of constant value), texels holding
// a body (depth < 1) or off the frame counting as black. A box of one texel is a bilinear
// read; at a texel's centre, the texel.
vec3 umbraFrameOverFootprint(vec2 at, vec2 halfTexels) {
  ivec2 size = textureSize(umbraFrameColour, 0);
  vec2 h = clamp(halfTexels, vec2(0.5), vec2(3.5));
  vec2 lo = at * vec2(size) - h, hi = lo + 2.0 * h;
  ivec2 first = ivec2(floor(lo)), last = ivec2(ceil(hi)) - ivec2(1);  // 8 texels at most
  vec3 sum = vec3(0.0);
  for (int j = first.y; j <= last.y; ++j) {
    float wy = min(hi.y, float(j + 1)) - max(lo.y, float(j));
    for (int i = first.x; i <= last.x; ++i) {
      ivec2 t = ivec2(i, j);
      if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, size)) || texelFetch(umbraFrameDepth, t, 0).r < 1.0)
        continue;
      sum += (wy * (min(hi.x, float(i + 1)) - max(lo.x, float(i)))) * texelFetch(umbraFrameColour, t, 0).rgb;
    }
  }
  return sum / ((hi.x - lo.x) * (hi.y - lo.y));
}

// The background of a ray leaving the atmosphere from x (radius r, view cosine mu) with
// refraction (eclipse paper, section 4.2), attenuated along the refracted path: a ray bent
// into the ground sees black; else the exit ray (the view ray turned towards the planet's
// centre by the deviation) looks up the frame at its vanishing point, black where the
// frame holds something there (the ray passed behind it), plus the Sun's disc along the
// exit ray. From outside the atmosphere (centre: the planet's centre from the camera) the
// Sun's term is the mean of umbraLimbSubsamples rays across the pixel towards the centre:
// the light of a ring seen from the shadow comes through a band of the limb much thinner
// than a pixel until the ring is hundreds of pixels wide.
// The frame is read over the pixel's footprint: the deviation grows towards the horizon,
// so the exit rays of a pixel spread over J = 1 + d(deviation)/d(zenith angle) pixels
// along u, the image of the vertical (J from the deviation of the ray turned one pixel's
// angle further down at x: from inside the air, the next pixel's ray). The
// footprint is the pixel stretched by J along u, taken as its box (half-widths
// (1 + (J - 1) u_i^2) / 2): each texel's light reaches the pixels whose footprints cover
// it, over J, so a star is neither dropped nor doubled, and it comes through dimmed by
// J, as radiance is kept along a ray (refraction's dimming near the horizon).
vec3 umbraRefractedBackground(vec3 x, float r, float mu, vec3 dir, vec3 centre, bool outside) {
  vec2 dc = umbraRefractionOf(r, mu);
  vec3 exitDir = umbraExitDirection(x, r, dir, dc.x);
  vec3 seen = vec3(0.0);
  vec2 at = dot(exitDir, umbraRayForward) > 0.0 ? umbraImageOf(exitDir) : vec2(-1.0);
  // Off the frame by more than any footprint: nothing to read (and no overflowing index).
  if (dc.y >= 0.0 && all(greaterThan(at, vec2(-0.5))) && all(lessThan(at, vec2(1.5)))) {
    float sinZ = sqrt(max(1.0 - mu * mu, 0.0)), step = max(umbraPixelAngle, 1e-7);
    float muBelow = mu * cos(step) - sinZ * sin(step);
    float stretch = max((umbraRefractionOf(r, muBelow).x - dc.x) / step, 0.0);  // J - 1
    // u: where the exit ray's image moves as it turns further down (none straight up or down).
    vec2 u = (umbraImageOf(umbraExitDirection(x, r, exitDir, 1e-3)) - at) * vec2(textureSize(umbraFrameColour, 0));
    u = dot(u, u) > 0.0 ? normalize(u) : vec2(0.0);
    seen = umbraFrameOverFootprint(at, vec2(0.5) + 0.5 * stretch * u * u);
  }
  seen *= umbraTerrainTransmission(dc.y) * umbraRefractedTransmittanceToTop(r, mu, dc.y);
  if (!outside || umbraLimbSubsamples <= 1) return seen + umbraRefractedSun(x, r, mu, dir);
  return seen + umbraLimbSun(centre, dir);
}

// The night sky's glow (airglow, zodiacal light, unresolved stars) above the air, seen
// from inside it along a ray of view cosine mu: a thin emitting layer's van Rhijn factor
// 1 / sqrt(1 - (r / r_layer)^2 (1 - mu^2)) times its zenith radiance.
float umbraGlow(float mu) {
  float k = umbraGlowLayerRatio;
  return umbraNightGlow / sqrt(max(1.0 - k * k * (1.0 - mu * mu), 1e-4));
}

#ifdef UMBRA_CLOUDS
// The cloud density of layer k at the unit vector u from the planet's centre (0 outside a
// cloud, 1 where whole).
float umbraCloudDensityAt(int k, vec3 u) {
  float c = umbraCloudCoverage[k];
  if (c <= 0.0 || c >= 1.0) return clamp(c, 0.0, 1.0);
  return umbraCloudDensity(umbraCloudNoise(umbraCloudFrame[k] * u * umbraCloudScale[k], uint(umbraCloudSeed[k])), c);
}

// Where the ray from y (radius r0) towards the unit direction d crosses the sphere of
// radius rc >= r0, as a unit vector (straight up from y when d points down).
vec3 umbraCloudCrossing(vec3 y, float r0, vec3 d, float rc) {
  float m = dot(y, d) / r0;
  if (m <= 0.0) return y / r0;
  float s = (rc - r0) * (rc + r0) / (r0 * m + sqrt((rc - r0) * (rc + r0) + r0 * r0 * m * m));
  return normalize(y + s * d);
}

// The share of the light arriving at cosine mu0 (and of the sky's light) that the layers
// above the ground point y (radius r0) let through, direct and scattered (1 - R each). One
// point per layer: where the ray to the light crosses it (the sky's light too: most of it
// comes from around the light; straight up when the light is down).
vec2 umbraCloudsAboveGround(vec3 y, float r0, vec3 towardsLight) {
  float mu0 = dot(y, towardsLight) / r0;
  vec2 through = vec2(1.0);
  for (int k = 0; k < 4; ++k) {
    if (k >= umbraCloudCount) break;
    float tau = umbraCloudTau[k] * umbraCloudDensityAt(k, umbraCloudCrossing(y, r0, towardsLight, umbraCloudRadius[k]));
    through *= vec2(mu0 > 0.0 ? 1.0 - umbraCloudReflectance(tau, mu0) : 1.0,
                    1.0 - umbraCloudReflectance(tau, umbraCloudDiffuseCosine));
  }
  return through;
}

// The radiance (per unit irradiance at the top) the layer sends along the ray from the point
// c (radius rc, unit normal n), lit by the light at unit direction l: its direct light (times
// `direct`) and the sky's, reflected on the face the eye looks at (`above`) or through it.
vec3 umbraCloudLight(float tau, vec3 n, float rc, vec3 l, bool above, vec3 direct) {
  float mu0 = dot(n, l);
  vec3 eDirect = umbraAtmDirectIrradiance(rc, mu0) * direct, eSky = umbraAtmIndirectIrradiance(rc, mu0);
  float m0 = max(mu0, 0.0);
  float shareDirect = above ? umbraCloudReflectance(tau, m0) : umbraCloudDiffuseTransmittance(tau, m0);
  float shareSky = above ? umbraCloudReflectance(tau, umbraCloudDiffuseCosine)
                         : umbraCloudDiffuseTransmittance(tau, umbraCloudDiffuseCosine);
  return (shareDirect * eDirect + shareSky * eSky) * 0.31830988618;
}

// The cloud layers over `seen` (the radiance the ray brings without them, frame units), for
// the ray from x (radius r, view cosine mu, direction dir) that ends at dLimit, along which
// the air sends sEnd (the Sun's, per unit irradiance) and sEndMoon (the Moon's, W m^-2 sr^-1)
// and lets tEnd through. Each crossing within the ray, from the farthest in:
//   L <- t_v L + (1 - t_v) S(x -> c) + T(x, c) L_cloud(c)
// (t_v: the layer's transmittance along the view; S(x -> c) is in L already, and the layer
// hides t_v of it behind). S(x -> c) is the ray's in-scattering in proportion to its
// extinction, S_end (1 - T(x, c)) / (1 - T_end): a uniform source along the ray (a second
// scattering lookup per crossing would cost twice the atmosphere stage on a CPU rasteriser;
// the error: docs/clouds.md).
vec3 umbraCloudsOver(vec3 seen, vec3 x, float r, float mu, vec3 dir, float dLimit, bool ground, vec3 sEnd, vec3 tEnd,
                     vec3 sEndMoon) {
  float hitS[8];
  int hitLayer[8];
  int n = 0;
  for (int k = 0; k < 4; ++k) {
    if (k >= umbraCloudCount) break;
    float rc = umbraCloudRadius[k];
    float q = -r * mu;
    float disc = (rc - r) * (rc + r) + r * r * mu * mu;
    if (disc < 0.0) continue;
    float big = q + (q >= 0.0 ? 1.0 : -1.0) * sqrt(disc);
    float small = big != 0.0 ? (r - rc) * (r + rc) / big : 0.0;
    float roots[2] = float[2](big, small);
    for (int j = 0; j < 2; ++j) {
      if (roots[j] > 0.0 && roots[j] < dLimit && n < 8) {
        hitS[n] = roots[j];
        hitLayer[n] = k;
        ++n;
      }
    }
  }
  // Farthest first.
  for (int i = 1; i < 8; ++i) {
    if (i >= n) break;
    for (int j = i; j > 0 && hitS[j] > hitS[j - 1]; --j) {
      float ts = hitS[j]; hitS[j] = hitS[j - 1]; hitS[j - 1] = ts;
      int tl = hitLayer[j]; hitLayer[j] = hitLayer[j - 1]; hitLayer[j - 1] = tl;
    }
  }
  vec3 L = seen;
  for (int i = 0; i < 8; ++i) {
    if (i >= n) break;
    int k = hitLayer[i];
    float s = hitS[i];
    vec3 c = x + s * dir;
    float rc = length(c);
    vec3 nrm = c / rc;
    float tau = umbraCloudTau[k] * umbraCloudDensityAt(k, nrm);
    if (tau <= 0.0) continue;
    float muV = dot(dir, nrm);
    bool above = muV < 0.0;
    float tv = umbraCloudDirect(tau, max(abs(muV), 0.02));
    vec3 T = umbraAtmTransmittance(r, mu, s, ground, false);
    vec3 share = clamp((vec3(1.0) - T) / max(vec3(1.0) - tEnd, vec3(1e-6)), vec3(0.0), vec3(1.0));
    vec3 S = share * (sEnd * umbraSolarIrradiance + sEndMoon);
    vec3 light = umbraCloudLight(tau, nrm, rc, umbraSunDirection, above, umbraCloudSunFactor) * umbraSolarIrradiance;
#ifdef UMBRA_MOON_LIGHT
    light += umbraCloudLight(tau, nrm, rc, umbraMoonDirection, above, vec3(1.0)) * umbraMoonIrradiance;
#endif
    L = tv * L + umbraAtmToDisplay * ((1.0 - tv) * S + T * light);
  }
  return L;
}
#endif

// The ground's albedo at the ground point y (planet-centred), d from the camera: the
// uniform one, or the reflectance map there, at the mip level of a pixel's width on the
// ground across the line of sight (explicit: derivatives are undefined in this branch).
vec3 umbraGroundAlbedoAt(vec3 y, float d) {
  if (umbraGroundMapOn == 0) return umbraGroundAlbedo;
  vec3 nb = umbraGroundToBodyFixed * normalize(y);
  vec2 at = vec2(atan(nb.y, nb.x) / (2.0 * 3.14159265) + 0.5, asin(clamp(nb.z, -1.0, 1.0)) / 3.14159265 + 0.5);
  float lod = log2(max(umbraPixelAngle * d / umbraGroundMapTexelM, 1.0));
  return textureLod(umbraGroundAlbedoMap, at, lod).rgb;
}

vec3 umbraAtmosphereComposite(vec2 uv) {
  vec2 ndc = 2.0 * uv - vec2(1.0);
  vec3 dir = umbraRayDirection(ndc);
  vec3 centre = umbraPlanetFromCamera;  // planet centre relative to the ray's origin
  if (umbraParallel == 1) centre -= ndc.x * umbraRayOriginX + ndc.y * umbraRayOriginY;
  vec3 frame = texture(umbraFrameColour, uv).rgb;
  float dFrame = umbraFrameDistance(texture(umbraFrameDepth, uv).r);
  vec3 background = umbraBackground(frame, dFrame, dir);

  // The view ray against the top of the atmosphere, by its impact vector.
  float top = umbraAtmTop;
  float tc = dot(centre, dir);
  vec3 perp = centre - tc * dir;  // from the ray's closest point to the centre
  float h = length(perp);
  if (h >= top) return background;
  float q = sqrt((top - h) * (top + h));
  if (tc + q <= 0.0) return background;  // the shell is behind

  // x: the camera when inside the shell, else the entry point; r, mu there.
  float t0, r, mu;
  vec3 x;
  bool inside = umbraParallel == 0 && umbraCameraRadius < top;
  if (inside) {
    t0 = 0.0;
    r = umbraCameraRadius;
    x = r * umbraCameraUp;
    mu = dot(umbraCameraUp, dir);
  } else {
    t0 = max(tc - q, 0.0);
    x = -perp - q * dir;
    r = top;
    mu = dot(x, dir) / top;
  }
  if (dFrame <= t0) return frame;  // an object before the atmosphere

  float muS = dot(x, umbraSunDirection) / r;
  float nu = dot(dir, umbraSunDirection);
  bool ground = umbraAtmRayIntersectsGround(r, mu);
  float dEnd = ground ? umbraAtmDistanceToBottom(r, mu) : umbraAtmDistanceToTop(r, mu);
  float dObject = dFrame - t0;
  // What the frame holds within 1 % of the ground hit, or within 3 m of the ground's radius,
  // is the planet itself (its depth is that of the analytic sphere, but with float camera
  // matrices: grazing hits seen from a few km up move by a few tenths of a percent, from
  // 10 m up by a few percent); it becomes the analytic ground.
  bool onGround = ground && (dObject >= dEnd * (1.0 - umbraGroundTolerance) ||
                             length(x + dObject * dir) < umbraAtmBottom + umbraGroundRadiusToleranceM);
  bool onObject = !onGround && dObject < dEnd;

  // S(x), the same for the three cases (the sky's ray misses the ground): looked up once,
  // as the segment's T. A SIMD rasteriser (Mesa's llvmpipe) runs every branch, masked.
  vec3 sx = umbraAtmScatteredRadiance(r, mu, muS, nu, ground);
  // The Moon's light, when it counts (night; a program of its own, UMBRA_MOON_LIGHT): the
  // same tables, lit from the Moon.
#ifdef UMBRA_MOON_LIGHT
  float muM = dot(x, umbraMoonDirection) / r;
  float nuM = dot(dir, umbraMoonDirection);
  vec3 sxMoon = umbraAtmScatteredRadiance(r, mu, muM, nuM, ground);
#else
  vec3 sxMoon = vec3(0.0);
#endif
  // The cloud layers over what the ray brings (a program of its own, UMBRA_CLOUDS).
#ifdef UMBRA_CLOUDS
#define umbraWithClouds(L, sEnd, tEnd, sEndMoon) \
  umbraCloudsOver(L, x, r, mu, dir, onObject ? dObject : dEnd, ground, sEnd, tEnd, sEndMoon)
#else
#define umbraWithClouds(L, sEnd, tEnd, sEndMoon) (L)
#endif
  if (onGround || onObject) {
    float d = onGround ? dEnd : dObject;
    vec3 T = umbraAtmTransmittance(r, mu, d, ground, onGround);
    vec3 S = umbraAtmInScatteringFrom(sx, T, r, mu, muS, nu, d, ground, onGround);
#ifdef UMBRA_MOON_LIGHT
    vec3 moonS = umbraAtmInScatteringFrom(sxMoon, T, r, mu, muM, nuM, d, ground, onGround) * umbraMoonIrradiance;
#else
    vec3 moonS = vec3(0.0);
#endif
    if (onObject) return umbraWithClouds(T * frame + umbraAtmToDisplay * (S * umbraSolarIrradiance + moonS), S, T, moonS);
    vec3 y = x + dEnd * dir;
    float muSg = dot(normalize(y), umbraSunDirection);
    float rg = umbraAtmBottom;
    // The eclipse shadow of other bodies on the ground (EclipseShading lit the planet's
    // pixel as its uniform albedo / pi E_sun cos i times that factor, the Sun's visible
    // fraction there): it dims the direct sunlight, the sky's light on the ground and the
    // light the air scatters along the ray, all lit by the same partly hidden Sun. (The
    // Monte-Carlo sky of atmosphere/MonteCarloSky.hpp: the sky in the penumbra is the
    // uneclipsed one times the visible fraction within 5 % up to 89 % obscuration; the
    // column of air over a point shares its shadow to the penumbra's gradient over the
    // column's height. Inside the umbra this leaves the ground and its air black, where
    // light scattered in from the sunlit air around gives 1e-3 to 1e-4 of day.) The
    // ground's own albedo is that one, or its map's.
    vec3 albedo = umbraGroundAlbedoAt(y, t0 + dEnd);
    // (where the frame cannot tell, the Sun low or the ground's mesh missed at grazing
    // incidence, the eclipse at the camera stands for it)
    vec3 eclipse = vec3(umbraCameraSunVisible);
    vec3 unshadowed = umbraGroundAlbedo * (0.31830988618 * umbraSolarIrradiance * muSg);
    if (dFrame < umbraFarAway && muSg > 0.05 && all(greaterThan(unshadowed, vec3(0.0))))
      eclipse = clamp(frame / unshadowed, vec3(0.0), vec3(1.0));
#ifdef UMBRA_CLOUDS
    vec2 clouds = umbraCloudsAboveGround(y, rg, umbraSunDirection);  // direct, sky light
#else
    vec2 clouds = vec2(1.0);
#endif
    // The sky's light on the ground: under an eclipsed sky, that sky's (its irradiance at
    // the camera), else the tables' dimmed by the eclipse there.
    vec3 skyLight = umbraEclipsedSkyOn == 1 ? umbraEclipsedSkyIrradiance : eclipse * umbraAtmIndirectIrradiance(rg, muSg);
    vec3 E = clouds.x * eclipse * umbraAtmDirectIrradiance(rg, muSg) + clouds.y * skyLight;
    vec3 raw = T * albedo * 0.31830988618 * E + eclipse * S;
    vec3 moonRaw = moonS;
#ifdef UMBRA_MOON_LIGHT
    float muMg = dot(normalize(y), umbraMoonDirection);
#ifdef UMBRA_CLOUDS
    vec2 cloudsM = umbraCloudsAboveGround(y, rg, umbraMoonDirection);
#else
    vec2 cloudsM = vec2(1.0);
#endif
    vec3 Em = cloudsM.x * umbraAtmDirectIrradiance(rg, muMg) + cloudsM.y * umbraAtmIndirectIrradiance(rg, muMg);
    moonRaw += T * albedo * 0.31830988618 * Em * umbraMoonIrradiance;
#endif
    // A pixel on the limb seen from outside: the part of it past the ground sees the Sun
    // through the atmosphere (the ring seen from the shadow, a few pixels wide).
    vec3 limbSun = umbraRefraction == 1 && umbraParallel == 0 && !inside && umbraLimbSubsamples > 1 &&
                           h + 0.5 * umbraPixelAngle * tc > umbraAtmBottom
                       ? umbraLimbSun(centre, dir) : vec3(0.0);
    return umbraWithClouds(umbraAtmToDisplay * (raw * umbraSolarIrradiance + moonRaw) + limbSun, S, T, moonS);
  }
  // From inside the air during a solar eclipse the sky is the eclipsed one: the light of the
  // air lit by a partly hidden Sun, point by point, every order (no scattering table holds it).
  if (umbraEclipsedSkyOn == 1 && inside) sx = umbraEclipsedSkyRadiance(dir);
  vec3 sky = umbraAtmToDisplay * (sx * umbraSolarIrradiance + sxMoon * umbraMoonIrradiance);
  vec3 glow = inside && dFrame >= umbraFarAway ? umbraAtmTransmittanceToTop(r, mu) * umbraGlow(mu) : vec3(0.0);
  vec3 T = umbraAtmTransmittanceToTop(r, mu);
  vec3 skyMoon = sxMoon * umbraMoonIrradiance;
  if (umbraRefraction == 1 && umbraParallel == 0 && dFrame >= umbraFarAway)
    return umbraWithClouds(umbraRefractedBackground(x, r, mu, dir, centre, !inside) + glow + sky, sx, T, skyMoon);
  return umbraWithClouds(T * background + glow + sky, sx, T, skyMoon);
}
