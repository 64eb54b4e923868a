// The scattering density J_k at each texel: the incoming L_(k-1) from a sphere of
// directions (Gauss-Legendre in mu on each side of the horizon, midpoint in phi, each
// direction standing for its mirror too), plus the ground's reflection of E_(k-2), times
// each scatterer's phase function towards the view (the forward lobes renormalised to their
// exact integral over the sphere).
#include "precompute/Batch.hpp"
#include "precompute/Kernels.hpp"
#include "precompute/Paths.hpp"

#include "Quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace umbra::atmosphere::stages {

void prepareDensityDirections(Batch& B) {
  const PrecomputeOptions& o = B.o;
  const Model& m = B.m;
  const ScatterGeometry g = B.g;  // a copy: the stores into the tables cannot alias it
  const double b = B.b;
  const int nl = B.nl, nc = B.nc, R = B.R;
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

  DensityDirections& d = B.directions;
  d.nTh = nTh, d.nPh = nPh, d.nDir = nDir;
  d.wx = std::move(wxAll), d.wy = std::move(wyAll), d.wz = std::move(wzAll), d.wdo = std::move(wdoAll);
  d.groundT = std::move(groundT), d.groundD = std::move(groundD), d.lobeIntegral = std::move(lobeIntegral);
}

void computeScatteringDensity(Batch& B, int order) {
  const Atmosphere& atm = B.atm;
  const PrecomputeOptions& o = B.o;
  const Model& m = B.m;
  const ScatterGeometry g = B.g;  // a copy: the stores into the tables cannot alias it
  const ShellRadii& shell = B.shell;
  const double b = B.b, alpha = B.alpha;
  const int nl = B.nl, ns = B.ns, MU = B.MU, MUS = B.MUS;
  const Table2D& Ttab = B.out.transmittance;
  const Table2D& deltaE = B.deltaE;
  FloatTable3D& density = B.density;
  const DensityDirections& d = B.directions;
  const int nTh = d.nTh, nPh = d.nPh, nDir = d.nDir;
  const std::vector<double>&wxAll = d.wx, &wyAll = d.wy, &wzAll = d.wz, &wdoAll = d.wdo;
  const std::vector<double>&groundT = d.groundT, &groundD = d.groundD, &lobeIntegral = d.lobeIntegral;
  B.run.run("scattering density", 2.0, B.R * MUS,
            [&, g, b, alpha, nl, ns, MU, MUS, nTh, nPh, nDir, order](int task) {
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
      B.incoming(order - 1, r, wz[j], muS, nu, ground, v.data());
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
    // The tabulated lobes of a wavelength (Lorenz-Mie's, one per component) summed into one
    // table with their weights at this altitude (sca rho w): one lookup per direction and
    // wavelength, however many aerosol populations; renormalised as one lobe. The
    // wavelengths side by side (mixed[i * stride + l], and the incoming light so too in
    // LwT): one lookup reads four (tableSums).
    const int stride = (nl + 3) / 4 * 4;
    std::vector<double> mixed, LwT, mixedIntegral(nl, 0.0), mixedNorm(stride), mixedSum(stride);
    for (int q = 0; q < ns; ++q)
      for (int l = 0; l < nl; ++l)
        for (auto [li, w] : m.phase[q * nl + l].lobes) {
          if (m.lobes[li].table.empty()) continue;
          if (mixed.empty()) mixed.assign(static_cast<std::size_t>(stride) * kPhaseTableSize, 0.0);
          const double f = m.sca[q * nl + l] * rho[q] * w;
          const double* T = m.lobes[li].table.data();
          for (int i = 0; i < kPhaseTableSize; ++i) mixed[static_cast<std::size_t>(i) * stride + l] += f * T[i];
          mixedIntegral[l] += f * lobeIntegral[li];
        }
    if (!mixed.empty()) {
      LwT.assign(static_cast<std::size_t>(stride) * nDir, 0.0);
      for (int l = 0; l < nl; ++l)
        for (int j = 0; j < nDir; ++j) LwT[static_cast<std::size_t>(j) * stride + l] = Lw[static_cast<std::size_t>(l) * nDir + j];
    }
    // cj: the cosines with the view of the directions [0, nDir) and of their mirrors (for
    // the tabulated lobes).
    std::vector<double> cj(2 * nDir), pPair(nDir), lobeSum(m.lobes.size() * nl), J(nl), sums(nl + 1);
    // Tabulated lobes (one per wavelength for Lorenz-Mie) share the cosines: the table
    // index and weight of each, computed once per view (as Model::evalLobe does).
    std::vector<int> tableIndex(2 * nDir);
    std::vector<double> tableWeight(2 * nDir);
    for (int y = 0; y < MU; ++y) {
      for (int k = 0; k < o.scatteringNu; ++k) {
        const int x = k * MUS + is;
        const ScatteringPoint p = g.texel(x, y, z);
        const double sz = std::sqrt(std::max(0.0, 1.0 - p.mu * p.mu));
        double vx = sinS > 1e-12 ? std::clamp((p.nu - p.mu * muS) / sinS, -sz, sz) : sz;
        const double vy = std::sqrt(std::max(0.0, sz * sz - vx * vx)), vz = p.mu;
        if (!mixed.empty()) {
#pragma omp simd
          for (int j = 0; j < nDir; ++j) {
            cj[j] = wx[j] * vx + wy[j] * vy + wz[j] * vz;
            cj[nDir + j] = wx[j] * vx - wy[j] * vy + wz[j] * vz;
          }
        }
        if (!mixed.empty()) tablePositions(cj.data(), 2 * nDir, tableIndex.data(), tableWeight.data());
        // A closed-form lobe's values over the directions, each averaged with its mirror's,
        // summed against each of its wavelengths' incoming light and renormalised to the
        // lobe's exact integral (one norm for all of them).
        for (std::size_t li = 0; li < m.lobes.size(); ++li) {
          const Lobe& lobe = m.lobes[li];
          if (!lobe.table.empty()) continue;
          const std::vector<int>& users = m.lobeUsers[li];
          lobePairSums(lobe.A, lobe.B, lobe.g, wx, wy, wz, vx, vy, vz, nDir, wdo, Lw.data(), users.data(),
                       static_cast<int>(users.size()), pPair.data(), sums.data());
          const double scale = sums[0] > 0.0 ? lobeIntegral[li] / sums[0] : 1.0;
          for (std::size_t u = 0; u < users.size(); ++u) lobeSum[li * nl + users[u]] = scale * sums[1 + u];
        }
        std::fill(J.begin(), J.end(), 0.0);
        if (!mixed.empty()) {
          tableSums(mixed.data(), stride, tableIndex.data(), tableWeight.data(), nDir, wdo, LwT.data(),
                    mixedNorm.data(), mixedSum.data());
          for (int l = 0; l < nl; ++l)
            J[l] = (mixedNorm[l] > 0.0 ? mixedIntegral[l] / mixedNorm[l] : 1.0) * mixedSum[l];
        }
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
            for (auto [li, w] : pm.lobes)
              if (m.lobes[li].table.empty()) s += w * lobeSum[li * nl + l];
            J[l] += m.sca[q * nl + l] * rho[q] * s;
          }
        }
        std::copy_n(J.data(), nl, density.at(x, y, z));
      }
    }
  });
}

}  // namespace umbra::atmosphere::stages
