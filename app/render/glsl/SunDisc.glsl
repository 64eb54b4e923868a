// The Sun's limb-darkened disc, seen along dir: the linear law of the eclipse paper's Eq. 1
// (eclipse::limbDarkenedLuminance, normalised to the disc's mean) times the disc's mean
// radiance E / (pi alpha^2). The one formula of the Sun's radiance on the GPU: the
// atmosphere's composite takes it through the air, the star stage (StarSplat.glsl,
// UMBRA_SUN_DISC) where no atmosphere is drawn.
float umbraLimbDarkenedSun(vec3 dir, vec3 sunDirection, float angularRadius, float irradiance, float limbDarkening) {
  vec3 a = normalize(dir), b = sunDirection;
  float angle = 2.0 * atan(length(a - b), length(a + b));
  if (angle >= angularRadius) return 0.0;
  float rho = angle / angularRadius;
  float u = limbDarkening;
  float profile = (1.0 - u * (1.0 - sqrt(max(1.0 - rho * rho, 0.0)))) / (1.0 - u / 3.0);
  return profile * irradiance / (3.14159265 * angularRadius * angularRadius);
}

// The corona around the disc (sky/Corona.hpp: Baumbach's K + F profile, averaged over position
// angle, in units of the disc's mean radiance) seen along dir; 0 on the disc itself.
float umbraCorona(vec3 dir, vec3 sunDirection, float angularRadius, float irradiance) {
  vec3 a = normalize(dir), b = sunDirection;
  float rho = 2.0 * atan(length(a - b), length(a + b)) / angularRadius;
  if (rho < 1.0) return 0.0;
  float relative = 1.0e-6 * (0.0532 * pow(rho, -2.5) + 1.425 * pow(rho, -7.0) + 2.565 * pow(rho, -17.0));
  return relative * irradiance / (3.14159265 * angularRadius * angularRadius);
}
