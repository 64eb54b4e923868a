// The atmosphere's ring from the limb-luminance LuT (eclipse paper, 5.4), used by
// AtmosphereRendering instead of ray marching when the ring is thinner than a few pixels
// on screen (ray marching would alias: only a few rays of a pixel see the refracted Sun).
// Needs AtmosphereComposite.glsl before it (rays, frame depth, the Sun's disc). Perspective
// views only.
//
// The LuT holds, for the camera's (u, v) in the shadow (Eq. 4, computed on the CPU in
// double), the ring's radiance per unit solar irradiance averaged over its height, at
// beta in [0, pi] around the occluder from the direction of the Sun (u_limb of Eq. 7).
// A pixel at angle theta from the planet's centre is covered by the ring [phi_occ,
// phi_atmo] by the overlap of [theta - p/2, theta + p/2] with it, over p (the pixel's
// angle): summed over the pixels that keeps the ring's flux (2 pi theta w L).
// With one layer (the LuT's default) the ring is uniform across its height.

uniform sampler3D umbraLimbLuminance;  // u, v, beta / pi
uniform vec2 umbraLimbUv;              // the camera's (u, v) as texture coordinates (the LuT's ranges)
uniform float umbraLimbOccluder;       // phi_occ (rad): the ground's angular radius
uniform float umbraLimbAtmosphere;     // phi_atmo (rad): the top's
uniform float umbraLimbDistance;       // m, camera to the limb (in front of it: an object)
uniform vec3 umbraSunFromCamera;       // unit

float umbraAngle(vec3 a, vec3 b) {
  vec3 na = normalize(a), nb = normalize(b);
  return 2.0 * atan(length(na - nb), length(na + nb));
}

vec3 umbraLimbRing(vec2 uv) {
  vec2 ndc = 2.0 * uv - vec2(1.0);
  vec3 dir = normalize(umbraRayForward + ndc.x * umbraRayX + ndc.y * umbraRayY);
  vec3 frame = texture(umbraFrameColour, uv).rgb;
  float dFrame = umbraFrameDistance(texture(umbraFrameDepth, uv).r);
  if (dFrame < 0.9 * umbraLimbDistance) return frame;  // an object before the planet
  vec3 c = normalize(umbraPlanetFromCamera);
  float theta = umbraAngle(dir, c);
  float halfPixel = 0.5 * umbraPixelAngle;
  float cover = max(0.0, min(theta + halfPixel, umbraLimbAtmosphere) - max(theta - halfPixel, umbraLimbOccluder)) /
                umbraPixelAngle;
  // The Sun past the ring (its part behind the ring is in the LuT).
  vec3 background = dFrame >= umbraFarAway && theta > umbraLimbAtmosphere ? frame + vec3(umbraSunDisc(dir)) : frame;
  if (cover <= 0.0) return background;
  vec3 a = dir - dot(dir, c) * c;
  vec3 s = umbraSunFromCamera - dot(umbraSunFromCamera, c) * c;
  float beta = length(a) > 0.0 && length(s) > 0.0 ? umbraAngle(a, s) : 0.0;
  vec3 L = texture(umbraLimbLuminance, vec3(umbraLimbUv, beta / 3.14159265)).rgb;
  // Per channel, as the shadow LuT's I / I_sun: the ring is mostly the Sun's white light
  // through the air (the composite's T * Sun), so the channels scale the white Sun.
  return mix(background, L * umbraSolarIrradiance, cover);
}
