// The star splat (StarRendering.h): one GL point of size 2 per star, its 2 x 2 pixels
// weighted bilinearly and divided by their solid angle. The vertex stage (UMBRA_STAR_VERTEX)
// projects the star's direction with the perspective ray basis of AtmosphereComposite.glsl;
// the fragment stage writes E w / Omega.
// With UMBRA_MILKY_WAY (after sky/glsl/MilkyWay.glsl), the fragment stage of a full-screen
// quad at depth 1 instead: the Milky Way map's radiance in each empty pixel's direction.
// With UMBRA_SUN_DISC (after SunDisc.glsl), the same quad: the Sun's disc and its corona
// out to kSunCoronaReachSolarRadii (StarRendering.h), each pixel's mean radiance over 4 x 4 subsamples near the disc (the
// corona at the pixel's centre beyond), or for a disc less than 2 pixels in radius a splat
// of the Sun's whole irradiance as a star's (no corona).

uniform vec3 umbraRayForward;  // dir = F + x X + y Y at NDC (x, y)
uniform vec3 umbraRayX;
uniform vec3 umbraRayY;
uniform vec2 umbraViewportSize; // pixels

#ifdef UMBRA_STAR_VERTEX
in vec3 umbraStarDirection;
in vec3 umbraStarIrradiance;
flat out vec2 umbraStarPixel;      // window coordinates of the star's image point
flat out vec3 umbraStarIrradianceOut;

void main() {
  vec3 d = umbraStarDirection;
  float f = dot(d, umbraRayForward);
  vec2 ndc = vec2(dot(d, umbraRayX) / dot(umbraRayX, umbraRayX), dot(d, umbraRayY) / dot(umbraRayY, umbraRayY)) /
             max(f, 1e-30);
  if (f <= 0.0) ndc = vec2(4.0);  // behind the camera: clipped
  gl_Position = vec4(ndc, 1.0, 1.0);  // depth 1: drawn where the frame holds nothing
  gl_PointSize = 2.0;
  umbraStarPixel = (0.5 * ndc + vec2(0.5)) * umbraViewportSize;
  umbraStarIrradianceOut = umbraStarIrradiance;
}
#else
#if !defined(UMBRA_MILKY_WAY) && !defined(UMBRA_SUN_DISC)
flat in vec2 umbraStarPixel;
flat in vec3 umbraStarIrradianceOut;
#endif

// The solid angle of the pixel whose centre is at window coordinates p.
float umbraPixelSolidAngle(vec2 p) {
  vec2 ndc = 2.0 * p / umbraViewportSize - vec2(1.0);
  vec3 v = umbraRayForward + ndc.x * umbraRayX + ndc.y * umbraRayY;
  float l = length(v);
  return abs(dot(cross(umbraRayX, umbraRayY), umbraRayForward)) * 4.0 /
         (umbraViewportSize.x * umbraViewportSize.y * l * l * l);
}

#ifdef UMBRA_MILKY_WAY
uniform sampler2D umbraMilkyWayMap;  // linear RGB, 16-bit
uniform float umbraMilkyWayScale;    // texel value -> frame radiance [W m^-2 sr^-1]
uniform float umbraMilkyWayRows;     // the map's height in texels

// The map's radiance in the pixel's direction, its mipmap level chosen so that a texel
// (pi / rows high) spans about the pixel's footprint (sqrt(Omega) across).
vec4 umbraMilkyWay() {
  vec2 ndc = 2.0 * gl_FragCoord.xy / umbraViewportSize - vec2(1.0);
  vec3 d = normalize(umbraRayForward + ndc.x * umbraRayX + ndc.y * umbraRayY);
  float lod = 0.5 * log2(umbraPixelSolidAngle(gl_FragCoord.xy)) - log2(3.14159265358979 / umbraMilkyWayRows);
  return vec4(umbraMilkyWayScale * textureLod(umbraMilkyWayMap, umbraMilkyWayCoord(d), max(lod, 0.0)).rgb, 0.0);
}
#elif defined(UMBRA_SUN_DISC)
uniform vec3 umbraSunFromCamera;      // unit, world axes
uniform float umbraSunAngularRadius;  // rad
uniform float umbraSolarIrradiance;   // W m^-2 at the camera
uniform float umbraLimbDarkening;
uniform vec2 umbraSunPixel;           // window coordinates of the Sun's centre
uniform float umbraSunRadiusPixels;   // the disc's radius in pixels, at its place
const int umbraSunSubsamples = 4;
uniform float umbraSunCoronaRadii;    // the corona drawn out to this many solar radii (StarRendering.h)

vec4 umbraSunDisc() {
  if (umbraSunRadiusPixels < 2.0) {
    vec2 w = max(vec2(1.0) - abs(gl_FragCoord.xy - umbraSunPixel), vec2(0.0));
    return vec4(vec3(umbraSolarIrradiance * w.x * w.y / umbraPixelSolidAngle(gl_FragCoord.xy)), 0.0);
  }
  float d = length(gl_FragCoord.xy - umbraSunPixel);
  if (d > umbraSunCoronaRadii * umbraSunRadiusPixels + 2.0) return vec4(0.0);
  if (d > umbraSunRadiusPixels + 2.0) {  // the corona alone, smooth over a pixel
    vec2 ndc = 2.0 * gl_FragCoord.xy / umbraViewportSize - vec2(1.0);
    return vec4(vec3(umbraCorona(umbraRayForward + ndc.x * umbraRayX + ndc.y * umbraRayY, umbraSunFromCamera,
                                 umbraSunAngularRadius, umbraSolarIrradiance)), 0.0);
  }
  float sum = 0.0;
  for (int j = 0; j < umbraSunSubsamples; ++j)
    for (int i = 0; i < umbraSunSubsamples; ++i) {
      vec2 p = gl_FragCoord.xy + (vec2(float(i), float(j)) + vec2(0.5)) / float(umbraSunSubsamples) - vec2(0.5);
      vec2 ndc = 2.0 * p / umbraViewportSize - vec2(1.0);
      vec3 dir = umbraRayForward + ndc.x * umbraRayX + ndc.y * umbraRayY;
      sum += umbraLimbDarkenedSun(dir, umbraSunFromCamera, umbraSunAngularRadius, umbraSolarIrradiance, umbraLimbDarkening) +
             umbraCorona(dir, umbraSunFromCamera, umbraSunAngularRadius, umbraSolarIrradiance);
    }
  return vec4(vec3(sum / float(umbraSunSubsamples * umbraSunSubsamples)), 0.0);
}
#else
vec4 umbraStarSplat() {
  vec2 w = max(vec2(1.0) - abs(gl_FragCoord.xy - umbraStarPixel), vec2(0.0));
  return vec4(umbraStarIrradianceOut * (w.x * w.y / umbraPixelSolidAngle(gl_FragCoord.xy)), 0.0);
}
#endif
#endif
