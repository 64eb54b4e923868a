#pragma once
// The eclipse through an occluder's atmosphere in the renderer (eclipse paper, 5.4):
// receivers take that occluder's shadow from the atmospheric shadow LuT
// (vtkEclipseShadowLutSource with an atmosphere; EclipseShading::SetAtmosphereShadowLut),
// computed only for the u columns the scene's receivers can be in (the source's update
// extent; the source caches each extent it computes).
#include "AtmosphereRendering.h"
#include "EclipseShading.h"
#include "SceneInputs.h"  // the renderer's types the glue fills

#include "ShadowLut.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkEclipseAtmosphereSource;
class vtkEclipseShadowLutSource;
class vtkLimbLuminanceSource;

namespace umbra::pipeline {

/// The u texel columns [first, last] of a `width`-wide shadow LuT that a bilinear lookup
/// reads for any point of `receiver` in the shadow of `occluder` (Eq. 4: u grows with the
/// distance from the occluder and shrinks with the distance from the Sun, so its extremes
/// are at the receiver's nearest and farthest points). Clamped to [0, width - 1].
std::array<int, 2> shadowLutColumns(const SunLight& sun, const SphereBody& occluder, const SphereBody& receiver,
                                    int width);

/// Whether any point of `receiver` can be in `occluder`'s penumbra: the sphere meets the
/// cone of the lines tangent to the Sun and the occluder that cross between them
/// (conservative: the cone's part before the occluder counts too).
bool canBeInPenumbra(const SunLight& sun, const SphereBody& occluder, const SphereBody& receiver);

/// The ranges of a shadow LuT for a scene (eclipse::lutRangeForDistances, as `umbra profile
/// shadow` chooses them): for each body of `receivers` that can be in the penumbra of a body
/// of `occluders` (not itself), its distances from that occluder (centre -+ radius, at least
/// the occluder's radius); the union of their u ranges, its ends moved out to a geometric
/// grid of relative step 1e-3 (a body moving a little keeps the range), v for it as eclipse::lutRangeForU
/// (`darkUmbra`: airless; `height` rows). None (a whole LuT) when no receiver can be in a
/// penumbra, when the distances reach the Sun, or when a whole LuT of `height` rows
/// resolves the penumbra there (eclipse::rangedLutPays is false: e.g. the Moon in Earth's
/// shadow at 256 rows).
std::optional<eclipse::LutRange> sceneLutRange(const SunLight& sun, const std::vector<SphereBody>& occluders,
                                               const std::vector<SphereBody>& receivers, bool darkUmbra, int height);
/// The same for a point (radius 0, e.g. the camera) behind `occluder`.
std::optional<eclipse::LutRange> pointLutRange(const SunLight& sun, const SphereBody& occluder,
                                               const glm::dvec3& pointM, bool darkUmbra, int height);
/// Columns of a ranged LuT: its u texel spacing no coarser than that of a whole LuT of
/// `width` columns (ceil(width (uMax - uMin)) + 1), in [2, width].
int rangedLutWidth(const eclipse::LutRange& range, int width);

/// The Sun's distance `distanceM` as eclipse tables are made for it: the nearest point of a
/// geometric grid of relative step 1e-4 (so that a scene in motion keeps its table for a
/// while; the Sun's angular radius off by 5e-5 of itself at most).
double sunDistanceOnGrid(double distanceM);

/// What an eclipse table of a scene's atmosphere is made for: the occluder (the body with
/// the atmosphere), its model and geometry, the table's `width` x `height` texels and its u,
/// v ranges (none: the whole table; ranged: rangedLutWidth columns). Equal requests give
/// the same table: a GUI computes one in a worker and keeps it while the request stays the
/// same.
struct EclipseTableRequest {
  std::string occluder;
  atmosphere::AtmosphereModelPtr model;  ///< requests are equal when its name() is
  double occluderRadiusM = 0.0, sunRadiusM = 0.0, sunOccluderDistanceM = 0.0;
  int width = 0, height = 0;
  std::optional<eclipse::LutRange> range;
  bool operator==(const EclipseTableRequest& o) const;
  bool operator!=(const EclipseTableRequest& o) const { return !(*this == o); }
};

/// What applySceneAtmosphereShadow computes for a scene: the ranges of sceneLutRange of the
/// other bodies and the texels [extent[0], extent[1]] x [extent[2], extent[3]] of the
/// table (ranged: all of its columns).
struct AtmosphereShadowRequest : EclipseTableRequest {
  std::array<int, 6> extent{};
  bool operator==(const AtmosphereShadowRequest& o) const;
  bool operator!=(const AtmosphereShadowRequest& o) const { return !(*this == o); }
};

/// What applySceneLimbLuminance computes for a scene: the ranges of pointLutRange of the
/// camera (the whole table when none).
struct LimbLuminanceRequest : EclipseTableRequest {};

/// The request for `in` with a table of `width` x `height` texels; none without an
/// atmosphere or when no other body can be shaded. Cheap (no table is touched).
std::optional<AtmosphereShadowRequest> sceneAtmosphereShadowRequest(const SceneInputs& in, int width, int height);

/// Sets `source` up for `request` (bodies, model, width, height; table sizes, limb views,
/// cache as the caller set them) and connects its atmosphere tables
/// (ConnectAtmosphereTables: from their cache); returns that tables source (to observe
/// its progress), or null.
vtkAlgorithm* setUpAtmosphereShadow(vtkEclipseShadowLutSource* source, const AtmosphereShadowRequest& request);

/// The long part: sets `source` up (setUpAtmosphereShadow) and computes the request's
/// texels (the source caches them by parameter hash; its width is given back after).
/// Throws std::runtime_error naming the body when the table cannot be made (or the
/// computation was aborted).
void updateAtmosphereShadow(vtkEclipseShadowLutSource* source, const AtmosphereShadowRequest& request);

/// When `in` has an atmosphere, sets `source` up for it (occluder = the body with the
/// atmosphere, its model, the Sun; table sizes, limb views, cache as the caller set them),
/// updates it and hands the result to `shading` (SetAtmosphereShadowLut). Near the
/// occluder (sceneLutRange of the other bodies: e.g. Phobos by Mars) the table covers only
/// their u and v ranges, rangedLutWidth columns of it; elsewhere the whole table's u columns
/// that every other body needs (shadowLutColumns; the source's ranges set to [0, 1]). The
/// source's width is given back after the update. Without an atmosphere, removes any.
/// Throws std::runtime_error naming the body when the table cannot be made.
void applySceneAtmosphereShadow(EclipseShading& shading, const SceneInputs& in, vtkEclipseShadowLutSource* source);

/// The limb-luminance LuT `in` needs with a table of `width` x `height` texels and a ring
/// drawn from it below `ringThresholdPx` on screen: when `in` has an atmosphere, the
/// threshold is > 0 and the camera is in that body's shadow (v < 1) outside the atmosphere
/// (where AtmosphereRendering can draw the ring from it); ranged around the camera's
/// distance when pointLutRange gives ranges (near the occluder: Phobos by Mars). None
/// otherwise. Cheap (no table is touched; the model is read for its top radius).
std::optional<LimbLuminanceRequest> sceneLimbLuminanceRequest(const SceneInputs& in, int width, int height,
                                                              double ringThresholdPx);

/// Sets `source` up for `request` as setUpAtmosphereShadow does; returns the tables source.
vtkAlgorithm* setUpLimbLuminance(vtkLimbLuminanceSource* source, const LimbLuminanceRequest& request);

/// The long part: sets `source` up (setUpLimbLuminance) and computes the table (the
/// source caches it by parameter hash; its width is given back after). Throws
/// std::runtime_error naming the body when the table cannot be made (or was aborted).
void updateLimbLuminance(vtkLimbLuminanceSource* source, const LimbLuminanceRequest& request);

/// When `in` needs a limb-luminance LuT (sceneLimbLuminanceRequest with the source's sizes
/// and `atmosphere`'s GetLimbRingThresholdPixels), updates `source` for it and hands it to
/// `atmosphere` (AtmosphereRendering::SetLimbLuminance: the ring drawn from it when thin on
/// screen). Otherwise removes any (nothing computed). Throws std::runtime_error naming the body.
void applySceneLimbLuminance(AtmosphereRendering& atmosphere, const SceneInputs& in, vtkLimbLuminanceSource* source);

/// Small tables for quick looks and tests (about a second): Bruneton tables as
/// useSmallAtmosphereTables with 2 orders, a 128x64 deviation table; the shadow LuT 64x32
/// with limb views of 32 rows and 4x4 scattering cells; the limb-luminance LuT 8 (u) x 32
/// (v) x 16 (beta) with views of 32 rows and 4x4 cells (fewer v rows put the ring's flux
/// off: docs/accuracy-vs-speed/gui.md, "The limb-luminance LuT in the GUI").
void useSmallEclipseShadowTables(vtkEclipseShadowLutSource* source);
void useSmallLimbLuminanceTables(vtkLimbLuminanceSource* source);

} // namespace umbra::pipeline
