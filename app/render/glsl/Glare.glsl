// One separable pass of the glare of vtkUmbraRenderPass (Glare.h): light of every source
// texel s spread along one axis with the kernel w(j), j = -R..R (sum 1), renormalised by
// the part of the kernel that lands inside the frame, N(s) = sum of w(j) for s + j in
// [0, L): no energy leaves the frame and none is made (a scatter written as a gather).
//   out(x) = scale * sum_j src(x - j) w(j) / N(x - j)
// R = 0 with w = (1) and N = 1 is a scaled copy.

uniform sampler2D umbraGlareSource;
uniform ivec2 umbraGlareStep;          // (1, 0): along rows; (0, 1): along columns
uniform int umbraGlareRadius;          // R <= 64
uniform int umbraGlareLength;          // L: the frame's extent along the step
uniform float umbraGlareWeight[129];   // w(j) at index j + R
uniform float umbraGlarePrefix[130];   // prefix[i] = sum of weight[k] for k < i
uniform float umbraGlareScale;

vec3 umbraGlare(ivec2 p) {
  int x = p.x * umbraGlareStep.x + p.y * umbraGlareStep.y;
  int r = umbraGlareRadius;
  vec3 sum = vec3(0.0);
  for (int j = -r; j <= r; ++j) {
    int s = x - j;
    if (s < 0 || s >= umbraGlareLength) continue;
    int hi = min(r, umbraGlareLength - 1 - s);
    int lo = max(-r, -s);
    float inside = umbraGlarePrefix[hi + r + 1] - umbraGlarePrefix[lo + r];
    sum += texelFetch(umbraGlareSource, p - umbraGlareStep * j, 0).rgb * (umbraGlareWeight[j + r] / inside);
  }
  return umbraGlareScale * sum;
}
