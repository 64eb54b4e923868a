// T to the top of the atmosphere per (r, mu): the column densities along the ray to the
// top (straight, or traced through each distinct refractive medium), exp(-tau).
#include "precompute/Batch.hpp"
#include "precompute/Kernels.hpp"
#include "precompute/Paths.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace umbra::atmosphere::stages {

void computeTransmittance(Batch& B) {
  const PrecomputeOptions& o = B.o;
  const Model& m = B.m;
  const ShellRadii& shell = B.shell;
  const double t = B.t;
  const int nl = B.nl, nc = B.nc, TW = B.TW, TH = B.TH;
  const std::vector<RefractiveMedium>& media = B.media;
  const std::vector<std::vector<int>>& mediumUsers = B.mediumUsers;
  BatchResult& out = B.out;
  out.transmittance.resize(TW, TH, nl);
  // The columns of straight rays, shared with the other batches when they are given.
  std::vector<double>* shared = o.refraction ? nullptr : B.transmittanceColumns;
  const bool reuse = shared && shared->size() == static_cast<std::size_t>(TW) * TH * nc;
  if (shared && !reuse) shared->assign(static_cast<std::size_t>(TW) * TH * nc, 0.0);
  B.run.run("transmittance", 1.0, TW * TH, [&, TW, TH, t, nl, nc, shared, reuse](int i) {
    const int x = i % TW, y = i / TW;
    const RadiusMu rm = rMuAtTexel(shell, x, y, TW, TH);
    std::vector<double> col(nc), tau(nl);
    double* T = out.transmittance.at(x, y);
    if (!o.refraction) {
      double* c = shared ? &(*shared)[static_cast<std::size_t>(i) * nc] : col.data();
      if (!reuse) {
        const Path p = straightPath(rm.radiusM, rm.mu, distanceToTopBoundaryM(t, rm.radiusM, rm.mu));
        std::size_t seg = 0;
        m.columns(p, 0.0, p.length, o.transmittanceSamples, seg, c);
      }
      m.opticalDepth(c, tau.data());
      for (int l = 0; l < nl; ++l) T[l] = std::exp(-tau[l]);
      return;
    }
    for (std::size_t k = 0; k < media.size(); ++k) {
      const Path p = tracedPath(media[k], rm.radiusM, rm.mu, o.refractionStepM, false);
      std::fill(col.begin(), col.end(), 0.0);
      std::size_t seg = 0;
      m.columns(p, 0.0, p.length, o.transmittanceSamples, seg, col.data());
      m.opticalDepth(col.data(), tau.data());
      for (int l : mediumUsers[k]) T[l] = std::exp(-tau[l]);
    }
  });
}

}  // namespace umbra::atmosphere::stages
