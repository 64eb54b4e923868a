// L_k from J_k: along each view ray, the density (its four (r, mu) rows blended once per
// sample, then read bilinearly in (mu_s, nu) per texel) times the transmittance from the
// start, trapezoid rule; added into the multiple-scattering table, and kept as delta for
// the next order.
#include "precompute/Batch.hpp"
#include "precompute/Kernels.hpp"
#include "precompute/Paths.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace umbra::atmosphere::stages {

void computeMultipleScattering(Batch& B) {
  const ScatterGeometry g = B.g;  // a copy: the stores into the tables cannot alias it
  const double b = B.b;
  const int nl = B.nl, W = B.W, MU = B.MU, R = B.R, MUS = B.MUS, l0 = B.l0;
  const std::vector<RaySamples>& mRays = B.multipleScatteringRays();
  const Model& m = B.m;
  const TexelPoints& points = B.points;
  const FloatTable3D& density = B.density;
  FloatTable3D& delta = B.delta;
  FloatTable3D& multiple = B.multiple;
  // An r slice a step when the tables spill, made in memory of its own (SliceBuffer).
  SliceBuffer deltaSlice(delta, false), sumSlice(multiple, true);
  const bool spill = deltaSlice.spilled() || sumSlice.spilled();
  const auto between = [&](int done) {
    deltaSlice.moveTo(done / MU);
    sumSlice.moveTo(done / MU);
  };
  B.run.run("multiple scattering", 1.0, R * MU, [&, g, b, nl, W, MU, MUS, l0](int i) {
    const int y = i % MU, z = i / MU;
    const RaySamples& s = mRays[i];
    const int N = s.n;
    std::vector<double> Tview(static_cast<std::size_t>(N + 1) * nl);
    rayTransmittance(m, s, Tview.data());
    std::vector<RMuCell> cells(N + 1);
    for (int k = 0; k <= N; ++k)
      cells[k] = rMuCell(g, s.r[k], s.mu[k], rayIntersectsGround(b, s.r[k], s.mu[k]));
    // Samples outer, texels inner. J is linear in the (r, mu) weights, which depend on
    // the sample only: the sample's four (r, mu) rows are blended once into one row of
    // (mu_s, nu) texels, and each texel reads that row bilinearly (4 reads, not 16).
    const std::size_t rowSize = static_cast<std::size_t>(W) * nl;
    std::vector<double> sxA(W), muSA(W), wsA(W), wnA(W), acc(rowSize, 0.0), blend(rowSize);
    std::vector<int> x00A(W);
    for (int x = 0; x < W; ++x) {
      const ScatteringPoint p = points(x, y, z);
      sxA[x] = sunX(p), muSA[x] = p.muS;
    }
    for (int k = 0; k <= N && s.ds > 0.0; ++k) {
      const double w = s.ds * ((k == 0 || k == N) ? 0.5 : 1.0);
      const double* T = &Tview[static_cast<std::size_t>(k) * nl];
      blendRows(density, cells[k], blend.data());
      const double xr = s.xr[k], yr = s.yr[k], tx = s.tx[k], ty = s.ty[k];
      sNuTexels(g, xr, yr, tx, ty, sxA.data(), muSA.data(), W, x00A.data(), wsA.data(), wnA.data());
      gatherTexels(blend.data(), nl, MUS, x00A.data(), wsA.data(), wnA.data(), W, w, T, acc.data());
    }
    for (int x = 0; x < W; ++x) {
      const double* a = &acc[static_cast<std::size_t>(x) * nl];
      std::copy_n(a, nl, deltaSlice.at(x, y, z));
      float* sum = sumSlice.at(x, y, z) + l0;
      for (int l = 0; l < nl; ++l) sum[l] = static_cast<float>(sum[l] + a[l]);
    }
  }, spill ? MU : 0, between);
}

}  // namespace umbra::atmosphere::stages
