// L_1 per scattering component, without its phase function: each view ray traced
// (traceViewRay, kept for the next orders), then along it the sunlight that reaches each
// sample (the transmittance table's row at its radius, the Sun's visibility over the
// horizon) times the ray's weights of rho_q T_view.
#include "precompute/Batch.hpp"
#include "precompute/Kernels.hpp"
#include "precompute/Paths.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace umbra::atmosphere::stages {

void computeSingleScattering(Batch& B) {
  const Atmosphere& atm = B.atm;
  const Model& m = B.m;
  const ScatterGeometry g = B.g;  // a copy: the stores into the tables cannot alias it
  const ShellRadii& shell = B.shell;
  const double alpha = B.alpha;
  const int nl = B.nl, ns = B.ns, W = B.W, MU = B.MU, R = B.R, TW = B.TW, TH = B.TH, l0 = B.l0;
  const Table2D& Ttab = B.out.transmittance;
  std::vector<RaySamples>& singleRays = B.singleRays;
  const RefractiveMedium& referenceMedium = B.referenceMedium;
  const int samples = B.o.singleScatteringSamples;
  const TexelPoints& points = B.points;
  std::vector<FloatTable3D>& single = B.single;
  BatchResult& out = B.out;
  singleRays.assign(static_cast<std::size_t>(R) * MU, RaySamples{});
  // An r slice a step when the tables spill, made in memory of its own (SliceBuffer).
  std::vector<SliceBuffer> slices;
  for (FloatTable3D& S : single) slices.emplace_back(S, false);
  const bool spill = !slices.empty() && slices.front().spilled();
  const auto between = [&](int done) {
    for (SliceBuffer& S : slices) S.moveTo(done / MU);
  };
  B.run.run("single scattering", 1.3, R * MU, [&, g, alpha, nl, ns, W, MU, TW, TH, l0, samples](int i) {
    const int y = i % MU, z = i / MU;
    RaySamples& s = singleRays[i];
    // A[k][q][l] = beta_s * int rho_q T_view hat_k
    std::vector<double> A;
    traceViewRay(m, g, referenceMedium, samples, y, z, s, &A);
    const int N = s.n;
    for (int k = 0; k <= N; ++k)
      for (int q = 0; q < ns; ++q)
        for (int l = 0; l < nl; ++l) {
          const std::size_t idx = (static_cast<std::size_t>(k) * ns + q) * nl + l;
          A[idx] = m.sca[q * nl + l] * A[idx];
        }
    // Samples outer, texels inner: the sample's radius fixes the transmittance row
    // (blended once) and the horizon; the texels' sun cosines are computed together.
    std::vector<double> sxA(W), muSA(W), visA(W), fxA(W), Trow(static_cast<std::size_t>(TW) * nl);
    std::vector<double> acc(static_cast<std::size_t>(W) * ns * nl, 0.0);
    for (int x = 0; x < W; ++x) {
      const ScatteringPoint p = points(x, y, z);
      sxA[x] = sunX(p), muSA[x] = p.muS;
    }
    for (int k = 0; k <= N && s.ds > 0.0; ++k) {
      const TransmittanceCoords rc = transmittanceCoordsFromRMu(shell, s.r[k], 1.0);
      const double fy = rc.xR * (TH - 1);
      const int iy = std::min(static_cast<int>(fy), TH - 2);
      const double wy = fy - iy;
      const double* row0 = Ttab.at(0, iy);
      const double* row1 = Ttab.at(0, iy + 1);
      for (std::size_t i = 0; i < Trow.size(); ++i) Trow[i] = (1 - wy) * row0[i] + wy * row1[i];
      sunTexels(shell, alpha, s.r[k], s.xr[k], s.yr[k], sxA.data(), muSA.data(), W, TW, visA.data(), fxA.data());
      const double* a = A.data() + static_cast<std::size_t>(k) * ns * nl;  // A is empty without scatterers
      for (int x = 0; x < W; ++x) {
        const double vis = visA[x];
        if (vis == 0.0) continue;
        const int ix = std::min(static_cast<int>(fxA[x]), TW - 2);
        const double wx = fxA[x] - ix;
        const double* T0 = &Trow[static_cast<std::size_t>(ix) * nl];
        const double* T1 = T0 + nl;
        double* ax = acc.data() + static_cast<std::size_t>(x) * ns * nl;
        for (int q = 0; q < ns; ++q)
          for (int l = 0; l < nl; ++l) ax[q * nl + l] += a[q * nl + l] * ((1 - wx) * T0[l] + wx * T1[l]) * vis;
      }
    }
    for (int x = 0; x < W; ++x)
      for (int q = 0; q < ns; ++q)
        std::copy_n(&acc[(static_cast<std::size_t>(x) * ns + q) * nl], nl, slices[q].at(x, y, z) + l0);
  }, spill ? MU : 0, between);

  // L_1 (phases included) at a texel, for the statistics.
  out.orderMean.push_back(B.meanOf(
      [&](int x, int y, int z, double* v) {
        const ScatteringPoint p = points(x, y, z);
        std::fill(v, v + nl, 0.0);
        for (int q = 0; q < ns; ++q) {
          const Component& comp = atm.components[m.scatterers[q]];
          const float* S = single[q].at(x, y, z) + l0;
          for (int l = 0; l < nl; ++l) v[l] += S[l] * comp.phase(l)(p.nu);
        }
      },
      [&, reading = SliceWindow(B.incomingTables(1))](int z) mutable { reading(z + 1, z + 2); }));
}

}  // namespace umbra::atmosphere::stages
