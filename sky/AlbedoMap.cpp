#include "AlbedoMap.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace umbra::sky {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr float kDarkFraction = 0.1f;           // of the largest value: darker is a mark's texel
constexpr std::size_t kLargestSpotTexels = 400;  // a dark island this small or smaller is a mark or a hole
}

void validate(const AlbedoMap& map, const char* what) {
  const std::string who = what;
  if (map.width < 2 || map.height < 2)
    throw std::invalid_argument(who + ": an albedo map needs at least 2x2 values, got " + std::to_string(map.width) +
                                "x" + std::to_string(map.height));
  if (map.values.size() != static_cast<std::size_t>(map.width) * map.height)
    throw std::invalid_argument(who + ": " + std::to_string(map.values.size()) + " values for " +
                                std::to_string(map.width) + "x" + std::to_string(map.height));
  bool any = false;
  for (float v : map.values) {
    if (!(std::isfinite(v) && v >= 0.0f)) throw std::invalid_argument(who + ": a value is negative or not finite");
    any = any || v > 0.0f;
  }
  if (!any) throw std::invalid_argument(who + ": every value is 0");
}

int fillGaps(AlbedoMap& map, std::vector<char> gap) {
  const int w = map.width, h = map.height;
  std::vector<std::size_t> gaps;
  for (std::size_t k = 0; k < map.values.size(); ++k)
    if (gap[k]) gaps.push_back(k);
  if (gaps.size() == map.values.size()) return 0;
  const int filled = static_cast<int>(gaps.size());
  std::vector<std::pair<std::size_t, float>> next;
  std::vector<std::size_t> left;
  while (!gaps.empty()) {
    next.clear();
    left.clear();
    for (std::size_t k : gaps) {
      const int i = static_cast<int>(k % w), j = static_cast<int>(k / w);
      double sum = 0.0;
      int n = 0;
      for (int dj = -1; dj <= 1; ++dj) {
        const int jj = j + dj;
        if (jj < 0 || jj >= h) continue;
        for (int di = -1; di <= 1; ++di) {
          const std::size_t kk = static_cast<std::size_t>(jj) * w + (i + di + w) % w;
          if (!gap[kk]) sum += map.values[kk], ++n;
        }
      }
      if (n > 0) next.emplace_back(k, static_cast<float>(sum / n));
      else left.push_back(k);
    }
    for (const auto& [k, v] : next) map.values[k] = v, gap[k] = 0;
    gaps.swap(left);
  }
  return filled;
}

std::vector<char> darkSpots(const AlbedoMap& map) {
  const int w = map.width, h = map.height;
  const float largest = *std::max_element(map.values.begin(), map.values.end());
  std::vector<char> dark(map.values.size()), spots(map.values.size(), 0);
  for (std::size_t k = 0; k < map.values.size(); ++k) dark[k] = map.values[k] < kDarkFraction * largest;
  // The dark texels' 8-connected islands (longitude wraps); the small ones are marks.
  std::vector<char> seen(map.values.size(), 0);
  std::vector<std::size_t> island, stack;
  for (std::size_t start = 0; start < map.values.size(); ++start) {
    if (!dark[start] || seen[start]) continue;
    island.clear();
    stack.assign(1, start);
    seen[start] = 1;
    while (!stack.empty()) {
      const std::size_t k = stack.back();
      stack.pop_back();
      island.push_back(k);
      const int i = static_cast<int>(k % w), j = static_cast<int>(k / w);
      for (int dj = std::max(0, j - 1); dj <= std::min(h - 1, j + 1); ++dj)
        for (int di = -1; di <= 1; ++di) {
          const std::size_t kk = static_cast<std::size_t>(dj) * w + (i + di + w) % w;
          if (dark[kk] && !seen[kk]) seen[kk] = 1, stack.push_back(kk);
        }
    }
    if (island.size() > kLargestSpotTexels) continue;
    for (std::size_t k : island) {  // the island and its neighbours (JPEG ringing)
      const int i = static_cast<int>(k % w), j = static_cast<int>(k / w);
      for (int dj = std::max(0, j - 1); dj <= std::min(h - 1, j + 1); ++dj)
        for (int di = -1; di <= 1; ++di) spots[static_cast<std::size_t>(dj) * w + (i + di + w) % w] = 1;
    }
  }
  return spots;
}

double sample(const AlbedoMap& map, double lonRad, double latRad) {
  const double x = (lonRad + kPi) / (2.0 * kPi) * map.width - 0.5;
  const double y = std::clamp((latRad + 0.5 * kPi) / kPi * map.height - 0.5, 0.0, map.height - 1.0);
  const double fx = std::floor(x), fy = std::floor(y);
  const double tx = x - fx, ty = y - fy;
  auto column = [&](double i) {
    const long w = map.width;
    return static_cast<int>(((static_cast<long>(i) % w) + w) % w);
  };
  const int i0 = column(fx), i1 = column(fx + 1.0);
  const int j0 = static_cast<int>(fy), j1 = std::min(j0 + 1, map.height - 1);
  auto at = [&](int i, int j) { return static_cast<double>(map.values[static_cast<std::size_t>(j) * map.width + i]); };
  return (1.0 - ty) * ((1.0 - tx) * at(i0, j0) + tx * at(i1, j0)) + ty * ((1.0 - tx) * at(i0, j1) + tx * at(i1, j1));
}

double nearSideDiscMean(const AlbedoMap& map) {
  double sum = 0.0, weight = 0.0;
  for (int j = 0; j < map.height; ++j) {
    const double lat = ((j + 0.5) / map.height - 0.5) * kPi;
    for (int i = 0; i < map.width; ++i) {
      const double lon = ((i + 0.5) / map.width - 0.5) * 2.0 * kPi;
      const double mu = std::cos(lat) * std::cos(lon);
      if (mu <= 0.0) continue;
      const double w = mu * std::cos(lat);
      sum += w * map.values[static_cast<std::size_t>(j) * map.width + i];
      weight += w;
    }
  }
  return weight > 0.0 ? sum / weight : 0.0;
}

}  // namespace umbra::sky
