#pragma once
// A body's albedo map: an equirectangular image in body-fixed coordinates (the IAU
// rotation model's frame: latitude from the north pole axis, east longitude from the prime
// meridian), such as the Clementine mosaic of the Moon. Values are taken as proportional
// to the albedo; the map is scaled so that the disc it shows at zero phase from above
// (latitude 0, longitude 0: the Moon's near side at mean libration) has the body's
// geometric albedo.
#include <vector>

namespace umbra::sky {

/// width columns from east longitude -180 deg (the west edge of column 0) to +180 deg,
/// height rows from latitude -90 deg (the south edge of row 0) to +90 deg.
struct AlbedoMap {
  int width = 0;
  int height = 0;
  std::vector<float> values;  ///< row by row, row 0 southernmost; finite, >= 0
};

/// Throws std::invalid_argument (what is wrong, after `what`) unless the map has at
/// least 2x2 values, as many as width x height, all finite and >= 0, not all 0.
void validate(const AlbedoMap& map, const char* what);

/// Fills the texels where `gap` is non-zero with the mean of their filled neighbours,
/// growing in from the edges of each gap (longitude wraps); returns how many were filled.
/// A map that is all gap is left as it is.
int fillGaps(AlbedoMap& map, std::vector<char> gap);

/// The texels of a mosaic's small dark marks and holes (the Clementine JPEG has a grid of
/// black marks in the south and a few holes, with JPEG ringing around them): islands of at
/// most 400 texels (20 x 20) darker than 0.1 of the map's largest value, and their 8 neighbours.
/// Large dark areas (the polar shadows) and the maria (brighter) are not marked.
std::vector<char> darkSpots(const AlbedoMap& map);

/// The map at (longitude, latitude), bilinear between texel centres, wrapping in longitude
/// and clamped at the poles' rows: the CPU twin of the texture lookup.
double sample(const AlbedoMap& map, double lonRad, double latRad);

/// The mean of the map over the disc seen from latitude 0, longitude 0 at zero phase,
/// where the Lommel–Seeliger radiance is the same everywhere on the disc: each texel
/// weighted by its area projected on the disc, cos(lat) cos(lon) dS. The factor that
/// keeps the geometric albedo is 1 / this.
double nearSideDiscMean(const AlbedoMap& map);

}  // namespace umbra::sky
