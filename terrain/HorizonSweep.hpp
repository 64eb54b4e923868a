#pragma once
// The visible fraction of the Sun at every sample of a height field at once, by a sweep
// along the Sun's azimuth: the fast path of lighting over time (LightingStatistics), where
// the DP search per sample (SoftShadow) is the reference.
//
// The samples are cut into strips one sample wide along the Sun's azimuth at the grid's
// centre (over a patch of 100 km the footprints are parallel to within 0.06 deg). In a
// strip, taken from its sunward end, each sample's horizon is its tangent to the upper
// convex hull of the samples sunward of it: with heights less the sphere's drop,
// g = h - a^2 / 2R (a along the strip), the terrain's elevation seen from p is
// (g_q - g_p) / (a_q - a_p) + a_p / R to second order in distance / R, so the highest is
// on the hull, and a vertex that the new sample hides is hidden from every sample behind
// it: amortised O(1) a sample (the sky-view sweep of terrain analysis).
//
// Against the DP search, the occluders are the strip's samples (up to half a sample aside
// of the footprint, not the bilinear surface under it) and the footprints are parallel;
// the errors are measured in docs/accuracy-vs-speed/terrain.md ("Lighting over time").
// No-data samples cast no shadow; a receiver there sits at HeightField::receiverHeight.
#include "EclipsedDisc.hpp"
#include "HeightField.hpp"
#include "SoftShadow.hpp"

#include <vector>

namespace umbra::terrain {

/// The visible fraction of `sun` at every sample, row-major like the heights, strips in
/// parallel; with an `occluder` in front of the Sun (EclipsedDisc.hpp: its place on the
/// disc seen from the grid's centre), the part of the disc above each sample's horizon and
/// outside the occluder. Throws std::invalid_argument for a bad field or Sun (as
/// visibleFractionMap).
std::vector<float> sweepVisibleFractionMap(const HeightField& field, const SunDisc& sun,
                                           const OccluderOnDisc* occluder = nullptr);

} // namespace umbra::terrain
