// Display transform of vtkUmbraRenderPass (full-screen quad): the HDR frame holds linear
// radiance in W m^-2 sr^-1. Display value = curve(radiance * 2^ExposureEV), sRGB-encoded.
//   umbraToneMapping 0 (Linear):   curve(x) = clamp(x, 0, 1)  -- exposure stays linear
//   umbraToneMapping 1 (Reinhard): curve(x) = x / (1 + x) per channel
// then the exact sRGB OETF (IEC 61966-2-1). No physics here.

uniform sampler2D umbraHdr;
uniform float umbraExposureScale;  // 2^ExposureEV
uniform int umbraToneMapping;

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
  return umbraEncodeSrgb(umbraToneCurve(hdr * umbraExposureScale));
}
