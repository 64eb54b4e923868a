#pragma once
// The Sun and the Moon over one eclipse (hours), interpolated: the eclipse predictions
// evaluate them thousands of times, and ELP's every term costs 2 ms a call.
#include "scene/Ephemeris.hpp"

#include <glm/glm.hpp>

#include <cmath>

namespace umbra::scene {

/// A vector function of time through its values at `Nodes` Chebyshev nodes of a window
/// (a polynomial of degree Nodes - 1).
template <int Nodes>
class ChebyshevInterpolated {
public:
  template <class F>
  ChebyshevInterpolated(double centreTt, double halfWidthDays, F f) : centre(centreTt), half(halfWidthDays) {
    for (int i = 0; i < Nodes; ++i) {
      nodes[i] = std::cos((2.0 * i + 1.0) * 3.14159265358979323846 / (2.0 * Nodes));  // in [-1, 1]
      values[i] = f(centre + half * nodes[i]);
    }
  }
  glm::dvec3 operator()(double tt) const {
    const double u = (tt - centre) / half;
    glm::dvec3 v(0.0);
    for (int i = 0; i < Nodes; ++i) {
      double w = 1.0;
      for (int j = 0; j < Nodes; ++j)
        if (j != i) w *= (u - nodes[j]) / (nodes[i] - nodes[j]);
      v += w * values[i];
    }
    return v;
  }

private:
  double centre, half;
  double nodes[Nodes];
  glm::dvec3 values[Nodes];
};

/// The Earth from epv00 and the Moon from Meeus' series plus ELP's difference from it (no
/// term of which is shorter than days), both interpolated over the window: ELP is summed
/// `Nodes` times an eclipse, not thousands. Four nodes over 0.35 day either side keep the
/// Moon within 1 m of ELP (EclipsesTest.InterpolatedMoon measures it).
template <int Nodes = 4>
struct EclipseEphemerides {
  EclipseEphemerides(double centreTt, double halfWidthDays)
      : earth(centreTt, halfWidthDays, [](double t) { return scene::earthHeliocentricM(t); }),
        elpCorrection(centreTt, halfWidthDays,
                      [](double t) { return moonGeocentricElpM(t) - moonGeocentricMeeusM(t); }) {}
  glm::dvec3 moonGeocentricM(double tt) const { return moonGeocentricMeeusM(tt) + elpCorrection(tt); }
  glm::dvec3 earthHeliocentricM(double tt) const { return earth(tt); }

  ChebyshevInterpolated<Nodes> earth, elpCorrection;
};

}  // namespace umbra::scene
