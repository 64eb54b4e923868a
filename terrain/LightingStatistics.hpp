#pragma once
// Lighting over time at every sample of a height field: what a landing site's planners ask
// of it. The time series of visible fractions of the Sun (one map per time step, from
// HorizonSweep or the DP search) is reduced, one step at a time, to three maps:
//  - the fraction of the time lit: the share of the time with any of the disc visible;
//  - the longest continuous shadow [s]: the longest run of steps with none of it visible;
//  - the mean visible fraction of the disc (the mean solar power on a panel facing the Sun,
//    as a share of a full Sun's).
// Each step stands for a duration its caller gives (`umbra terrain lighting`: the time
// nearer to it than to the other steps, within the range, so that the durations add up
// to the range); with no time at all (a range of one instant) the shares are the steps'.
#include <cstddef>
#include <vector>

namespace umbra::terrain {

struct LightingMaps {
  int width = 0, height = 0;
  double totalS = 0.0;                      ///< the time covered
  std::vector<float> litTimeFraction;       ///< row-major like the heights
  std::vector<float> longestShadowS;
  std::vector<float> meanVisibleFraction;
};

class LightingAccumulator {
public:
  /// Throws std::invalid_argument for a size below 1 x 1.
  LightingAccumulator(int width, int height);
  /// One step, in time order: the visible fraction at every sample (values in [0, 1]),
  /// standing for durationS >= 0 seconds. Throws std::invalid_argument for a map of
  /// another size, a negative or non-finite duration, or a fraction outside [0, 1].
  void add(const std::vector<float>& fraction, double durationS);
  /// The maps so far (the shares weighted by duration; with no time covered, by step).
  LightingMaps maps() const;
  std::size_t steps() const { return steps_; }

  /// The steps that follow this one's, reduced elsewhere (another rank's share of the
  /// time): afterwards this holds what adding them here one by one would have given (to
  /// the rounding of the sums; a shadow running across the join is one shadow). Throws
  /// std::invalid_argument for another size.
  void append(const LightingAccumulator& later);
  /// The whole state as numbers (to send between ranks), and back. fromState throws
  /// std::invalid_argument for a state of another size.
  std::vector<double> state() const;
  static LightingAccumulator fromState(int width, int height, const double* state, std::size_t count);

private:
  int width_, height_;
  std::size_t steps_ = 0;
  double totalS_ = 0.0;
  std::vector<double> litS_, fractionS_, litSteps_, fractionSum_, runS_, longestS_;
  std::vector<double> leadingS_, everLit_;  ///< the shadow from the first step on, and whether it ended (0 / 1)
};

} // namespace umbra::terrain
