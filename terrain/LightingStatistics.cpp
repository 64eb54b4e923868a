#include "LightingStatistics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace umbra::terrain {

LightingAccumulator::LightingAccumulator(int width, int height) : width_(width), height_(height) {
  if (width < 1 || height < 1) throw std::invalid_argument("lighting statistics need at least one sample");
  const std::size_t n = static_cast<std::size_t>(width) * height;
  for (auto* v : {&litS_, &fractionS_, &litSteps_, &fractionSum_, &runS_, &longestS_}) v->assign(n, 0.0);
}

void LightingAccumulator::add(const std::vector<float>& fraction, double durationS) {
  if (fraction.size() != litS_.size())
    throw std::invalid_argument("lighting statistics: a map of " + std::to_string(fraction.size()) + " samples, expected " +
                                std::to_string(litS_.size()));
  if (!(durationS >= 0.0) || !std::isfinite(durationS))
    throw std::invalid_argument("lighting statistics: a step's duration must be finite and >= 0");
  for (std::size_t k = 0; k < fraction.size(); ++k) {
    const double v = fraction[k];
    if (!(v >= 0.0 && v <= 1.0))
      throw std::invalid_argument("lighting statistics: visible fraction " + std::to_string(v) + " outside [0, 1]");
    const bool lit = v > 0.0;
    litS_[k] += lit ? durationS : 0.0;
    fractionS_[k] += v * durationS;
    litSteps_[k] += lit ? 1.0 : 0.0;
    fractionSum_[k] += v;
    runS_[k] = lit ? 0.0 : runS_[k] + durationS;
    longestS_[k] = std::max(longestS_[k], runS_[k]);
  }
  totalS_ += durationS;
  ++steps_;
}

LightingMaps LightingAccumulator::maps() const {
  LightingMaps m;
  m.width = width_;
  m.height = height_;
  m.totalS = totalS_;
  const std::size_t n = litS_.size();
  m.litTimeFraction.resize(n);
  m.longestShadowS.resize(n);
  m.meanVisibleFraction.resize(n);
  const bool byTime = totalS_ > 0.0;
  const double steps = std::max<std::size_t>(steps_, 1);
  for (std::size_t k = 0; k < n; ++k) {
    m.litTimeFraction[k] = static_cast<float>(byTime ? litS_[k] / totalS_ : litSteps_[k] / steps);
    m.meanVisibleFraction[k] = static_cast<float>(byTime ? fractionS_[k] / totalS_ : fractionSum_[k] / steps);
    m.longestShadowS[k] = static_cast<float>(longestS_[k]);
  }
  return m;
}

} // namespace umbra::terrain
