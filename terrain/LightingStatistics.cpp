#include "LightingStatistics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace umbra::terrain {

LightingAccumulator::LightingAccumulator(int width, int height) : width_(width), height_(height) {
  if (width < 1 || height < 1) throw std::invalid_argument("lighting statistics need at least one sample");
  const std::size_t n = static_cast<std::size_t>(width) * height;
  for (auto* v : {&litS_, &fractionS_, &litSteps_, &fractionSum_, &runS_, &longestS_, &leadingS_, &everLit_})
    v->assign(n, 0.0);
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
    if (lit) everLit_[k] = 1.0;
    if (everLit_[k] == 0.0) leadingS_[k] += durationS;
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

void LightingAccumulator::append(const LightingAccumulator& later) {
  if (later.width_ != width_ || later.height_ != height_)
    throw std::invalid_argument("lighting statistics: appending another size");
  for (std::size_t k = 0; k < litS_.size(); ++k) {
    litS_[k] += later.litS_[k];
    fractionS_[k] += later.fractionS_[k];
    litSteps_[k] += later.litSteps_[k];
    fractionSum_[k] += later.fractionSum_[k];
    // A shadow running across the join: this one's last run and the later one's first.
    longestS_[k] = std::max({longestS_[k], later.longestS_[k], runS_[k] + later.leadingS_[k]});
    if (everLit_[k] == 0.0) leadingS_[k] += later.leadingS_[k];
    runS_[k] = later.everLit_[k] != 0.0 ? later.runS_[k] : runS_[k] + later.runS_[k];
    everLit_[k] = std::max(everLit_[k], later.everLit_[k]);
  }
  totalS_ += later.totalS_;
  steps_ += later.steps_;
}

std::vector<double> LightingAccumulator::state() const {
  std::vector<double> out{static_cast<double>(steps_), totalS_};
  for (const auto* v : {&litS_, &fractionS_, &litSteps_, &fractionSum_, &runS_, &longestS_, &leadingS_, &everLit_})
    out.insert(out.end(), v->begin(), v->end());
  return out;
}

LightingAccumulator LightingAccumulator::fromState(int width, int height, const double* state, std::size_t count) {
  LightingAccumulator a(width, height);
  const std::size_t n = a.litS_.size();
  if (count != 2 + 8 * n)
    throw std::invalid_argument("lighting statistics: a state of " + std::to_string(count) + " numbers, expected " +
                                std::to_string(2 + 8 * n));
  a.steps_ = static_cast<std::size_t>(state[0]);
  a.totalS_ = state[1];
  const double* at = state + 2;
  for (auto* v : {&a.litS_, &a.fractionS_, &a.litSteps_, &a.fractionSum_, &a.runS_, &a.longestS_, &a.leadingS_, &a.everLit_}) {
    v->assign(at, at + n);
    at += n;
  }
  return a;
}

} // namespace umbra::terrain
