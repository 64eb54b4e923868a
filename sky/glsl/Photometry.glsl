// The Hapke–Lommel–Seeliger reflectance per fragment: the GLSL twin of sky/Photometry.cpp
// (the formulas are in sky/Photometry.hpp). The phase angle comes as its sine and cosine,
// from the cross and dot products of the unit directions to the light and to the eye:
// exact near 0, where acos of a float dot product is off by 3e-4 rad.
//
// umbraHapkeParameters: x = g (opposition width), y = w (Lambert share), z = c (forward).

const float umbraSkyPi = 3.14159265358979;

// B(alpha): 2 at 0, 1 from pi/2 on.
float umbraOppositionSurge(float sinPhase, float cosPhase, float g) {
  if (cosPhase <= 0.0) return 1.0;
  float t = sinPhase / cosPhase;
  if (t < 1.0e-20) return 2.0;
  float e = exp(-g / t);
  return 2.0 - t / (2.0 * g) * (1.0 - e) * (3.0 - e);
}

// S(alpha): 1 at 0.
float umbraGrainPhase(float sinPhase, float cosPhase, vec3 hapke) {
  float a = atan(sinPhase, cosPhase);
  float lambertSphere = (sinPhase + (umbraSkyPi - a) * cosPhase) / umbraSkyPi;
  float f = 1.0 - cosPhase;
  return (1.0 - hapke.y) + hapke.y * lambertSphere + hapke.z * f * f;
}

// F = 2/(3 pi) B S mu_i / (mu_i + mu_r), 1/sr; 0 where unlit or hidden.
float umbraHapkeReflectance(float cosIncidence, float cosEmergence, float sinPhase, float cosPhase, vec3 hapke) {
  if (cosIncidence <= 0.0 || cosEmergence <= 0.0) return 0.0;
  return 2.0 / (3.0 * umbraSkyPi) * umbraOppositionSurge(sinPhase, cosPhase, hapke.x) *
         umbraGrainPhase(sinPhase, cosPhase, hapke) * cosIncidence / (cosIncidence + cosEmergence);
}

// The same for unit vectors: the normal, the direction to the light and to the eye.
float umbraHapkeReflectanceOf(vec3 n, vec3 toLight, vec3 toEye, vec3 hapke) {
  return umbraHapkeReflectance(dot(n, toLight), dot(n, toEye), length(cross(toLight, toEye)), dot(toLight, toEye),
                               hapke);
}

// The relief's unit normal (sky/NormalMap.hpp, reliefNormal): the sphere's unit normal nb
// (body-fixed) tilted by the tangent-space texel t (RGB: east, south, up), its slopes times
// strength.
vec3 umbraReliefNormal(vec3 nb, vec3 t, float strength) {
  vec3 east = vec3(-nb.y, nb.x, 0.0);
  float l = length(east);
  east = l > 1.0e-6 ? east / l : vec3(0.0, 1.0, 0.0);
  vec3 north = cross(nb, east);
  vec3 d = 2.0 * t - vec3(1.0);
  return normalize(strength * (d.x * east - d.y * north) + max(d.z, 0.05) * nb);
}
