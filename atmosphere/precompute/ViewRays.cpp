// The view rays of the scattering tables, one per (r, mu) texel row: samples along the ray
// (straight, or traced through the reference medium) with their radii, frames and column
// densities from the start, and (for the single scattering) the hat-function weights of
// rho_q T_view that its sum takes.
#include "precompute/Batch.hpp"
#include "precompute/Kernels.hpp"
#include "precompute/Paths.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace umbra::atmosphere::stages {

void traceViewRay(const Model& m, const ScatterGeometry& g, const RefractiveMedium& medium, int N, int y, int z,
                  RaySamples& s, std::vector<double>* rhoT) {
  const PrecomputeOptions& o = m.o;
  const double b = m.b, t = m.t;
  const int nl = m.nl, nc = m.nc, ns = static_cast<int>(m.scatterers.size());
  const ScatteringPoint p = g.texel(0, y, z);
  s.ground = p.rayIntersectsGround;
  const double L = s.ground ? distanceToBottomBoundaryM(b, p.r, p.mu) : distanceToTopBoundaryM(t, p.r, p.mu);
  Path path = !o.refraction || !(L > 0.0)
                  ? straightPath(p.r, p.mu, L)
                  : tracedPath(medium, p.r, p.mu, std::min(o.refractionStepM, std::max(1.0, L / N)), true);
  s.n = N;
  s.ds = path.length / N;
  s.r.resize(N + 1), s.xr.resize(N + 1), s.yr.resize(N + 1), s.tx.resize(N + 1), s.ty.resize(N + 1);
  s.mu.resize(N + 1);
  s.col.resize(static_cast<std::size_t>(N + 1) * nc);
  std::vector<double> col(nc, 0.0);
  std::size_t seg = 0, seg2 = 0;
  for (int k = 0; k <= N; ++k) {
    const double sk = k * s.ds;
    if (k > 0) m.columns(path, sk - s.ds, sk, o.opticalDepthSubsamples, seg2, col.data());
    double x, yy, tx, ty;
    path.eval(sk, seg, x, yy, tx, ty);
    if (!(std::isfinite(x) && std::isfinite(yy) && std::isfinite(tx) && std::isfinite(ty) && std::isfinite(s.ds)))
      throwNonFiniteLookup();
    const double r = std::max(std::sqrt(x * x + yy * yy), 1e-3);
    s.r[k] = r, s.xr[k] = x / r, s.yr[k] = yy / r, s.tx[k] = tx, s.ty[k] = ty;
    s.mu[k] = clampCosine((x * tx + yy * ty) / r);
    std::copy_n(col.data(), nc, &s.col[static_cast<std::size_t>(k) * nc]);
  }
  if (!rhoT) return;
  // Hat-function weights of rho_q * T_view for the single-scattering sum: Simpson on
  // the sub-intervals, T_view there from the trapezoidal shape of the interval's
  // optical depth scaled to its Simpson total. Exact for any density variation that the
  // sub-intervals resolve, whatever the sample count (the sun's transmittance is then
  // interpolated linearly between samples).
  std::vector<double> tauAll(static_cast<std::size_t>(N + 1) * nl);
  for (int k = 0; k <= N; ++k)
    m.opticalDepth(&s.col[static_cast<std::size_t>(k) * nc], &tauAll[static_cast<std::size_t>(k) * nl]);
  rhoT->assign(static_cast<std::size_t>(N + 1) * ns * nl, 0.0);
  const int msub = o.opticalDepthSubsamples;
  std::vector<double> rhoSub(static_cast<std::size_t>(msub + 1) * nc), cum(msub + 1);
  std::size_t seg3 = 0;
  for (int k = 1; k <= N && s.ds > 0.0; ++k) {
    const double s0 = (k - 1) * s.ds, h = s.ds / msub;
    for (int j = 0; j <= msub; ++j) {
      double x, yy, tx, ty;
      path.eval(s0 + j * h, seg3, x, yy, tx, ty);
      const double alt = std::sqrt(x * x + yy * yy) - b;
      for (int c = 0; c < nc; ++c) rhoSub[j * nc + c] = m.density(c, alt);
    }
    for (int l = 0; l < nl; ++l) {
      cum[0] = 0.0;
      double ePrev = 0.0;
      for (int j = 0; j <= msub; ++j) {
        double e = 0.0;
        for (int c = 0; c < nc; ++c) e += m.ext[c * nl + l] * rhoSub[j * nc + c];
        if (j > 0) cum[j] = cum[j - 1] + 0.5 * h * (e + ePrev);
        ePrev = e;
      }
      const double tau0 = tauAll[static_cast<std::size_t>(k - 1) * nl + l];
      const double dtau = tauAll[static_cast<std::size_t>(k) * nl + l] - tau0;
      for (int j = 0; j <= msub; ++j) {
        const double frac = cum[msub] > 0.0 ? cum[j] / cum[msub] : 0.0;
        const double Tj = std::exp(-(tau0 + dtau * frac));
        const double wj = h / 3.0 * ((j == 0 || j == msub) ? 1.0 : (j % 2 ? 4.0 : 2.0)) * Tj;
        const double u = static_cast<double>(j) / msub;
        for (int q = 0; q < ns; ++q) {
          const double v = wj * rhoSub[j * nc + m.scatterers[q]];
          (*rhoT)[(static_cast<std::size_t>(k - 1) * ns + q) * nl + l] += v * (1.0 - u);
          (*rhoT)[(static_cast<std::size_t>(k) * ns + q) * nl + l] += v * u;
        }
      }
    }
  }
}

void buildViewRays(Batch& B, int N, std::vector<RaySamples>& rays) {
  const Model& m = B.m;
  const ScatterGeometry g = B.g;  // a copy: the stores into the tables cannot alias it
  const int MU = B.MU;
  const RefractiveMedium& referenceMedium = B.referenceMedium;
  rays.assign(static_cast<std::size_t>(B.R) * MU, RaySamples{});
  B.run.run("view rays", 0.3, B.R * MU, [&, g, MU, N](int i) {
    traceViewRay(m, g, referenceMedium, N, i % MU, i / MU, rays[i], nullptr);
  });
}

}  // namespace umbra::atmosphere::stages
