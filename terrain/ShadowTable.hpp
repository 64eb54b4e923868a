#pragma once
// Shadow tables: the DP search's result at every sample of a height field for one position
// of the Sun, made once and looked up between samples, so that a pixel needs only a short
// search near its own point instead of the whole footprint.
//
// A sample holds the far horizon: the highest terrain along its footprint from `nearTexels`
// on, as the Sun's centre above it in solar radii,
//   d = (sun elevation - horizon elevation) / angular radius   (terrain paper, Eq. 6),
// resolved within kShadowTableOffsetLimit radii of the Sun and clamped there. A point
// between samples takes d bilinear from its four samples, and the near horizon from its
// own search over the first nearTexels + 1 texels (the samples' far stretches start up to
// a texel further along), cell by cell and exact (ShadowMethod::Cells); its d is the
// smaller, and the visible fraction follows by Eq. 7.
// The split is what makes a table work: the near terrain (the slope at the point, a rim a
// few samples away) turns the horizon within a sample, which no interpolation follows;
// seen from further, the horizon changes smoothly from sample to sample.
//
// A table serves every Sun within half a step of its own: the Sun's direction in the
// tangent frame is rounded to multiples of `stepRad` in elevation and in azimuth (from +y
// through +x), its angular radius to multiples of stepRad / 20 (roundedSun). The table is
// made for the rounded Sun; the shading's cosine keeps the exact one.
#include "HeightField.hpp"
#include "MaximumMipmap.hpp"
#include "SoftShadow.hpp"

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace umbra::terrain {

inline constexpr double kShadowTableOffsetLimit = 4.0;  ///< |d| kept [solar radii]
/// The default rounding of the Sun's direction: 0.01 deg (1/27 of the Sun's radius).
inline constexpr double kDefaultSunStepRad = 0.01 * 3.14159265358979323846 / 180.0;
/// The default stretch each point searches itself [texels].
inline constexpr double kDefaultNearTexels = 16.0;

/// The Sun rounded for a table (direction and angular radius; limb darkening kept).
/// Throws std::invalid_argument for a step not in (0, 0.1] rad or a zero direction.
SunDisc roundedSun(const SunDisc& sun, double stepRad);

struct ShadowTable {
  int width = 0, height = 0;
  std::vector<float> offsets;  ///< far d per sample, row-major like the heights
  SunDisc sun;                 ///< the (rounded) Sun it was made for
  double nearTexels = kDefaultNearTexels;

  /// The far d at grid coordinates (fractional; clamped to the grid), bilinear.
  double farOffsetAt(glm::dvec2 grid) const;
  /// The search near a point: cell by cell (ShadowMethod::Cells), up to nearTexels + 1.
  ShadowOptions nearSearch() const;
  /// The visible fraction at grid coordinates g on the bilinear surface: the far d, and the
  /// near horizon searched there (nearSearch).
  double fractionAt(const HeightField& field, const MaximumMipmap& mip, glm::dvec2 grid) const;
};

/// The table for `sun` (give it rounded) by the DP or Uniform search, rows in parallel;
/// `progress` as visibleFractionMap's. Throws std::invalid_argument as horizonMap, and for
/// nearTexels not in [0, 1024].
ShadowTable makeShadowTable(const HeightField& field, const MaximumMipmap& mip, const SunDisc& sun,
                            const ShadowOptions& options, double nearTexels = kDefaultNearTexels,
                            const std::function<void(double)>& progress = {});

/// What a table depends on, as the cache's parameters: the height field (a digest of its
/// heights, its size, spacing and radius), the rounded Sun (as multiples of the step), the
/// search's options, the near stretch and the offset limit.
std::map<std::string, std::string> shadowTableKey(const HeightField& field, const SunDisc& roundedSun, double stepRad,
                                                  const ShadowOptions& options, double nearTexels);

/// FNV-1a 64 over the field's size, spacing, radius and heights (every NaN alike), 16 hex digits.
std::string heightFieldDigest(const HeightField& field);

} // namespace umbra::terrain
