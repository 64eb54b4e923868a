#include "MaximumMipmap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace umbra::terrain {
namespace {
constexpr double kNone = -std::numeric_limits<double>::infinity();
double validOrNone(double h) { return std::isnan(h) ? kNone : h; }
} // namespace

MaximumMipmap::MaximumMipmap(const HeightField& f) {
  f.validate();
  int w = f.width - 1, h = f.height - 1;
  std::vector<double> level0(static_cast<std::size_t>(w) * h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      level0[static_cast<std::size_t>(j) * w + i] =
          std::max({validOrNone(f.at(i, j)), validOrNone(f.at(i + 1, j)), validOrNone(f.at(i, j + 1)),
                    validOrNone(f.at(i + 1, j + 1))});
  this->maxima.push_back(std::move(level0));
  this->widths.push_back(w);
  this->heights.push_back(h);
  while (w > 1 || h > 1) {
    const int cw = (w + 1) / 2, ch = (h + 1) / 2;
    const std::vector<double>& fine = this->maxima.back();
    std::vector<double> coarse(static_cast<std::size_t>(cw) * ch, kNone);
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        double& m = coarse[static_cast<std::size_t>(j / 2) * cw + i / 2];
        m = std::max(m, fine[static_cast<std::size_t>(j) * w + i]);
      }
    this->maxima.push_back(std::move(coarse));
    this->widths.push_back(w = cw);
    this->heights.push_back(h = ch);
  }
}

} // namespace umbra::terrain
