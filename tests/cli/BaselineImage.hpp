#pragma once
// Image tests against baseline EXR files (tests/cli/baselines): the comparison, the
// baselines' rounding and their update (UMBRA_UPDATE_BASELINES=1 rewrites them).
//
// What is compared: the exposed radiance x = L * 2^exposureEV per channel (L from the
// render's EXR, W m^-2 sr^-1; the exposure from its header), the value the tone curve
// turns into the display (x = 1: white). The EXR's radiance does not depend on the
// exposure; x does, so a change of a scene's exposure fails the test as a change of its
// light does. Thresholds (docs/accuracy-vs-speed/image-tests.md):
//   - a value is off when |x - x_base| > 5 % of x_base + 1e-3 (1e-3: a tenth of an 8-bit
//     step of a mid-grey, invisible on the display);
//   - at most 1 % of the values may be off (the rim of a disc, the horizon or the Sun's
//     few pixels may move by a pixel between rasterisers: llvmpipe builds, GPUs);
//   - the mean of min(x, 4) per channel within 2 % of the baseline's (+ 1e-3): a uniform
//     change below the 5 % per value (e.g. 0.05 EV) still fails; clipped at 4 so that the
//     Sun's few pixels (x ~ 1e5) do not decide it.
#include "umbra/tables/Exr.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>

namespace umbra::test {

struct ImageDifference {
  double offFraction = 0.0;        ///< values off by more than 5 % + 1e-3
  double worstMeanRelative = 0.0;  ///< max over channels of |mean - mean_base| / (mean_base + 1e-3), of min(x, 4)
  bool sameSize = false;
  bool matches() const { return sameSize && offFraction <= 0.01 && worstMeanRelative <= 0.02; }
  std::string describe() const {
    std::ostringstream s;
    if (!sameSize) return "the sizes differ";
    s << 100.0 * offFraction << " % of the values off by > 5 % (limit 1 %), channel means off by "
      << 100.0 * worstMeanRelative << " % (limit 2 %)";
    return s.str();
  }
};

/// 2^exposureEV from a render's (or a baseline's) header; 1 when it has none.
inline double exposureScale(const tables::Table& t) {
  const auto it = t.parameters.find("exposureEV");
  return it == t.parameters.end() ? 1.0 : std::exp2(std::stod(it->second));
}

/// Compares a render with its baseline (both R, G, B radiance EXRs with exposureEV).
inline ImageDifference compareImages(const tables::Table& image, const tables::Table& baseline) {
  ImageDifference d;
  d.sameSize = image.width == baseline.width && image.height == baseline.height &&
               image.channels == baseline.channels && image.data.size() == baseline.data.size();
  if (!d.sameSize || image.data.empty()) return d;
  const double ka = exposureScale(image), kb = exposureScale(baseline);
  const std::size_t nc = image.channels.size(), n = image.data.size();
  std::size_t off = 0;
  std::vector<double> meanA(nc, 0.0), meanB(nc, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double a = ka * image.data[i], b = kb * baseline.data[i];
    off += !(std::abs(a - b) <= 0.05 * std::abs(b) + 1e-3);  // (a NaN is off)
    meanA[i % nc] += std::min(a, 4.0);
    meanB[i % nc] += std::min(b, 4.0);
  }
  d.offFraction = static_cast<double>(off) / static_cast<double>(n);
  for (std::size_t c = 0; c < nc; ++c) {
    const double rel = std::abs(meanA[c] - meanB[c]) / (meanB[c] + 1e-3 * static_cast<double>(n / nc));
    d.worstMeanRelative = std::isfinite(rel) ? std::max(d.worstMeanRelative, rel) : 1e300;
  }
  return d;
}

/// Rounds a float to 7 bits of mantissa (relative error below 0.4 %, far under the 5 % of
/// the comparison): the baselines' ZIP compression then keeps them at a few KB.
inline float roundMantissa(float v) {
  std::uint32_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  bits = (bits + (1u << 15)) & ~((1u << 16) - 1u);
  float out;
  std::memcpy(&out, &bits, sizeof out);
  return std::isfinite(out) ? out : v;
}

inline bool updatingBaselines() {
  const char* e = std::getenv("UMBRA_UPDATE_BASELINES");
  return e && std::string(e) == "1";
}

/// The baseline of `name` (tests/cli/baselines/NAME.exr); with UMBRA_UPDATE_BASELINES=1
/// first rewritten from `image` (rounded, with `command` and the render's header).
inline tables::Table baselineFor(const std::string& name, const tables::Table& image, const std::string& command) {
  const std::string path = UMBRA_SOURCE_DIR "/tests/cli/baselines/" + name + ".exr";
  if (updatingBaselines()) {
    tables::Table t = image;
    for (float& v : t.data) v = roundMantissa(v);
    t.parameters.erase("scene");  // (an absolute path of the machine that wrote it)
    t.parameters["command"] = command;
    tables::writeExr(path, t);
  }
  return tables::readExr(path, {"R", "G", "B"});
}

} // namespace umbra::test
