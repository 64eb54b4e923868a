#pragma once
// One batch of wavelengths through the precomputation: what its stages share (the model,
// the parametrisation, the sizes, the view rays, the working tables) and the stages
// themselves, one file each, in the order computeBatch runs them:
//   Transmittance.cpp      T to the top per (r, mu), along straight or refracted rays
//   Irradiance.cpp         the direct irradiance E_0, and the indirect E_k of each order
//   ViewRays.cpp           the view rays' samples, transmittance and single-scattering weights
//   SingleScattering.cpp   L_1 per component, without the phase function
//   ScatteringDensity.cpp  J_k: the light scattered at a point from every direction
//   MultipleScattering.cpp L_k from J_k along the view rays
// A stage's parallel tasks take its numbers (sizes, radii, the parametrisation) by value:
// with Runner::run's copy of the task on cache lines of its own, the threads then read
// nothing that the calling thread writes (read by reference from the stage's stack, they
// cost the scattering density up to 20 % with 2 threads).
// Each stage's test against a closed form or a brute-force integral
// (tests/atmosphere/test_precompute.cpp, Precompute.*): transmittance, VerticalTransmittance-
// IsExpOfVerticalOpticalDepth and HorizontalTransmittanceMatchesHighSampleIntegral;
// direct irradiance, DirectIrradianceIsTheTransmittanceTimesTheVisibleDisc; view rays and
// single scattering, SingleScatteringOpticallyThinLimit and SingleScatteringMatchesBrute-
// ForceIntegral; scattering density, indirect irradiance and multiple scattering,
// SecondOrderTwilightAtTheZenithMatchesBruteForce and NightSkyBelowTheLowestSunMatches-
// BruteForce. Their pieces: test_precompute_stages.cpp.
#include "Atmosphere.hpp"
#include "Precompute.hpp"
#include "Refraction.hpp"
#include "precompute/Model.hpp"
#include "precompute/Parametrisation.hpp"
#include "precompute/Runner.hpp"

#include <vector>

namespace umbra::atmosphere::stages {

/// A view ray's samples: positions, tangents, radii and the transmittance from the start.
struct RaySamples {
  int n = 0;          // intervals (n + 1 samples)
  double ds = 0.0;    // interval length
  bool ground = false;
  std::vector<double> r, xr, yr, tx, ty, mu;  // per sample; xr = x / r, yr = y / r; mu local
  std::vector<double> T;                      // [i * nl + l]
  std::vector<double> rhoT;  // [(i * ns + q) * nl + l]: int rho_q T_view hat_i ds
};

/// The 2D tables of a batch; its 3D tables go straight into the final ones (single, multiple:
/// all wavelengths wide, the batch's channels from l0 on), so that no batch-wide copy of
/// them is ever held.
struct BatchResult {
  Table2D transmittance, directIrradiance, irradiance;
  std::vector<std::vector<double>> orderMean;
};

/// The sphere of directions of the scattering density, per radius (ScatteringDensity.cpp).
struct DensityDirections {
  int nTh = 0, nPh = 0, nDir = 0;
  std::vector<double> wx, wy, wz, wdo;  // [z * nDir + j]: direction, solid angle
  std::vector<double> groundT;          // [(z * nTh + lt) * nl + l]: T to the ground
  std::vector<double> groundD;          // [z * nTh + lt]: distance to the ground, -1 for none
  std::vector<double> lobeIntegral;     // per lobe: its exact integral over the sphere
};

struct Batch {
  Batch(const Atmosphere& atm, const PrecomputeOptions& o, Runner& run, std::vector<FloatTable3D>& single,
        FloatTable3D& multiple, int l0);

  const Atmosphere& atm;
  const PrecomputeOptions& o;
  Runner& run;
  const Model m;
  const int nl, nc, ns;
  const ShellRadii shell;
  const double b, t, alpha;
  const ScatterGeometry g;
  const TexelPoints points;  // g.texel, tabulated
  const int W, MU, R, MUS, TW, TH, IW, IH;
  const std::size_t texels;
  std::vector<FloatTable3D>& single;  // per scatterer, all wavelengths wide
  FloatTable3D& multiple;             // all wavelengths wide
  const int l0;                  // the batch's first channel in them

  /// Without refraction, the transmittance texels' column densities [i * nc + c], which do
  /// not depend on the wavelength: computed by the first batch, read by the others (null: not
  /// shared).
  std::vector<double>* transmittanceColumns = nullptr;

  /// Refractive media: one per distinct refractivity (dispersion) for the transmittance,
  /// with the wavelengths that use it; the reference wavelength's for the scattering paths.
  std::vector<RefractiveMedium> media;
  std::vector<std::vector<int>> mediumUsers;
  RefractiveMedium referenceMedium;

  BatchResult out;
  std::vector<RaySamples> singleRays, multipleRays;
  /// L_{k-1} and J_k, in single precision (a relative 6e-8, far below the quadratures'
  /// error): half the memory of double, the largest share of a batch's.
  FloatTable3D delta, density;
  Table2D deltaE, nextE;   // E_{k-2} (from order 3 on) and E_{k-1}
  DensityDirections directions;

  /// Whether the multiple-scattering integrals take rays of their own (their sample count
  /// differs from the single scattering's), and the rays they take.
  bool ownMultipleScatteringRays() const { return o.multipleScatteringSamples != o.singleScatteringSamples; }
  const std::vector<RaySamples>& multipleScatteringRays() const {
    return ownMultipleScatteringRays() ? multipleRays : singleRays;
  }
  /// The irradiance table's texel (x, y): its radius and the Sun's cosine.
  void irradianceTexel(int x, int y, double& r, double& muS) const {
    r = b + (t - b) * y / (IH - 1.0);
    muS = clampCosine(-1.0 + 2.0 * x / (IW - 1.0));
  }
  /// L_{k-1}(r, mu, mu_s, nu) added into v: order 1 from the single tables (phases
  /// included), else delta.
  void incoming(int order, double r, double mu, double muS, double nu, bool ground, double* v) const {
    incoming(order, rMuCell(g, r, mu, ground), sNuCell(g, muS, nu), nu, v);
  }
  /// The same at the cells of (r, mu) and (mu_s, nu), for a caller that reuses them.
  void incoming(int order, const RMuCell& a, const SNuCell& c, double nu, double* v) const {
    if (order == 1) {
      // A buffer on the stack for up to 64 wavelengths (this runs a million times an order).
      double small[64];
      std::vector<double> large(nl > 64 ? nl : 0);
      double* tmp = nl > 64 ? large.data() : small;
      for (int q = 0; q < ns; ++q) {
        std::fill_n(tmp, nl, 0.0);
        accumulate4(single[q], a, c, 1.0, tmp, l0, nl);
        const Component& comp = atm.components[m.scatterers[q]];
        for (int l = 0; l < nl; ++l) v[l] += tmp[l] * comp.phase(l)(nu);
      }
    } else {
      accumulate4(delta, a, c, 1.0, v);
    }
  }
  /// The mean over the scattering texels of texelValue(x, y, z, v) per wavelength.
  template <class F>
  std::vector<double> meanOf(F&& texelValue) const {
    std::vector<double> sum(nl, 0.0);
    std::vector<double> v(nl);
    for (int z = 0; z < R; ++z)
      for (int y = 0; y < MU; ++y)
        for (int x = 0; x < W; ++x) {
          texelValue(x, y, z, v.data());
          for (int l = 0; l < nl; ++l) sum[l] += v[l];
        }
    for (double& s : sum) s /= static_cast<double>(texels);
    return sum;
  }
};

/// The sun's direction in the ray's frame (x: the view's azimuth).
inline double sunX(const ScatteringPoint& p) {
  const double sz = std::sqrt(std::max(0.0, (1.0 - p.mu) * (1.0 + p.mu)));
  const double ss = std::sqrt(std::max(0.0, (1.0 - p.muS) * (1.0 + p.muS)));
  if (sz < 1e-12) return ss;
  return std::clamp((p.nu - p.mu * p.muS) / sz, -ss, ss);
}

// The stages, in the order they run.
void computeTransmittance(Batch& batch);
void computeDirectIrradiance(Batch& batch);
void buildViewRays(Batch& batch, int samples, std::vector<RaySamples>& rays);
void computeSingleScattering(Batch& batch);
void prepareDensityDirections(Batch& batch);
void computeScatteringDensity(Batch& batch, int order);
void computeIndirectIrradiance(Batch& batch, int order);
void computeMultipleScattering(Batch& batch);

}  // namespace umbra::atmosphere::stages
