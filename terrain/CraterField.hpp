#pragma once
// A deterministic synthetic crater field (no lunar DEM ships offline): simple bowl-shaped
// craters with raised rims and ejecta blankets, superposed, with a power-law size
// distribution (cumulative number above diameter D falling as D^-2, the Moon's
// equilibrium slope), on a gently rolling plain. The same seed and size give the same
// heights on every platform (own 64-bit generator, no std:: distributions).
#include "HeightField.hpp"

#include <cstdint>

namespace umbra::terrain {

struct CraterFieldOptions {
  std::uint64_t seed = 1;
  int size = 512;                     ///< samples along each side (2 .. 8192)
  double spacingM = 30.0;
  double bodyRadiusM = kMoonRadiusM;
  double smallestDiameterTexels = 4.0;
  double largestDiameterFraction = 0.35;  ///< of the field's side
  double density = 0.25;              ///< crater area per field area in each factor-of-two size bin
};

/// Crater geometry (Pike 1977, fresh simple craters): depth 0.2 D below the rim crest,
/// rim 0.04 D above the plain; ejecta thickness falls as (r / R)^-3 out to 3 R.
HeightField makeCraterField(const CraterFieldOptions& options);

} // namespace umbra::terrain
