#pragma once
// Soft shadows of the Sun on a height field on a sphere (terrain paper, section 3).
//
// Every method reduces the Sun to the elevation of the terrain's horizon in the vertical
// plane through the receiver and the Sun's centre (the plane through the body's centre,
// the receiver and the Sun direction; its trace on the gnomonic grid is the straight
// footprint of the shadow ray). With the paper's prism assumption (section 3.4) the
// visible part of the disc is the circular segment above that horizon, Eq. 7, with
// d = (sun elevation - horizon elevation) / sun angular radius, both seen from the
// receiver: the quantity Eq. 6 forms in the paper's texture-space units.
//
// Methods:
//  - DynamicProgramming (Algorithm 1): the footprint is cut into concatenated intervals,
//    one texel of mip level N'-1 each; each interval is refined down the maximum mipmap
//    level by level, visiting every texel the footprint crosses (not the canonical DDA's
//    subset, Fig. 4b). A texel is refined only when the highest elevation its maximum
//    height allows (an exact bound over the texel's stretch of footprint) can still raise
//    the horizon inside the solar disc; the recursion's optimal cost is the horizon
//    elevation (the angle Delta h / t of Eq. 1, not Delta h alone: Eq. 3 would favour the
//    texels next to the receiver, Fig. 3b). Umbra (horizon above the disc's top) stops it.
//  - Uniform: a fixed number of equal steps along the footprint (the paper's baseline).
//  - Cells: every cell the footprint crosses, in order; inside a cell the bilinear height
//    along the footprint is a parabola and the elevation's highest point has a closed
//    form (cellSearch). Exact, and a constant few lookups a cell: for short stretches
//    (the near search of a shadow table), where the DP's mipmap buys nothing.
//  - Reference: many rays over the solar disc: the disc is cut into vertical strips, each
//    strip's rays have their own vertical plane, whose horizon is found with fine steps
//    over the bilinear surface; a ray is blocked when it lies below its strip's horizon.
//    No prism assumption; the limb-darkened flux of each strip's visible part is exact.
//
// All searches stop where the footprint leaves the grid (outside: no occluder) or where
// no terrain up to the field's maximum height can reach the disc's lower edge.
#include "HeightField.hpp"
#include "MaximumMipmap.hpp"

#include <glm/glm.hpp>

#include <functional>
#include <string>
#include <vector>

namespace umbra::terrain {

/// Angular radius of the Sun seen from 1 au [rad] (solar radius 696342 km).
inline constexpr double kSunAngularRadiusAt1AuRad = 696342e3 / 149597870700.0;

enum class ShadowMethod { DynamicProgramming, Uniform, Reference, Cells };

/// "dp", "uniform", "reference", "cells"; throws std::invalid_argument otherwise.
ShadowMethod parseShadowMethod(const std::string& name);
const char* shadowMethodName(ShadowMethod method);

struct SunDisc {
  glm::dvec3 direction{0.0, 0.0, 1.0};  ///< towards the Sun's centre, tangent frame (normalised on use)
  double angularRadiusRad = kSunAngularRadiusAt1AuRad;
  double limbDarkening = 0.0;            ///< 0: uniform disc (Eq. 7); else linear limb darkening (eclipse paper Eq. 1)
};

struct ShadowOptions {
  ShadowMethod method = ShadowMethod::DynamicProgramming;
  int levels = 6;                    ///< N': mip levels per concatenated interval (>= 1)
  int uniformSteps = 128;            ///< steps along the footprint for Uniform (>= 1)
  int referenceStrips = 32;          ///< vertical strips of the disc for Reference (>= 2)
  double referenceStepTexels = 0.125;  ///< step along each strip's footprint for Reference [texels]
  /// DP, Uniform and Cells: the horizon is resolved where it lies within this many solar radii of
  /// the Sun's centre (1: on the disc, all the fraction needs; the search stops once it
  /// is above, and leaves out terrain below). Shadow tables take more, to interpolate.
  double windowRadii = 1.0;
  /// DP, Uniform and Cells: the stretch of the footprint searched, from and to [texels] (the whole
  /// footprint by default; its start is where the local slope is taken). A shadow table
  /// keeps the horizon beyond its first texels; the renderer adds the slope nearby.
  double fromTexels = 1e-3, toTexels = 1e30;
  /// Throws std::invalid_argument naming the bad field.
  void validate() const;
};

/// The horizon towards the Sun's centre at one receiver.
struct Horizon {
  double sunElevationRad = 0.0;      ///< the Sun's centre above the receiver's horizontal
  double horizonElevationRad = 0.0;  ///< the highest terrain along the footprint (-inf: none)
  long long samples = 0;             ///< heights or mipmap texels looked at
  bool degenerate = false;           ///< the Sun at the receiver's zenith or nadir: no azimuth
};

/// Horizon towards the Sun for the receiver at sample (i, j) by DynamicProgramming, Uniform
/// or Cells (Reference has no single horizon: use visibleFraction).
Horizon horizonTowardsSun(const HeightField& field, const MaximumMipmap& mip, int i, int j, const SunDisc& sun,
                          const ShadowOptions& options);

/// The same for a receiver anywhere on the grid: grid coordinates (fractional, as
/// HeightField::planeM) and its height [m] (on the surface: field.bilinear(grid)). What
/// the renderer's view ray meets between samples (app/render/TerrainRendering).
Horizon horizonTowardsSunAt(const HeightField& field, const MaximumMipmap& mip, glm::dvec2 grid, double heightM,
                            const SunDisc& sun, const ShadowOptions& options);

/// Disc occlusion (Eq. 6-7): the visible fraction of the disc for a horizon, uniform or limb-darkened.
double discFractionAboveHorizon(const Horizon& horizon, const SunDisc& sun);
/// Eq. 7 alone: the visible fraction for the disc's centre d solar radii above the horizon.
double discFractionForOffset(double d, const SunDisc& sun);

/// Visible fraction of the solar disc (0 = umbra, 1 = fully lit) at sample (i, j).
/// `samples`, if given, receives the number of heights / texels looked at.
double visibleFraction(const HeightField& field, const MaximumMipmap& mip, int i, int j, const SunDisc& sun,
                       const ShadowOptions& options, long long* samples = nullptr);

/// The visible fraction at every sample (row-major like the heights), in parallel.
/// `progress` (optional) is called from one thread with the fraction done.
struct ShadowMapStats {
  long long samples = 0;
};
std::vector<double> visibleFractionMap(const HeightField& field, const MaximumMipmap& mip, const SunDisc& sun,
                                       const ShadowOptions& options,
                                       const std::function<void(double)>& progress = {},
                                       ShadowMapStats* stats = nullptr);

/// The horizon towards the Sun at every sample (row-major), in parallel: the DP, Uniform or
/// Cells search (std::invalid_argument for Reference, which has no single horizon).
std::vector<Horizon> horizonMap(const HeightField& field, const MaximumMipmap& mip, const SunDisc& sun,
                                const ShadowOptions& options, const std::function<void(double)>& progress = {},
                                ShadowMapStats* stats = nullptr);

} // namespace umbra::terrain
