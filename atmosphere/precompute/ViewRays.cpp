// The view rays of the scattering tables, one per (r, mu) texel row: samples along the ray
// (straight, or traced through the reference medium) with their radii, frames and
// transmittance from the start, and the hat-function weights of rho_q T_view that the
// single-scattering sum takes.
#include "precompute/Batch.hpp"
#include "precompute/Kernels.hpp"
#include "precompute/Paths.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace umbra::atmosphere::stages {

void buildViewRays(Batch& B, int N, std::vector<RaySamples>& rays) {
  const PrecomputeOptions& o = B.o;
  const Model& m = B.m;
  const ScatterGeometry g = B.g;  // a copy: the stores into the tables cannot alias it
  const double b = B.b, t = B.t;
  const int nl = B.nl, nc = B.nc, ns = B.ns, R = B.R, MU = B.MU;
  const RefractiveMedium& referenceMedium = B.referenceMedium;
  rays.assign(static_cast<std::size_t>(R) * MU, RaySamples{});
  B.run.run("view rays", 0.3, R * MU, [&, g, b, t, nl, nc, ns, MU, N](int i) {
    const int y = i % MU, z = i / MU;
    const ScatteringPoint p = g.texel(0, y, z);
    RaySamples& s = rays[i];
    s.ground = p.rayIntersectsGround;
    const double L = s.ground ? distanceToBottomBoundaryM(b, p.r, p.mu) : distanceToTopBoundaryM(t, p.r, p.mu);
    Path path = !o.refraction || !(L > 0.0)
                    ? straightPath(p.r, p.mu, L)
                    : tracedPath(referenceMedium, p.r, p.mu, std::min(o.refractionStepM, std::max(1.0, L / N)), true);
    s.n = N;
    s.ds = path.length / N;
    s.r.resize(N + 1), s.xr.resize(N + 1), s.yr.resize(N + 1), s.tx.resize(N + 1), s.ty.resize(N + 1);
    s.mu.resize(N + 1);
    s.T.resize(static_cast<std::size_t>(N + 1) * nl);
    std::vector<double> col(nc, 0.0), tau(nl), tauAll(static_cast<std::size_t>(N + 1) * nl);
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
      m.opticalDepth(col.data(), tau.data());
      for (int l = 0; l < nl; ++l) {
        s.T[static_cast<std::size_t>(k) * nl + l] = std::exp(-tau[l]);
        tauAll[static_cast<std::size_t>(k) * nl + l] = tau[l];
      }
    }
    // Hat-function weights of rho_q * T_view for the single-scattering sum: Simpson on
    // the sub-intervals, T_view there from the trapezoidal shape of the interval's
    // optical depth scaled to its Simpson total. Exact for any density variation that the
    // sub-intervals resolve, whatever the sample count (the sun's transmittance is then
    // interpolated linearly between samples).
    s.rhoT.assign(static_cast<std::size_t>(N + 1) * ns * nl, 0.0);
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
            s.rhoT[(static_cast<std::size_t>(k - 1) * ns + q) * nl + l] += v * (1.0 - u);
            s.rhoT[(static_cast<std::size_t>(k) * ns + q) * nl + l] += v * u;
          }
        }
      }
    }
  });
}

}  // namespace umbra::atmosphere::stages
