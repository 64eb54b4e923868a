#pragma once
// One batch of wavelengths through the precomputation: what its stages share (the model,
// the parametrisation, the sizes, the view rays, the working tables) and the stages
// themselves, one file each, in the order computeBatch runs them:
//   Transmittance.cpp      T to the top per (r, mu), along straight or refracted rays
//   Irradiance.cpp         the direct irradiance E_0, and the indirect E_k of each order
//   ViewRays.cpp           the view rays' samples, column densities and single-scattering weights
//   SingleScattering.cpp   L_1 per component, without the phase function (tracing the view rays)
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

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace umbra::atmosphere::stages {

/// A view ray's samples: positions, tangents, radii and the column densities from the start
/// (nc a sample, not nl: the transmittance is made from them where it is needed).
struct RaySamples {
  int n = 0;          // intervals (n + 1 samples)
  double ds = 0.0;    // interval length
  bool ground = false;
  std::vector<double> r, xr, yr, tx, ty, mu;  // per sample; xr = x / r, yr = y / r; mu local
  std::vector<double> col;                    // [i * nc + c]: int rho_c ds from the start
};

/// The transmittance from the ray's start at each of its samples, T[i * nl + l].
inline void rayTransmittance(const Model& m, const RaySamples& s, double* T) {
  for (int i = 0; i <= s.n; ++i) {
    double* Ti = T + static_cast<std::size_t>(i) * m.nl;
    m.opticalDepth(&s.col[static_cast<std::size_t>(i) * m.nc], Ti);
    for (int l = 0; l < m.nl; ++l) Ti[l] = std::exp(-Ti[l]);
  }
}

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
  /// The indirect irradiance's directions per Sun column x (ComputeIndirectIrradiance):
  /// their (mu_s, nu) cells [x * nDir + j] and nu, the same at every radius and order.
  std::vector<SNuCell> irradianceSNu;
  std::vector<double> irradianceNu;
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
  /// L_{k-1}(r, mu, mu_s, nu) added into v, at the cells of (r, mu) (rMuCell) and (mu_s, nu)
  /// (sNuCell), which the callers reuse: order 1 from the single tables (phases included),
  /// else delta.
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
  /// The tables of L_(order): the single-scattering tables for 1, else delta.
  std::vector<const FloatTable3D*> incomingTables(int order) const {
    std::vector<const FloatTable3D*> v;
    if (order == 1) {
      for (const FloatTable3D& s : single) v.push_back(&s);
    } else {
      v.push_back(&delta);
    }
    return v;
  }
  /// The r slice whose texels a lookup at radius r starts from (rMuCell's iz; the next one
  /// too).
  int sliceAt(double r) const { return rMuCell(g, r, 1.0, false).iz; }
  /// The mean over the scattering texels of texelValue(x, y, z, v) per wavelength, slice by
  /// slice, afterSlice(z) after each.
  template <class F, class G>
  std::vector<double> meanOf(F&& texelValue, G&& afterSlice) const {
    std::vector<double> sum(nl, 0.0);
    std::vector<double> v(nl);
    for (int z = 0; z < R; ++z) {
      for (int y = 0; y < MU; ++y)
        for (int x = 0; x < W; ++x) {
          texelValue(x, y, z, v.data());
          for (int l = 0; l < nl; ++l) sum[l] += v[l];
        }
      afterSlice(z);
    }
    for (double& s : sum) s /= static_cast<double>(texels);
    return sum;
  }
};

/// The r slices of spilled tables that a stage reads, as it goes (Runner::run's steps, the
/// work moving up in r): window(from, to) lets the slices below `from` go and brings those
/// from `from` to `to` in, each slice once. Nothing for tables that do not spill.
class SliceWindow {
public:
  explicit SliceWindow(std::vector<const FloatTable3D*> tables) : tables_(std::move(tables)) {}
  void operator()(int from, int to) {
    if (from > released_) {
      for (const FloatTable3D* T : tables_) T->release(released_, from);
      released_ = from;
    }
    const int first = std::max(populated_, from);
    if (to > first) {
      for (const FloatTable3D* T : tables_) T->populate(first, to);
      populated_ = to;
    }
  }
  bool spilled() const {
    return std::any_of(tables_.begin(), tables_.end(), [](const FloatTable3D* T) { return T->spilled.on; });
  }

private:
  std::vector<const FloatTable3D*> tables_;
  int released_ = 0, populated_ = 0;
};

/// The r slice of a spilled table that a stage writes, a step at a time (Runner::run's
/// steps, one slice each): made in memory of its own, then written to the table's file
/// (copySpilledTableMemory). Written in place, each 4 KiB page of the file that the
/// process maps costs a page fault, and under a virtual machine's shadow page tables
/// more than the copy. `accumulate`: the stage adds to the slice's values (read from the
/// file first). For a table that does not spill, at() is the table's own.
class SliceBuffer {
public:
  SliceBuffer(FloatTable3D& table, bool accumulate) : table_(table), accumulate_(accumulate) {
    if (table.spilled.on) slice_.resize(table.width, table.height, 1, table.channels);
  }
  bool spilled() const { return table_.spilled.on; }
  float* at(int x, int y, int z) { return spilled() ? slice_.at(x, y, 0) : table_.at(x, y, z); }
  /// Between steps: slice z_ (the one finished) into the table, and slice z (next) made.
  void moveTo(int z) {
    if (!spilled()) return;
    const std::size_t bytes = slice_.values.size() * sizeof(float);
    const auto copy = [&](bool toTable) {
      copySpilledTableMemory(table_.values.data(), table_.offset(0, 0, z_) * sizeof(float), slice_.values.data(), bytes,
                             toTable);
    };
    if (z_ >= 0) copy(true);
    z_ = z < table_.depth ? z : -1;
    if (z_ >= 0 && accumulate_) copy(false);
  }

private:
  FloatTable3D& table_;
  FloatTable3D slice_;
  bool accumulate_;
  int z_ = -1;
};

/// The sun's direction in the ray's frame (x: the view's azimuth).
inline double sunX(const ScatteringPoint& p) {
  const double sz = std::sqrt(std::max(0.0, (1.0 - p.mu) * (1.0 + p.mu)));
  const double ss = std::sqrt(std::max(0.0, (1.0 - p.muS) * (1.0 + p.muS)));
  if (sz < 1e-12) return ss;
  return std::clamp((p.nu - p.mu * p.muS) / sz, -ss, ss);
}

/// View ray (y, z) with `samples` intervals into s (straight, or traced through `medium`);
/// with rhoT, also the hat-function weights of rho_q T_view that the single scattering
/// sums ([(i * ns + q) * nl + l]: int rho_q T_view hat_i ds).
void traceViewRay(const Model& m, const ScatterGeometry& g, const RefractiveMedium& medium, int samples, int y,
                  int z, RaySamples& s, std::vector<double>* rhoT);

// The stages, in the order they run.
void computeTransmittance(Batch& batch);
void computeDirectIrradiance(Batch& batch);
/// Every view ray, without weights (the multiple scattering's, when it takes rays of its
/// own; computeSingleScattering traces its own).
void buildViewRays(Batch& batch, int samples, std::vector<RaySamples>& rays);
void computeSingleScattering(Batch& batch);
void prepareDensityDirections(Batch& batch);
void computeScatteringDensity(Batch& batch, int order);
void computeIndirectIrradiance(Batch& batch, int order);
void computeMultipleScattering(Batch& batch);

}  // namespace umbra::atmosphere::stages
