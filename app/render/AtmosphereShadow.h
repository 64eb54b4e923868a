#pragma once
// The eclipse through an occluder's atmosphere in the renderer (eclipse paper, 5.4):
// receivers take that occluder's shadow from the atmospheric shadow LuT
// (vtkEclipseShadowLutSource with an atmosphere; EclipseShading::SetAtmosphereShadowLut),
// computed only for the u columns the scene's receivers can be in (the source's update
// extent; the source caches each extent it computes).
#include "AtmosphereRendering.h"
#include "EclipseShading.h"

#include <array>

class vtkEclipseAtmosphereSource;
class vtkEclipseShadowLutSource;
class vtkLimbLuminanceSource;

namespace umbra::render {

struct SceneInputs;

/// The u texel columns [first, last] of a `width`-wide shadow LuT that a bilinear lookup
/// reads for any point of `receiver` in the shadow of `occluder` (Eq. 4: u grows with the
/// distance from the occluder and shrinks with the distance from the Sun, so its extremes
/// are at the receiver's nearest and farthest points). Clamped to [0, width - 1].
std::array<int, 2> shadowLutColumns(const SunLight& sun, const SphereBody& occluder, const SphereBody& receiver,
                                    int width);

/// When `in` has an atmosphere, sets `source` up for it (occluder = the body with the
/// atmosphere, its model, the Sun; table sizes, limb views, cache as the caller set them),
/// updates it for the columns every other body needs, and hands the result to `shading`
/// (SetAtmosphereShadowLut). Without an atmosphere, removes any. Throws
/// std::runtime_error naming the body when the table cannot be made.
void applySceneAtmosphereShadow(EclipseShading& shading, const SceneInputs& in, vtkEclipseShadowLutSource* source);

/// When `in` has an atmosphere and its camera is in that body's shadow (v < 1) outside the
/// atmosphere, sets `source` up for it as applySceneAtmosphereShadow does, updates it and
/// hands the limb-luminance LuT to `atmosphere`
/// (AtmosphereRendering::SetLimbLuminance: the ring drawn from it when thin on screen).
/// Otherwise removes any (nothing computed). Throws std::runtime_error naming the body.
void applySceneLimbLuminance(AtmosphereRendering& atmosphere, const SceneInputs& in, vtkLimbLuminanceSource* source);

/// Small tables for quick looks and tests (about a second): Bruneton tables as
/// useSmallAtmosphereTables with 2 orders, a 128x64 deviation table; the shadow LuT 64x32
/// with limb views of 32 rows and 4x4 scattering cells; the limb-luminance LuT 8x8x16
/// with views of 32 rows and 4x4 cells.
void useSmallEclipseShadowTables(vtkEclipseShadowLutSource* source);
void useSmallLimbLuminanceTables(vtkLimbLuminanceSource* source);

} // namespace umbra::render
