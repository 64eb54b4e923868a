// The star splat (StarRendering.h): one GL point of size 2 per star, its 2 x 2 pixels
// weighted bilinearly and divided by their solid angle. The vertex stage (UMBRA_STAR_VERTEX)
// projects the star's direction with the perspective ray basis of AtmosphereComposite.glsl;
// the fragment stage writes E w / Omega.

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
flat in vec2 umbraStarPixel;
flat in vec3 umbraStarIrradianceOut;

// The solid angle of the pixel whose centre is at window coordinates p.
float umbraPixelSolidAngle(vec2 p) {
  vec2 ndc = 2.0 * p / umbraViewportSize - vec2(1.0);
  vec3 v = umbraRayForward + ndc.x * umbraRayX + ndc.y * umbraRayY;
  float l = length(v);
  return abs(dot(cross(umbraRayX, umbraRayY), umbraRayForward)) * 4.0 /
         (umbraViewportSize.x * umbraViewportSize.y * l * l * l);
}

vec4 umbraStarSplat() {
  vec2 w = max(vec2(1.0) - abs(gl_FragCoord.xy - umbraStarPixel), vec2(0.0));
  return vec4(umbraStarIrradianceOut * (w.x * w.y / umbraPixelSolidAngle(gl_FragCoord.xy)), 0.0);
}
#endif
