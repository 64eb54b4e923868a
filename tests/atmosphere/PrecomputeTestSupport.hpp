#pragma once
// Small precomputation tables for tests: fast enough for the suite, fine enough for the
// closed-form and reference checks.
#include "Precompute.hpp"

namespace umbra::test {

inline atmosphere::PrecomputeOptions smallPrecomputeOptions() {
  atmosphere::PrecomputeOptions o;
  o.transmittanceWidth = 64;
  o.transmittanceHeight = 16;
  o.scatteringR = 8;
  o.scatteringMu = 32;
  o.scatteringMuS = 8;
  o.scatteringNu = 4;
  o.irradianceWidth = 16;
  o.irradianceHeight = 4;
  o.sphereSamples = 8;
  o.irradianceSamples = 16;
  o.singleScatteringSamples = 30;
  o.multipleScatteringSamples = 30;
  return o;
}

} // namespace umbra::test
