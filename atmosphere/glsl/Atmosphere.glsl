// GLSL twin of the atmosphere lookups: atmosphere/TextureCoords.cpp (the transmittance
// parametrisation) and the lookups of atmosphere/Precompute.cpp (transmittanceToTop,
// lookupScattering, skyRadiance, indirectIrradiance, directIrradiance), plus Bruneton
// 2017's transmittance between two points. Keep the two side by side:
// tests/render/test_atmosphere_glsl.cpp compares them pixel by pixel.
//
// All values are per unit solar irradiance, one channel per wavelength (R, G, B = 680,
// 550, 440 nm); lengths in metres, radii from the planet's centre. The tables are float
// textures (app/render/AtmosphereRendering.cxx uploads them), sampled with linear
// filtering at coordinates that never straddle two tables or the two halves of mu:
//   umbraAtmTransmittanceTable      2D, x_mu x x_r (texel centres on the unit-range ends)
//   umbraAtmScatteringTable         3D, (NU * MU_S) x MU x (R * (1 + components)): slab 0 is
//                              the multiple scattering, slab 1 + q the single scattering
//                              of component q (without its phase function)
//   umbraAtmIrradianceTable         2D, indirect irradiance, x_mu_s = (mu_s + 1) / 2, x_r linear
// The phase function of component q is the sum of two lobes k = 0, 1, per channel:
//   A (1 + B c^2) / (1 + g^2 - 2 g c)^(3/2),  A, B, g = umbraAtmPhase[6q + 3k + 0, 1, 2]
// (isotropic, Rayleigh, Penndorf, Henyey-Greenstein, Cornette-Shanks: one lobe; double
// Henyey-Greenstein: two), or, where umbraAtmPhaseTabulated[q] is 1 (Lorenz-Mie's tables),
//   umbraAtmPhaseTable              2D, RGB p(theta) at theta = pi i / (N - 1), i in [0, N),
//                              row q per component (linear between the samples).
// No VTK shader tag may appear in this file, comments included.

uniform sampler2D umbraAtmTransmittanceTable;
uniform sampler3D umbraAtmScatteringTable;
uniform sampler2D umbraAtmIrradianceTable;
uniform float umbraAtmSunAngularRadius;  // the tables' (options.sunAngularRadiusRad), for E_0
uniform float umbraAtmBottom;          // m
uniform float umbraAtmTop;             // m
uniform float umbraAtmMuSMin;          // the lowest sun in the tables
uniform int umbraAtmScatteringSize[4];  // R, MU, MU_S, NU
uniform int umbraAtmComponents;        // single-scattering tables (<= 4)
uniform vec3 umbraAtmPhase[24];
uniform sampler2D umbraAtmPhaseTable;
uniform int umbraAtmPhaseTabulated[4];

float umbraAtmSafeSqrt(float a) { return sqrt(max(a, 0.0)); }

// Bruneton's GetTextureCoordFromUnitRange.
float umbraAtmTexCoord(float x, float n) { return (0.5 + x * (n - 1.0)) / n; }

// distanceToTopBoundaryM (far intersection; r <= top).
float umbraAtmDistanceToTop(float r, float mu) {
  float t = umbraAtmTop;
  float outside = (t - r) * (t + r);
  float disc = max(0.0, outside + r * r * mu * mu);
  if (mu < 0.0) return max(0.0, -r * mu + sqrt(disc));
  float den = r * mu + sqrt(disc);
  if (outside <= 0.0 || den <= 0.0) return 0.0;
  return outside / den;
}

// distanceToBottomBoundaryM (near intersection).
float umbraAtmDistanceToBottom(float r, float mu) {
  float b = umbraAtmBottom;
  float above = (r - b) * (r + b);
  float disc = max(0.0, r * r * mu * mu - above);
  float den = -r * mu + sqrt(disc);
  if (den <= 0.0) return 0.0;
  return max(0.0, above / den);
}

bool umbraAtmRayIntersectsGround(float r, float mu) {
  float b = umbraAtmBottom;
  return mu < 0.0 && r * r * mu * mu - (r - b) * (r + b) >= 0.0;
}

// ---- transmittance -------------------------------------------------------------------

// transmittanceUvFromRMu (Eq. 2 of the eclipse paper) for a table of n texels (the
// transmittance and the refraction tables share it).
vec2 umbraAtmTransmittanceUvSized(float r, float mu, vec2 n) {
  float b = umbraAtmBottom, t = umbraAtmTop;
  r = clamp(r, b, t);
  mu = clamp(mu, -1.0, 1.0);
  float H = sqrt((t - b) * (t + b));
  float rho = umbraAtmSafeSqrt((r - b) * (r + b));
  float d = umbraAtmDistanceToTop(r, mu);
  float dMin = t - r, dMax = rho + H;
  float xMu = clamp((d - dMin) / (dMax - dMin), 0.0, 1.0);
  float xR = clamp(rho / H, 0.0, 1.0);
  return vec2(umbraAtmTexCoord(xMu, n.x), umbraAtmTexCoord(xR, n.y));
}
vec2 umbraAtmTransmittanceUv(float r, float mu) {
  return umbraAtmTransmittanceUvSized(r, mu, vec2(textureSize(umbraAtmTransmittanceTable, 0)));
}

// transmittanceToTop: T from (r, mu) to the top (below the horizon: the horizon's value).
vec3 umbraAtmTransmittanceToTop(float r, float mu) {
  return texture(umbraAtmTransmittanceTable, umbraAtmTransmittanceUv(r, mu)).rgb;
}

// The radius of the point at distance d along (r, mu). In float r^2 carries ~0.5 m of
// rounding at Earth's radius, which near the ground moves a lookup between the table's
// lowest layers: a point known to be on the ground (endsOnGround) gets the bottom radius.
float umbraAtmRadiusAlong(float r, float mu, float d, bool endsOnGround) {
  if (endsOnGround) return umbraAtmBottom;
  return clamp(sqrt(d * d + 2.0 * r * mu * d + r * r), umbraAtmBottom, umbraAtmTop);
}

// T between (r, mu) and the point at distance d along the ray (Bruneton 2017,
// GetTransmittance): a ratio of two transmittances to the top, taken upwards for rays
// that hit the ground.
vec3 umbraAtmTransmittance(float r, float mu, float d, bool rayHitsGround, bool endsOnGround) {
  float rd = umbraAtmRadiusAlong(r, mu, d, endsOnGround);
  float mud = clamp((r * mu + d) / rd, -1.0, 1.0);
  if (rayHitsGround) {
    return min(umbraAtmTransmittanceToTop(rd, -mud) /
                   max(umbraAtmTransmittanceToTop(r, -mu), vec3(1e-30)), vec3(1.0));
  }
  return min(umbraAtmTransmittanceToTop(r, mu) /
                 max(umbraAtmTransmittanceToTop(rd, mud), vec3(1e-30)), vec3(1.0));
}

// ---- scattering (Bruneton's 4D parametrisation, ScatterGeometry in Precompute.cpp) ----

// Distance from the ground to the top along mu_s (as ScatterGeometry::uMuS, no cancellation).
float umbraAtmDistanceToTopFromGround(float muS) {
  float b = umbraAtmBottom, t = umbraAtmTop;
  float H2 = (t - b) * (t + b);
  float root = sqrt(b * b * muS * muS + H2);
  return muS > 0.0 ? H2 / (b * muS + root) : root - b * muS;
}

float umbraAtmUMuS(float muS) {
  float b = umbraAtmBottom, t = umbraAtmTop;
  float H = sqrt((t - b) * (t + b));
  // D = distance from the ground to the top along muSMin; A its unit-range position.
  float D = umbraAtmDistanceToTopFromGround(umbraAtmMuSMin);
  float A = (D - (t - b)) / (H - (t - b));
  muS = clamp(muS, -1.0, 1.0);
  float d = umbraAtmDistanceToTopFromGround(muS);
  float a = (d - (t - b)) / (H - (t - b));
  return umbraAtmTexCoord(max(1.0 - a / A, 0.0) / (1.0 + a), float(umbraAtmScatteringSize[2]));
}

// One table of the scattering texture (slab 0: multiple, 1 + q: single of component q),
// quadrilinear: the hardware interpolates r, mu and mu_s, nu is interpolated here.
vec3 umbraAtmLookupScattering(int slab, float r, float mu, float muS, float nu, bool rayHitsGround) {
  float b = umbraAtmBottom, t = umbraAtmTop;
  float R = float(umbraAtmScatteringSize[0]), MU = float(umbraAtmScatteringSize[1]);
  float MUS = float(umbraAtmScatteringSize[2]), NU = float(umbraAtmScatteringSize[3]);
  float H = sqrt((t - b) * (t + b));
  r = clamp(r, b, t);
  float rho = umbraAtmSafeSqrt((r - b) * (r + b));
  float uR = umbraAtmTexCoord(clamp(rho / H, 0.0, 1.0), R);
  float uMu;
  float halfMu = 0.5 * MU;
  float fy;
  if (rayHitsGround) {
    float d = umbraAtmDistanceToBottom(r, mu);
    float dMin = r - b, dMax = rho;
    float x = dMax <= dMin ? 0.0 : clamp((d - dMin) / (dMax - dMin), 0.0, 1.0);
    uMu = 0.5 - 0.5 * umbraAtmTexCoord(x, halfMu);
    fy = clamp(uMu * MU - 0.5, 0.0, halfMu - 1.0);
  } else {
    float d = umbraAtmDistanceToTop(r, mu);
    float dMin = t - r, dMax = rho + H;
    float x = clamp((d - dMin) / (dMax - dMin), 0.0, 1.0);
    uMu = 0.5 + 0.5 * umbraAtmTexCoord(x, halfMu);
    fy = clamp(uMu * MU - 0.5, halfMu, MU - 1.0);
  }
  float fz = clamp(uR * R - 0.5, 0.0, R - 1.0);
  float fs = clamp(umbraAtmUMuS(muS) * MUS - 0.5, 0.0, MUS - 1.0);
  float fn = clamp(0.5 * (clamp(nu, -1.0, 1.0) + 1.0) * (NU - 1.0), 0.0, NU - 1.0);
  float kn = min(floor(fn), NU - 2.0);
  float wn = fn - kn;
  float depth = R * float(1 + umbraAtmComponents);
  float y = (fy + 0.5) / MU;
  float z = (float(slab) * R + fz + 0.5) / depth;
  float x0 = (kn * MUS + fs + 0.5) / (NU * MUS);
  float x1 = ((kn + 1.0) * MUS + fs + 0.5) / (NU * MUS);
  vec3 s0 = texture(umbraAtmScatteringTable, vec3(x0, y, z)).rgb;
  if (wn <= 0.0) return s0;
  vec3 s1 = texture(umbraAtmScatteringTable, vec3(x1, y, z)).rgb;
  return mix(s0, s1, wn);
}

// The phase function of component q at cos theta = nu, per channel.
vec3 umbraAtmPhaseOf(int q, float nu) {
  if (umbraAtmPhaseTabulated[q] != 0) {
    float n = float(textureSize(umbraAtmPhaseTable, 0).x);
    float theta = acos(clamp(nu, -1.0, 1.0)) / 3.14159265358979;
    return texture(umbraAtmPhaseTable, vec2(umbraAtmTexCoord(theta, n), (float(q) + 0.5) / 4.0)).rgb;
  }
  vec3 p = vec3(0.0);
  for (int k = 0; k < 2; ++k) {
    vec3 A = umbraAtmPhase[6 * q + 3 * k];
    vec3 B = umbraAtmPhase[6 * q + 3 * k + 1];
    vec3 g = umbraAtmPhase[6 * q + 3 * k + 2];
    vec3 x = max(vec3(1.0) + g * g - 2.0 * g * nu, vec3(1e-12));
    p += A * (vec3(1.0) + B * nu * nu) / (x * sqrt(x));
  }
  return p;
}

// Single scattering of every component times its phase, plus multiple (muS >= muSMin).
vec3 umbraAtmTableRadiance(float r, float mu, float muS, float nu, bool rayHitsGround) {
  vec3 L = umbraAtmLookupScattering(0, r, mu, muS, nu, rayHitsGround);
  for (int q = 0; q < 4; ++q) {
    if (q >= umbraAtmComponents) break;
    L += umbraAtmLookupScattering(1 + q, r, mu, muS, nu, rayHitsGround) * umbraAtmPhaseOf(q, nu);
  }
  return L;
}

// distanceToSunCosineM (TextureCoords.hpp): from r along mu to where the Sun's zenith
// cosine rises to m; 0 when muS >= m, umbraAtmNever when it never does.
const float umbraAtmNever = 3.0e38;
float umbraAtmDistanceToSunCosine(float r, float mu, float muS, float nu, float m) {
  if (muS >= m) return 0.0;
  if (m == 0.0) return nu > 0.0 ? -muS / nu * r : umbraAtmNever;  // linear
  float m2 = m * m;
  float A = nu * nu - m2, B = muS * nu - m2 * mu, C = muS * muS - m2;
  vec2 roots = vec2(-1.0);
  if (A == 0.0) {
    if (B != 0.0) roots.x = -0.5 * C / B;
  } else {
    float disc = B * B - A * C;
    if (disc < -1e-5 * (B * B + abs(A * C))) return umbraAtmNever;
    disc = max(disc, 0.0);
    float q = -(B + (B < 0.0 ? -sqrt(disc) : sqrt(disc)));
    roots.x = q / A;
    if (q != 0.0) roots.y = C / q;
  }
  float u = umbraAtmNever;
  if (roots.x >= 0.0 && (muS + roots.x * nu) * m >= 0.0) u = roots.x;
  if (roots.y >= 0.0 && (muS + roots.y * nu) * m >= 0.0) u = min(u, roots.y);
  return u >= umbraAtmNever ? umbraAtmNever : u * r;
}

// skyRadiance: the tables' radiance; below their lowest Sun (the air in the planet's
// shadow) the light from where the ray first reaches sunlit air, T(x, x_d) S(x_d), or none.
// One table lookup either way: Mesa's llvmpipe runs both sides of every branch, masked,
// and the lookup is the expensive part (docs/accuracy-vs-speed/atmosphere-tables.md, "Below the tables'
// lowest Sun": the night-side path costs llvmpipe ~10 % of the atmosphere pass).
vec3 umbraAtmScatteredRadiance(float r, float mu, float muS, float nu, bool rayHitsGround) {
  vec3 T = vec3(1.0);
  if (muS < umbraAtmMuSMin) {
    float end = rayHitsGround ? umbraAtmDistanceToBottom(r, mu) : umbraAtmDistanceToTop(r, mu);
    float d = umbraAtmDistanceToSunCosine(r, mu, muS, nu, umbraAtmMuSMin);
    if (d < end) {
      T = umbraAtmTransmittance(r, mu, d, rayHitsGround, false);
      float rd = umbraAtmRadiusAlong(r, mu, d, false);
      mu = clamp((r * mu + d) / rd, -1.0, 1.0);
      r = rd;
    } else {
      T = vec3(0.0);
    }
    muS = umbraAtmMuSMin;
  }
  return T * umbraAtmTableRadiance(r, mu, muS, nu, rayHitsGround);
}

// ---- irradiance ------------------------------------------------------------------------

// One row of the irradiance table across mu_s cell ix: geometric where the cell lies below
// the horizon and both nodes are lit, else linear (lookupIrradiance).
vec3 umbraAtmIrradianceRow(int ix, int iy, float wx, bool belowHorizon) {
  vec3 a = texelFetch(umbraAtmIrradianceTable, ivec2(ix, iy), 0).rgb;
  vec3 b = texelFetch(umbraAtmIrradianceTable, ivec2(ix + 1, iy), 0).rgb;
  vec3 straight = mix(a, b, wx);
  if (!belowHorizon) return straight;
  bvec3 lit = greaterThan(min(a, b), vec3(0.0));
  vec3 geometric = a * pow(max(b, vec3(1e-37)) / max(a, vec3(1e-37)), vec3(wx));
  return mix(straight, geometric, vec3(lit));
}

// indirectIrradiance and directIrradiance (E_0) on a horizontal surface at radius r.
vec3 umbraAtmIndirectIrradiance(float r, float muS) {
  if (muS < umbraAtmMuSMin) return vec3(0.0);  // below the tables' lowest Sun: dark
  ivec2 n = textureSize(umbraAtmIrradianceTable, 0);
  float fx = 0.5 * (clamp(muS, -1.0, 1.0) + 1.0) * float(n.x - 1);
  float fy = clamp((r - umbraAtmBottom) / (umbraAtmTop - umbraAtmBottom), 0.0, 1.0) * float(n.y - 1);
  int ix = min(int(fx), n.x - 2), iy = min(int(fy), n.y - 2);
  float wx = fx - float(ix), wy = fy - float(iy);
  bool belowHorizon = 2 * (ix + 1) <= n.x - 1;  // the cell's upper node at mu_s <= 0
  return mix(umbraAtmIrradianceRow(ix, iy, wx, belowHorizon), umbraAtmIrradianceRow(ix, iy + 1, wx, belowHorizon), wy);
}
// E_0 from the transmittance, not the table's interpolated cells (directIrradiance).
vec3 umbraAtmDirectIrradiance(float r, float muS) {
  float a = umbraAtmSunAngularRadius;
  float cosine = muS < -a ? 0.0 : (muS > a ? muS : (muS + a) * (muS + a) / (4.0 * a));
  return umbraAtmTransmittanceToTop(r, muS) * cosine;
}

// ---- the radiance along a view segment (Bruneton 2017, GetSkyRadianceToPoint) ---------

// In-scattered radiance between (r, mu) and the point at distance d along the ray, with
// the sun at cosines muS (zenith) and nu (view): S(x) - T(x, y) S(y). endsOnGround: the
// point is on the ground.
// umbraAtmInScatteringFrom: the same with S(x) = umbraAtmScatteredRadiance(r, mu, ...) and
// T(x, y) = umbraAtmTransmittance(r, mu, d, ...) already at hand (a caller that needs them
// too looks each up once).
vec3 umbraAtmInScatteringFrom(vec3 sx, vec3 T, float r, float mu, float muS, float nu, float d, bool rayHitsGround,
                              bool endsOnGround) {
  float rd = umbraAtmRadiusAlong(r, mu, d, endsOnGround);
  float mud = clamp((r * mu + d) / rd, -1.0, 1.0);
  float muSd = clamp((r * muS + d * nu) / rd, -1.0, 1.0);
  vec3 sy = umbraAtmScatteredRadiance(rd, mud, muSd, nu, rayHitsGround);
  return max(sx - T * sy, vec3(0.0));
}
vec3 umbraAtmInScatteringToPoint(float r, float mu, float muS, float nu, float d, bool rayHitsGround,
                                 bool endsOnGround) {
  return umbraAtmInScatteringFrom(umbraAtmScatteredRadiance(r, mu, muS, nu, rayHitsGround),
                                  umbraAtmTransmittance(r, mu, d, rayHitsGround, endsOnGround), r, mu, muS, nu, d,
                                  rayHitsGround, endsOnGround);
}
