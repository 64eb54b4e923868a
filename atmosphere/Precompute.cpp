#include "Precompute.hpp"
#include "Quadrature.hpp"

#include "Refraction.hpp"
#include "SightLines.hpp"  // refractiveMedium
#include "TextureCoords.hpp"
#include "precompute/Kernels.hpp"
#include "precompute/Model.hpp"
#include "precompute/Parametrisation.hpp"
#include "precompute/Paths.hpp"
#include "precompute/Runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <sstream>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace umbra::atmosphere {

using namespace stages;

// ---- options -------------------------------------------------------------------------------

std::string PrecomputeOptions::validate() const {
  std::ostringstream e;
  if (transmittanceWidth < 2 || transmittanceHeight < 2) e << "transmittance size must be >= 2x2; ";
  if (scatteringR < 2 || scatteringMuS < 2 || scatteringNu < 2) e << "scattering R, MU_S, NU must be >= 2; ";
  if (scatteringMu < 4 || scatteringMu % 2 != 0) e << "scatteringMu must be even and >= 4; ";
  if (irradianceWidth < 2 || irradianceHeight < 2) e << "irradiance size must be >= 2x2; ";
  if (orders < 1) e << "orders must be >= 1; ";
  if (transmittanceSamples < 2 || transmittanceSamples % 2 != 0) e << "transmittanceSamples must be even and >= 2; ";
  if (singleScatteringSamples < 1 || multipleScatteringSamples < 1) e << "scattering samples must be >= 1; ";
  if (opticalDepthSubsamples < 2 || opticalDepthSubsamples % 2 != 0) e << "opticalDepthSubsamples must be even and >= 2; ";
  if (sphereSamples != 0 && sphereSamples < 2) e << "sphereSamples must be 0 (from the phase functions) or >= 2; ";
  if (irradianceSamples < 2 || irradianceSamples % 2 != 0) e << "irradianceSamples must be even and >= 2; ";
  if (!(muSMin >= -1.0 && muSMin < 1.0)) e << "muSMin must be in [-1, 1); ";
  if (!(sunAngularRadiusRad >= 0.0 && sunAngularRadiusRad < 0.5)) e << "sunAngularRadiusRad must be in [0, 0.5); ";
  if (!(refractionStepM > 0.0)) e << "refractionStepM must be > 0; ";
  if (wavelengthBatch < 0) e << "wavelengthBatch must be >= 0; ";
  return e.str();
}

std::size_t AtmosphereTables::bytes() const {
  std::size_t n = transmittance.values.size() + multipleScattering.values.size() +
                  directIrradiance.values.size() + irradiance.values.size();
  for (const Table3D& t : singleScattering) n += t.values.size();
  return n * sizeof(double);
}

namespace {

// ---- one batch of wavelengths ---------------------------------------------------------------

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

BatchResult computeBatch(const Atmosphere& atm, const PrecomputeOptions& o, Runner& run, std::vector<Table3D>& single,
                         Table3D& multiple, int l0) {
  const Model m(atm, o);
  const int nl = m.nl, nc = m.nc, ns = static_cast<int>(m.scatterers.size());
  const ShellRadii shell{atm.bottomRadiusM, atm.topRadiusM};
  const double b = m.b, t = m.t;
  const ScatterGeometry g(shell, {o.scatteringR, o.scatteringMu, o.scatteringMuS, o.scatteringNu}, o.muSMin);
  const int W = o.scatteringNu * o.scatteringMuS, MU = o.scatteringMu, R = o.scatteringR, MUS = o.scatteringMuS;
  const std::size_t texels = static_cast<std::size_t>(W) * MU * R;
  BatchResult out;

  // Refractive media: one per distinct refractivity (dispersion) for the transmittance,
  // the reference wavelength's for the scattering paths.
  std::vector<RefractiveMedium> media;
  std::vector<std::vector<int>> mediumUsers;
  RefractiveMedium referenceMedium;
  if (o.refraction) {
    std::map<double, int> seen;
    for (int l = 0; l < nl; ++l) {
      const double key = dispersionRatio(atm.dispersion, atm.wavelengthsNm[l], atm.refractivityReferenceWavelengthNm);
      auto it = seen.find(key);
      if (it == seen.end()) {
        seen[key] = static_cast<int>(media.size());
        media.push_back(refractiveMedium(atm, atm.wavelengthsNm[l]));
        mediumUsers.push_back({l});
      } else {
        mediumUsers[it->second].push_back(l);
      }
    }
    referenceMedium = refractiveMedium(atm, atm.refractivityReferenceWavelengthNm);
  }

  // ---- transmittance -----------------------------------------------------------------------
  const int TW = o.transmittanceWidth, TH = o.transmittanceHeight;
  out.transmittance.resize(TW, TH, nl);
  run.run("transmittance", 1.0, TW * TH, [&](int i) {
    const int x = i % TW, y = i / TW;
    const RadiusMu rm = rMuAtTexel(shell, x, y, TW, TH);
    std::vector<double> col(nc), tau(nl);
    double* T = out.transmittance.at(x, y);
    if (!o.refraction) {
      const Path p = straightPath(rm.radiusM, rm.mu, distanceToTopBoundaryM(t, rm.radiusM, rm.mu));
      std::size_t seg = 0;
      m.columns(p, 0.0, p.length, o.transmittanceSamples, seg, col.data());
      m.opticalDepth(col.data(), tau.data());
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
  const Table2D& Ttab = out.transmittance;

  // ---- direct irradiance -------------------------------------------------------------------
  const int IW = o.irradianceWidth, IH = o.irradianceHeight;
  out.directIrradiance.resize(IW, IH, nl);
  out.irradiance.resize(IW, IH, nl);
  const double alpha = o.sunAngularRadiusRad;
  auto irradianceTexel = [&](int x, int y, double& r, double& muS) {
    r = b + (t - b) * y / (IH - 1.0);
    muS = clampCosine(-1.0 + 2.0 * x / (IW - 1.0));
  };
  run.run("direct irradiance", 0.05, IH, [&](int y) {
    for (int x = 0; x < IW; ++x) {
      double r, muS;
      irradianceTexel(x, y, r, muS);
      directIrradianceAt(Ttab, shell, alpha, r, muS, out.directIrradiance.at(x, y));
    }
  });

  // ---- view-ray samples, per (r, mu) -------------------------------------------------------
  auto buildSamples = [&](int N, std::vector<RaySamples>& rays) {
    rays.assign(static_cast<std::size_t>(R) * MU, RaySamples{});
    run.run("view rays", 0.3, R * MU, [&](int i) {
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
  };
  std::vector<RaySamples> singleRays, multipleRays;
  buildSamples(o.singleScatteringSamples, singleRays);
  const bool sameRays = o.multipleScatteringSamples == o.singleScatteringSamples;
  if (!sameRays && o.orders > 1) buildSamples(o.multipleScatteringSamples, multipleRays);
  const std::vector<RaySamples>& mRays = sameRays ? singleRays : multipleRays;

  // The sun's direction in the ray's frame (x: the view's azimuth).
  auto sunX = [](const ScatteringPoint& p) {
    const double sz = std::sqrt(std::max(0.0, (1.0 - p.mu) * (1.0 + p.mu)));
    const double ss = std::sqrt(std::max(0.0, (1.0 - p.muS) * (1.0 + p.muS)));
    if (sz < 1e-12) return ss;
    return std::clamp((p.nu - p.mu * p.muS) / sz, -ss, ss);
  };

  // ---- single scattering -------------------------------------------------------------------
  run.run("single scattering", 1.0, R * MU, [&](int i) {
    const int y = i % MU, z = i / MU;
    const RaySamples& s = singleRays[i];
    const int N = s.n;
    // A[k][q][l] = beta_s * int rho_q T_view hat_k
    std::vector<double> A(static_cast<std::size_t>(N + 1) * ns * nl);
    for (int k = 0; k <= N; ++k)
      for (int q = 0; q < ns; ++q)
        for (int l = 0; l < nl; ++l) {
          const std::size_t idx = (static_cast<std::size_t>(k) * ns + q) * nl + l;
          A[idx] = m.sca[q * nl + l] * s.rhoT[idx];
        }
    // Samples outer, texels inner: the sample's radius fixes the transmittance row
    // (blended once) and the horizon; the texels' sun cosines are computed together.
    std::vector<double> sxA(W), muSA(W), visA(W), fxA(W), Trow(static_cast<std::size_t>(TW) * nl);
    std::vector<double> acc(static_cast<std::size_t>(W) * ns * nl, 0.0);
    for (int x = 0; x < W; ++x) {
      const ScatteringPoint p = g.texel(x, y, z);
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
        std::copy_n(&acc[(static_cast<std::size_t>(x) * ns + q) * nl], nl, single[q].at(x, y, z) + l0);
  });

  auto meanOf = [&](auto&& texelValue) {
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
  };
  // L_1 (phases included) at a texel, for the statistics.
  out.orderMean.push_back(meanOf([&](int x, int y, int z, double* v) {
    const ScatteringPoint p = g.texel(x, y, z);
    std::fill(v, v + nl, 0.0);
    for (int q = 0; q < ns; ++q) {
      const Component& comp = atm.components[m.scatterers[q]];
      const double* S = single[q].at(x, y, z) + l0;
      for (int l = 0; l < nl; ++l) v[l] += S[l] * comp.phase(l)(p.nu);
    }
  }));

  // The single-scattering weights are spent: free them before the working tables.
  for (std::vector<RaySamples>* rays : {&singleRays, &multipleRays})
    for (RaySamples& s : *rays) std::vector<double>().swap(s.rhoT);
  if (o.orders < 2) return out;

  // L_{k-1}(r, mu, mu_s, nu) added into v: order 1 from the single tables, else delta.
  Table3D delta, density;
  delta.resize(W, MU, R, nl);
  density.resize(W, MU, R, nl);
  auto incoming = [&](int order, double r, double mu, double muS, double nu, bool ground, double* v) {
    const RMuCell a = rMuCell(g, r, mu, ground);
    const SNuCell c = sNuCell(g, muS, nu);
    if (order == 1) {
      std::vector<double> tmp(nl);
      for (int q = 0; q < ns; ++q) {
        std::fill(tmp.begin(), tmp.end(), 0.0);
        accumulate4(single[q], a, c, 1.0, tmp.data(), l0, nl);
        const Component& comp = atm.components[m.scatterers[q]];
        for (int l = 0; l < nl; ++l) v[l] += tmp[l] * comp.phase(l)(nu);
      }
    } else {
      accumulate4(delta, a, c, 1.0, v);
    }
  };

  // Sphere of directions for the density, per radius: Gauss-Legendre in mu on each side
  // of the ground's horizon mu_h(r) (n/2 nodes below it, n - n/2 above; the nodes crowd
  // towards the ends, so both sides of the horizon, where the sky is brightest and the
  // radiance jumps to the ground's, are sampled within a degree or two), midpoint rule in
  // phi (n over (0, pi)). The incoming radiance is symmetric about the plane of the zenith
  // and the sun (phi -> -phi: the same (mu, mu_s, nu)), so only phi in (0, pi) is looked
  // up, each direction standing for itself and its mirror (wy -> -wy) with twice the solid
  // angle. A midpoint rule in theta missed the band along the horizon that lights the
  // shadowed air in twilight (docs/accuracy-vs-speed.md, "Twilight").
  const int nTh = o.sphereSamples, nPh = nTh, nDir = nTh * nPh;
  const double dA = kPi / nTh;
  const std::size_t RD = static_cast<std::size_t>(R) * nDir;
  std::vector<double> wxAll(RD), wyAll(RD), wzAll(RD), wdoAll(RD);
  const int nGround = nTh / 2, nSky = nTh - nGround;
  const GaussLegendreRule glSky(nSky), glGround(nGround);
  // Transmittance from (r_z, theta_l) to the ground along straight rays (for the ground term).
  std::vector<double> groundT(static_cast<std::size_t>(R) * nTh * nl, 0.0), groundD(static_cast<std::size_t>(R) * nTh, -1.0);
  for (int z = 0; z < R; ++z) {
    const double r = g.rFromU((z + 0.5) / R);
    const double muH = -std::sqrt(std::max(0.0, 1.0 - (b / r) * (b / r)));
    for (int lt = 0; lt < nTh; ++lt) {
      const bool sky = lt < nSky;
      const GaussLegendreRule& q = sky ? glSky : glGround;
      const int i = sky ? lt : lt - nSky;
      const double lo = sky ? muH : -1.0, hi = sky ? 1.0 : muH;
      const double mu = 0.5 * (lo + hi) + 0.5 * (hi - lo) * q.x[i], dMu = 0.5 * (hi - lo) * q.w[i];
      const double sinTh = std::sqrt(std::max(0.0, 1.0 - mu * mu));
      for (int mp = 0; mp < nPh; ++mp) {
        const double ph = (mp + 0.5) * dA;
        const std::size_t j = static_cast<std::size_t>(z) * nDir + lt * nPh + mp;
        wxAll[j] = std::cos(ph) * sinTh, wyAll[j] = std::sin(ph) * sinTh, wzAll[j] = mu;
        wdoAll[j] = 2.0 * dA * dMu;
      }
      if (sky || !rayIntersectsGround(b, r, mu)) continue;
      const double d = distanceToBottomBoundaryM(b, r, mu);
      groundD[z * nTh + lt] = d;
      const Path p = straightPath(r, mu, d);
      std::vector<double> col(nc, 0.0), tau(nl);
      std::size_t seg = 0;
      m.columns(p, 0.0, d, o.transmittanceSamples, seg, col.data());
      m.opticalDepth(col.data(), tau.data());
      for (int l = 0; l < nl; ++l) groundT[(static_cast<std::size_t>(z) * nTh + lt) * nl + l] = std::exp(-tau[l]);
    }
  }

  // The exact integral of each phase lobe over the sphere (trapezoid in cos theta, 2^17
  // pieces: a Henyey-Greenstein lobe of g = 0.95 peaks over 1e-3 in cos theta). The sum
  // over the directions above is renormalised to it per view (below): a forward peak
  // narrower than the directions' spacing is otherwise over- or under-counted depending on
  // where the view falls between them.
  std::vector<double> lobeIntegral(m.lobes.size(), 0.0);
  for (std::size_t li = 0; li < m.lobes.size(); ++li) {
    const int n = 1 << 17;
    double sum = 0.5 * (Model::evalLobe(m.lobes[li], -1.0) + Model::evalLobe(m.lobes[li], 1.0));
    for (int i = 1; i < n; ++i) sum += Model::evalLobe(m.lobes[li], -1.0 + 2.0 * i / n);
    lobeIntegral[li] = 2.0 * kPi * sum * 2.0 / n;
  }

  Table2D deltaE;  // E_{k-2}, from order 3 on (order 2's ground takes E_0 from directIrradianceAt)
  Table2D nextE;
  nextE.resize(IW, IH, nl);
  const int nIrTh = o.irradianceSamples / 2, nIrPh = 2 * o.irradianceSamples;
  const double dI = kPi / o.irradianceSamples;

  for (int order = 2; order <= o.orders; ++order) {
    // ---- scattering density J_order, one (r, mu_s) slice per task --------------------------
    run.run("scattering density", 2.0, R * MUS, [&](int task) {
      const int z = task / MUS, is = task % MUS;
      const ScatteringPoint p0 = g.texel(is, 0, z);
      const double r = p0.r, muS = p0.muS, sinS = std::sqrt(std::max(0.0, 1.0 - muS * muS));
      const double alt = r - b;
      const std::size_t zd = static_cast<std::size_t>(z) * nDir;
      const double *wx = &wxAll[zd], *wy = &wyAll[zd], *wz = &wzAll[zd], *wdo = &wdoAll[zd];
      // Incoming radiance per direction, times the solid angle: Lw[l][j].
      std::vector<double> Lw(static_cast<std::size_t>(nl) * nDir), v(nl), E(nl);
      std::vector<double> M0(nl, 0.0), M2(static_cast<std::size_t>(nl) * 6, 0.0);
      for (int j = 0; j < nDir; ++j) {
        const int lt = j / nPh;
        const double nu = clampCosine(wx[j] * sinS + wz[j] * muS);
        const bool ground = groundD[z * nTh + lt] >= 0.0;
        std::fill(v.begin(), v.end(), 0.0);
        incoming(order - 1, r, wz[j], muS, nu, ground, v.data());
        if (ground) {
          const double d = groundD[z * nTh + lt];
          const double muSg = clampCosine((r * muS + d * nu) / b);
          if (order == 2) {
            directIrradianceAt(Ttab, shell, alpha, b, muSg, E.data());  // E_0, exact at the setting Sun
          } else {
            lookupIrradiance(deltaE, shell, b, muSg, E.data());
          }
          const double* Tg = &groundT[(static_cast<std::size_t>(z) * nTh + lt) * nl];
          for (int l = 0; l < nl; ++l) v[l] += Tg[l] * atm.groundAlbedo[l] / kPi * E[l];
        }
        for (int l = 0; l < nl; ++l) {
          const double L = v[l] * wdo[j];
          Lw[static_cast<std::size_t>(l) * nDir + j] = L;
          M0[l] += L;
          double* M = &M2[l * 6];
          // xy and yz cancel with the mirror (M[3] = M[5] = 0)
          M[0] += wx[j] * wx[j] * L, M[1] += wy[j] * wy[j] * L, M[2] += wz[j] * wz[j] * L;
          M[4] += wx[j] * wz[j] * L;
        }
      }
      std::vector<double> rho(ns);
      for (int q = 0; q < ns; ++q) rho[q] = m.density(m.scatterers[q], alt);
      // cj: the cosines with the view of the directions [0, nDir) and of their mirrors.
      std::vector<double> cj(2 * nDir), pj(2 * nDir), pPair(nDir), lobeSum(m.lobes.size() * nl), J(nl);
      // Tabulated lobes (one per wavelength for Lorenz-Mie) share the cosines: the table
      // index and weight of each, computed once per view (as Model::evalLobe does).
      std::vector<int> tableIndex(2 * nDir);
      std::vector<double> tableWeight(2 * nDir);
      bool anyTable = false;
      for (const Lobe& lobe : m.lobes) anyTable = anyTable || !lobe.table.empty();
      for (int y = 0; y < MU; ++y) {
        for (int k = 0; k < o.scatteringNu; ++k) {
          const int x = k * MUS + is;
          const ScatteringPoint p = g.texel(x, y, z);
          const double sz = std::sqrt(std::max(0.0, 1.0 - p.mu * p.mu));
          double vx = sinS > 1e-12 ? std::clamp((p.nu - p.mu * muS) / sinS, -sz, sz) : sz;
          const double vy = std::sqrt(std::max(0.0, sz * sz - vx * vx)), vz = p.mu;
          if (!m.lobes.empty()) {
#pragma omp simd
            for (int j = 0; j < nDir; ++j) {
              cj[j] = wx[j] * vx + wy[j] * vy + wz[j] * vz;
              cj[nDir + j] = wx[j] * vx - wy[j] * vy + wz[j] * vz;
            }
          }
          if (anyTable) {
            for (int j = 0; j < 2 * nDir; ++j) Model::tablePosition(cj[j], tableIndex[j], tableWeight[j]);
          }
          for (std::size_t li = 0; li < m.lobes.size(); ++li) {
            const Lobe& lobe = m.lobes[li];
            if (lobe.table.empty()) {
              lobeValues(lobe.A, lobe.B, lobe.g, cj.data(), pj.data(), 2 * nDir);
            } else {
              const double* T = lobe.table.data();
              for (int j = 0; j < 2 * nDir; ++j) {
                const int i = tableIndex[j];
                const double w = tableWeight[j];
                pj[j] = (1 - w) * T[i] + w * T[i + 1];
              }
            }
#pragma omp simd
            for (int j = 0; j < nDir; ++j) pPair[j] = 0.5 * (pj[j] + pj[nDir + j]);
            const double norm = dot(pPair.data(), wdo, nDir);
            const double scale = norm > 0.0 ? lobeIntegral[li] / norm : 1.0;
            for (int l : m.lobeUsers[li]) {
              lobeSum[li * nl + l] = scale * dot(pPair.data(), &Lw[static_cast<std::size_t>(l) * nDir], nDir);
            }
          }
          std::fill(J.begin(), J.end(), 0.0);
          for (int q = 0; q < ns; ++q) {
            for (int l = 0; l < nl; ++l) {
              const PhaseModel& pm = m.phase[q * nl + l];
              double s = 0.0;
              if (pm.a != 0.0 || pm.b != 0.0) {
                const double* M = &M2[l * 6];
                const double vMv = vx * vx * M[0] + vy * vy * M[1] + vz * vz * M[2] +
                                   2.0 * (vx * vy * M[3] + vx * vz * M[4] + vy * vz * M[5]);
                s += pm.a * M0[l] + pm.b * vMv;
              }
              for (auto [li, w] : pm.lobes) s += w * lobeSum[li * nl + l];
              J[l] += m.sca[q * nl + l] * rho[q] * s;
            }
          }
          std::copy_n(J.data(), nl, density.at(x, y, z));
        }
      }
    });

    // ---- indirect irradiance E_{order-1} from L_{order-1} ----------------------------------
    run.run("indirect irradiance", 0.1, IH, [&](int y) {
      std::vector<double> v(nl);
      for (int x = 0; x < IW; ++x) {
        double r, muS;
        irradianceTexel(x, y, r, muS);
        const double sinS = std::sqrt(std::max(0.0, 1.0 - muS * muS));
        std::vector<double> E(nl, 0.0);
        for (int jt = 0; jt < nIrTh; ++jt) {
          const double th = (jt + 0.5) * dI, cz = std::cos(th), sth = std::sin(th);
          for (int ip = 0; ip < nIrPh; ++ip) {
            const double ph = (ip + 0.5) * dI;
            const double nu = clampCosine(std::cos(ph) * sth * sinS + cz * muS);
            std::fill(v.begin(), v.end(), 0.0);
            incoming(order - 1, r, cz, muS, nu, false, v.data());
            const double w = cz * sth * dI * dI;
            for (int l = 0; l < nl; ++l) E[l] += v[l] * w;
          }
        }
        std::copy_n(E.data(), nl, nextE.at(x, y));
        double* acc = out.irradiance.at(x, y);
        for (int l = 0; l < nl; ++l) acc[l] += E[l];
      }
    });
    deltaE = nextE;

    // ---- multiple scattering L_order from J_order ------------------------------------------
    run.run("multiple scattering", 1.0, R * MU, [&](int i) {
      const int y = i % MU, z = i / MU;
      const RaySamples& s = mRays[i];
      const int N = s.n;
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
        const ScatteringPoint p = g.texel(x, y, z);
        sxA[x] = sunX(p), muSA[x] = p.muS;
      }
      for (int k = 0; k <= N && s.ds > 0.0; ++k) {
        const double w = s.ds * ((k == 0 || k == N) ? 0.5 : 1.0);
        const double* T = &s.T[static_cast<std::size_t>(k) * nl];
        blendRows(density, cells[k], blend.data());
        const double xr = s.xr[k], yr = s.yr[k], tx = s.tx[k], ty = s.ty[k];
        sNuTexels(g, xr, yr, tx, ty, sxA.data(), muSA.data(), W, x00A.data(), wsA.data(), wnA.data());
        const std::size_t up = static_cast<std::size_t>(MUS) * nl;
        for (int x = 0; x < W; ++x) {
          const double* p00 = &blend[static_cast<std::size_t>(x00A[x]) * nl];
          const double* p01 = p00 + nl;
          const double* p10 = p00 + up;
          const double* p11 = p10 + nl;
          const double ws = wsA[x], wn = wnA[x];
          const double w00 = w * (1 - wn) * (1 - ws), w01 = w * (1 - wn) * ws, w10 = w * wn * (1 - ws), w11 = w * wn * ws;
          double* a = &acc[static_cast<std::size_t>(x) * nl];
          for (int l = 0; l < nl; ++l) a[l] += T[l] * (w00 * p00[l] + w01 * p01[l] + w10 * p10[l] + w11 * p11[l]);
        }
      }
      for (int x = 0; x < W; ++x) {
        const double* a = &acc[static_cast<std::size_t>(x) * nl];
        std::copy_n(a, nl, delta.at(x, y, z));
        double* sum = multiple.at(x, y, z) + l0;
        for (int l = 0; l < nl; ++l) sum[l] += a[l];
      }
    });
    out.orderMean.push_back(meanOf([&](int x, int y, int z, double* v) { std::copy_n(delta.at(x, y, z), nl, v); }));
  }
  return out;
}

Atmosphere subAtmosphere(const Atmosphere& atm, const std::vector<int>& ls) {
  Atmosphere s = atm;
  auto pick = [&](const std::vector<double>& v) {
    std::vector<double> r;
    for (int l : ls) r.push_back(v[l]);
    return r;
  };
  s.wavelengthsNm = pick(atm.wavelengthsNm);
  s.groundAlbedo = pick(atm.groundAlbedo);
  for (std::size_t c = 0; c < atm.components.size(); ++c) {
    const Component& a = atm.components[c];
    Component& d = s.components[c];
    d.scatteringPerM = pick(a.scatteringPerM);
    d.absorptionPerM = pick(a.absorptionPerM);
    d.phases.clear();
    for (int l : ls) d.phases.push_back(a.phases.at(l));
  }
  return s;
}

void copyChannels2D(const Table2D& from, Table2D& to, const std::vector<int>& ls) {
  const std::size_t n = static_cast<std::size_t>(from.width) * from.height;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < ls.size(); ++k) to.values[i * to.channels + ls[k]] = from.values[i * from.channels + k];
}
}  // namespace

ScatteringCoords scatteringCoordsFromRMuMuSNu(const ShellRadii& shell, const ScatteringTableSize& size,
                                              double muSMin, double r, double mu, double muS, double nu,
                                              bool rayIntersectsGround) {
  const ScatterGeometry g(shell, size, muSMin);
  return {ScatterGeometry::uNu(nu), g.uMuS(muS), g.uMu(r, mu, rayIntersectsGround), g.uR(r)};
}

ScatteringPoint rMuMuSNuFromScatteringCoords(const ShellRadii& shell, const ScatteringTableSize& size,
                                             double muSMin, const ScatteringCoords& c) {
  const ScatterGeometry g(shell, size, muSMin);
  ScatteringPoint p;
  p.r = g.rFromU(c.uR);
  p.mu = g.muFromU(p.r, c.uMu, p.rayIntersectsGround);
  p.muS = g.muSFromU(c.uMuS);
  p.nu = clampCosine(2.0 * c.uNu - 1.0);
  return p;
}

ScatteringPoint scatteringTexelPoint(const ShellRadii& shell, const ScatteringTableSize& size, double muSMin,
                                     int x, int y, int z) {
  return ScatterGeometry(shell, size, muSMin).texel(x, y, z);
}

// ---- precompute ------------------------------------------------------------------------------

int densityDirectionsFor(const Atmosphere& atmosphere) {
  double halfWidthRad = kPi / 2;  // of the narrowest forward peak
  for (const Component& c : atmosphere.components) {
    if (!c.scatters()) continue;
    for (std::size_t l = 0; l < atmosphere.wavelengthsNm.size(); ++l) {
      const PhaseFunction& p = c.phase(l);
      const double forward = p(1.0);
      for (double deg = 0.05; deg < halfWidthRad * 180.0 / kPi; deg += 0.05)
        if (p(std::cos(deg * kPi / 180.0)) <= 0.5 * forward) {
          halfWidthRad = deg * kPi / 180.0;
          break;
        }
    }
  }
  const int n = static_cast<int>(std::ceil(kPi / (1.5 * halfWidthRad) / 8.0)) * 8;
  return std::clamp(n, kMinDensityDirections, 64);
}

AtmosphereTables precompute(const Atmosphere& atmosphere, const PrecomputeOptions& optionsIn,
                            const PrecomputeProgress& progress) {
  if (const std::string e = optionsIn.validate(); !e.empty()) throw std::invalid_argument("PrecomputeOptions: " + e);
  if (const std::string e = atmosphere.validate(); !e.empty()) throw std::invalid_argument("Atmosphere: " + e);
  PrecomputeOptions options = optionsIn;
  if (options.sphereSamples == 0) options.sphereSamples = densityDirectionsFor(atmosphere);
  const int nl = static_cast<int>(atmosphere.wavelengthsNm.size());
  if (nl == 0) throw std::invalid_argument("Atmosphere: no wavelengths");
  const auto t0 = std::chrono::steady_clock::now();

  AtmosphereTables tables;
  tables.options = options;
  tables.bottomRadiusM = atmosphere.bottomRadiusM;
  tables.topRadiusM = atmosphere.topRadiusM;
  tables.wavelengthsNm = atmosphere.wavelengthsNm;
  for (const Component& c : atmosphere.components)
    if (c.scatters()) tables.scatteringComponents.push_back(c.name);

  const int batch = options.wavelengthBatch > 0 ? std::min(options.wavelengthBatch, nl) : nl;
  const int batches = (nl + batch - 1) / batch;
  std::map<std::string, double> timings;
  std::vector<std::string> order;
  const int orders = options.orders;
  const double weight = 1.0 + 0.05 + 0.3 * (options.multipleScatteringSamples != options.singleScatteringSamples ? 2 : 1) +
                        1.0 + (orders - 1) * (2.0 + 0.1 + 1.0);
  const int W = options.scatteringNu * options.scatteringMuS;
  tables.singleScattering.resize(tables.scatteringComponents.size());
  for (Table3D& T : tables.singleScattering) T.resize(W, options.scatteringMu, options.scatteringR, nl);
  tables.multipleScattering.resize(W, options.scatteringMu, options.scatteringR, nl);
  for (int bi = 0; bi < batches; ++bi) {
    std::vector<int> ls;
    for (int l = bi * batch; l < std::min(nl, (bi + 1) * batch); ++l) ls.push_back(l);
    Runner runner(progress, options.threads, static_cast<double>(bi) / batches, static_cast<double>(bi + 1) / batches);
    runner.setStages(weight);
    BatchResult r = computeBatch(batches == 1 ? atmosphere : subAtmosphere(atmosphere, ls), options, runner,
                                 tables.singleScattering, tables.multipleScattering, ls.front());
    if (batches == 1) {
      tables.transmittance = std::move(r.transmittance);
      tables.directIrradiance = std::move(r.directIrradiance);
      tables.irradiance = std::move(r.irradiance);
      tables.orderMeanRadiance = std::move(r.orderMean);
    } else {
      if (bi == 0) {
        auto size2 = [&](Table2D& d, const Table2D& s) { d.resize(s.width, s.height, nl); };
        size2(tables.transmittance, r.transmittance);
        size2(tables.directIrradiance, r.directIrradiance);
        size2(tables.irradiance, r.irradiance);
        tables.orderMeanRadiance.assign(r.orderMean.size(), std::vector<double>(nl, 0.0));
      }
      copyChannels2D(r.transmittance, tables.transmittance, ls);
      copyChannels2D(r.directIrradiance, tables.directIrradiance, ls);
      copyChannels2D(r.irradiance, tables.irradiance, ls);
      for (std::size_t k = 0; k < r.orderMean.size(); ++k)
        for (std::size_t i = 0; i < ls.size(); ++i) tables.orderMeanRadiance[k][ls[i]] = r.orderMean[k][i];
    }
    for (const std::string& s : runner.order) {
      if (std::find(order.begin(), order.end(), s) == order.end()) order.push_back(s);
      timings[s] += runner.timings[s];
    }
  }
  for (const std::string& s : order) tables.timings.push_back({s, timings[s]});
  tables.timings.push_back({"total", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()});
  if (progress && !progress(1.0, "done")) throw PrecomputeCancelled();
  return tables;
}

// ---- lookups ---------------------------------------------------------------------------------

void transmittanceToTop(const AtmosphereTables& tables, double r, double mu, double* out) {
  lookupTransmittance(tables.transmittance, tables.shell(), r, mu, out);
}

std::vector<double> transmittanceToTop(const AtmosphereTables& tables, double r, double mu) {
  std::vector<double> v(tables.wavelengthCount());
  transmittanceToTop(tables, r, mu, v.data());
  return v;
}

std::vector<double> lookupScattering(const AtmosphereTables& tables, const Table3D& table, double r, double mu,
                                     double muS, double nu, bool rayIntersectsGround) {
  const ScatterGeometry g = geometryOf(tables);
  std::vector<double> v(table.channels, 0.0);
  accumulate4(table, rMuCell(g, r, mu, rayIntersectsGround), sNuCell(g, muS, nu), 1.0, v.data());
  return v;
}

std::vector<double> transmittanceAlong(const AtmosphereTables& tables, double r, double mu, double d,
                                       bool rayIntersectsGround, bool endsOnGround) {
  const double b = tables.bottomRadiusM;
  const double rd = endsOnGround ? b : std::clamp(std::sqrt(d * d + 2.0 * r * mu * d + r * r), b, tables.topRadiusM);
  const double mud = clampCosine((r * mu + d) / rd);
  const std::vector<double> a = rayIntersectsGround ? transmittanceToTop(tables, rd, -mud) : transmittanceToTop(tables, r, mu);
  const std::vector<double> c = rayIntersectsGround ? transmittanceToTop(tables, r, -mu) : transmittanceToTop(tables, rd, mud);
  std::vector<double> out(a.size());
  for (std::size_t l = 0; l < a.size(); ++l) out[l] = std::min(a[l] / std::max(c[l], 1e-300), 1.0);
  return out;
}

namespace {

/// skyRadiance's table lookups at a Sun within the tables (muS >= muSMin).
std::vector<double> tableRadiance(const AtmosphereTables& tables, const Atmosphere& atmosphere, double r, double mu,
                                  double muS, double nu, bool ground) {
  std::vector<double> L = lookupScattering(tables, tables.multipleScattering, r, mu, muS, nu, ground);
  for (std::size_t q = 0; q < tables.singleScattering.size(); ++q) {
    const Component& c = atmosphere.component(tables.scatteringComponents[q]);
    const std::vector<double> S = lookupScattering(tables, tables.singleScattering[q], r, mu, muS, nu, ground);
    for (std::size_t l = 0; l < L.size(); ++l) L[l] += S[l] * c.phase(l)(nu);
  }
  return L;
}

}  // namespace

std::vector<double> skyRadiance(const AtmosphereTables& tables, const Atmosphere& atmosphere, double r, double mu,
                                double muS, double nu, const std::vector<double>& solarIrradiance) {
  const int nl = static_cast<int>(tables.wavelengthCount());
  const double b = tables.bottomRadiusM, muSMin = tables.options.muSMin;
  const bool ground = rayIntersectsGround(b, r, mu);
  std::vector<double> L;
  if (muS >= muSMin) {
    L = tableRadiance(tables, atmosphere, r, mu, muS, nu, ground);
  } else {
    const double end = ground ? distanceToBottomBoundaryM(b, r, mu) : distanceToTopBoundaryM(tables.topRadiusM, r, mu);
    const double d = distanceToSunCosineM(r, mu, muS, nu, muSMin);
    if (!(d < end)) return std::vector<double>(nl, 0.0);
    const double rd = std::clamp(std::sqrt(d * d + 2.0 * r * mu * d + r * r), b, tables.topRadiusM);
    L = tableRadiance(tables, atmosphere, rd, clampCosine((r * mu + d) / rd), muSMin, nu, ground);
    const std::vector<double> T = transmittanceAlong(tables, r, mu, d, ground);
    for (int l = 0; l < nl; ++l) L[l] *= T[l];
  }
  if (!solarIrradiance.empty())
    for (int l = 0; l < nl; ++l) L[l] *= solarIrradiance.at(l);
  return L;
}

std::vector<double> indirectIrradiance(const AtmosphereTables& tables, double r, double muS) {
  std::vector<double> v(tables.wavelengthCount(), 0.0);
  if (muS < tables.options.muSMin) return v;
  lookupIrradiance(tables.irradiance, tables.shell(), r, muS, v.data());
  return v;
}

double sunDiscCosine(double muS, double alphaRad) {
  if (muS < -alphaRad) return 0.0;
  if (muS > alphaRad) return muS;
  return (muS + alphaRad) * (muS + alphaRad) / (4.0 * alphaRad);
}

std::vector<double> directIrradiance(const AtmosphereTables& tables, double r, double muS) {
  std::vector<double> v(tables.wavelengthCount());
  directIrradianceAt(tables.transmittance, tables.shell(), tables.options.sunAngularRadiusRad, r, muS, v.data());
  return v;
}

}  // namespace umbra::atmosphere
