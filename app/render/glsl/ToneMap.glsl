// Display transform of vtkUmbraRenderPass (full-screen quad): the HDR frame holds linear
// radiance in W m^-2 sr^-1. Display value = curve(radiance * 2^ExposureEV), sRGB-encoded.
//   umbraToneMapping 0 (Linear):   curve(x) = clamp(x, 0, 1)  -- exposure stays linear
//   umbraToneMapping 1 (Reinhard): curve(x) = x / (1 + x) per channel
// then the exact sRGB OETF (IEC 61966-2-1). No physics here.
// With umbraNightVision 1, the radiance is first seen as the eye sees dim light
// (sky/NightVision.hpp, its CPU twin): at each pixel's own adaptation, the cones' share m
// (CIE 191) of its colour and the rest a grey of its scotopic luminance.

uniform sampler2D umbraHdr;
uniform float umbraExposureScale;  // 2^ExposureEV
uniform int umbraToneMapping;
uniform int umbraNightVision;          // 1: mesopic/scotopic vision
uniform vec3 umbraSunLinearSrgb;       // sky::sunLinearSrgb: undoes the frames' white balance
uniform float umbraSunlightEfficacy;   // cd m^-2 per W m^-2 sr^-1 of sunlight
uniform float umbraSunlightScotopic;   // sunlight's scotopic / photopic ratio

float umbraScotopic(vec3 xyz) {
  return xyz.x > 0.0 ? max(xyz.y * (1.33 * (1.0 + (xyz.y + xyz.z) / xyz.x) - 1.68), 0.0) : 0.0;
}

vec3 umbraNightVisionColour(vec3 c) {
  vec3 u = c * umbraSunLinearSrgb;
  vec3 xyz = umbraSunlightEfficacy * vec3(dot(vec3(0.4124, 0.3576, 0.1805), u), dot(vec3(0.2126, 0.7152, 0.0722), u),
                                          dot(vec3(0.0193, 0.1192, 0.9505), u));
  float scotopic = umbraScotopic(xyz);
  float lp = max(xyz.y, 0.0);
  const float v0 = 683.0 / 1699.0;
  float m = 0.5;
  for (int i = 0; i < 8; ++i) {
    float mes = (m * lp + (1.0 - m) * scotopic * v0) / (m + (1.0 - m) * v0);
    m = clamp(0.7670 + 0.3334 * log(max(mes, 1e-30)) / log(10.0), 0.0, 1.0);
  }
  vec3 grey = vec3(scotopic / (umbraSunlightEfficacy * umbraSunlightScotopic));
  return mix(grey, c, m);
}

vec3 umbraToneCurve(vec3 x) {
  x = max(x, vec3(0.0));
  if (umbraToneMapping == 1) return x / (vec3(1.0) + x);
  return min(x, vec3(1.0));
}

vec3 umbraEncodeSrgb(vec3 c) {
  vec3 lo = 12.92 * c;
  vec3 hi = 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055;
  return mix(hi, lo, vec3(lessThanEqual(c, vec3(0.0031308))));
}

vec3 umbraDisplayColour(vec3 hdr) {
  if (umbraNightVision == 1) hdr = umbraNightVisionColour(hdr);
  return umbraEncodeSrgb(umbraToneCurve(hdr * umbraExposureScale));
}
