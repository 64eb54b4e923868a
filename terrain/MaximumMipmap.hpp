#pragma once
// The maximum mipmap of a height field (Tevs et al. 2008; terrain paper, section 3.2):
// level 0 holds, for each grid cell (the square between four samples), the largest of its
// four corner heights, which bounds the bilinear surface over the cell; level m holds the
// largest of the (up to) 2 x 2 level m-1 values below it, i.e. the maximum over a block of
// 2^m x 2^m cells. No-data samples are left out; a block with no valid sample holds -inf.
#include "HeightField.hpp"

#include <vector>

namespace umbra::terrain {

class MaximumMipmap {
public:
  explicit MaximumMipmap(const HeightField& field);

  int levels() const { return static_cast<int>(this->maxima.size()); }
  int width(int level) const { return this->widths[level]; }
  int height(int level) const { return this->heights[level]; }
  /// Maximum height [m] over block (bi, bj) of the level (cells bi*2^level ...).
  double max(int level, int bi, int bj) const {
    return this->maxima[level][static_cast<std::size_t>(bj) * this->widths[level] + bi];
  }
  /// Maximum over the whole field (the top level's single value).
  double globalMax() const { return this->maxima.back().front(); }
  const std::vector<double>& level(int m) const { return this->maxima[m]; }

private:
  std::vector<std::vector<double>> maxima;
  std::vector<int> widths, heights;
};

} // namespace umbra::terrain
