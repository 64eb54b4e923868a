// The scattering density J_k at each texel: the incoming L_(k-1) from a sphere of
// directions (Gauss-Legendre in mu on each side of the horizon, midpoint in phi, each
// direction standing for its mirror too), plus the ground's reflection of E_(k-2), times
// each scatterer's phase function towards the view: the Rayleigh-like part a + b c^2 from
// the light's moments, the lobes from its azimuthal cosine modes (AzimuthModes), each lobe
// renormalised to its exact integral over the sphere.
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
  const TexelPoints& points = B.points;
  const int nTh = d.nTh, nPh = d.nPh, nDir = d.nDir;
  const std::vector<double>&wxAll = d.wx, &wyAll = d.wy, &wzAll = d.wz, &wdoAll = d.wdo;
  const std::vector<double>&groundT = d.groundT, &groundD = d.groundD, &lobeIntegral = d.lobeIntegral;

  // The lobes, integrated in azimuth by their cosine modes (AzimuthModes): the light of each
  // ring of directions interpolated by its cosine series, integrated against the lobe
  // however narrow its peak, for nPh products per ring and view instead of 2 nPh lobe
  // values. The lobes' modes (gamma) depend on the radius, the view's zenith cosine and the
  // ring; the light's (alpha, here of Lw = L wdo) on the radius and the Sun. The lobes: each
  // closed-form one (for the wavelengths that use it), and per wavelength the tabulated ones
  // (Lorenz-Mie's) summed with their weights at the radius into one table. Each one's sum
  // over the directions, sum_lt wdo_lt gamma_0 (wdo_lt = 2 dA dMu_lt: the sum with alpha
  // from Lw is 2 dA times the integral), is renormalised to its exact integral.
  std::vector<int> formLobes;
  for (std::size_t li = 0; li < m.lobes.size(); ++li)
    if (m.lobes[li].table.empty()) formLobes.push_back(static_cast<int>(li));
  const int nForm = static_cast<int>(formLobes.size());
  const AzimuthModes am(nPh);
  const int Q = am.Q;
  std::vector<int> everyWavelength(nl);
  for (int l = 0; l < nl; ++l) everyWavelength[l] = l;

  // A few radii a step when L_(k-1) spills: a radius reads the r slices around it; those
  // below the next step's leave memory, the next step's come in.
  SliceWindow window(B.incomingTables(order - 1));
  const int step = B.run.threadCount();
  const auto between = [&](int done) {
    if (done >= B.R) return window(B.R, B.R);
    const int last = std::min(done + step, B.R) - 1;
    window(B.sliceAt(g.texel(0, 0, done).r), B.sliceAt(g.texel(0, 0, last).r) + 2);
  };
  B.run.run("scattering density", 2.0, B.R, [&, g, b, alpha, nl, ns, MU, MUS, nTh, nPh, nDir, nForm, Q, order](int z) {
    const std::size_t zd = static_cast<std::size_t>(z) * nDir, ringModes = static_cast<std::size_t>(nTh) * nPh;
    const double *wx = &wxAll[zd], *wy = &wyAll[zd], *wz = &wzAll[zd], *wdo = &wdoAll[zd];
    const double r = g.texel(0, 0, z).r, alt = r - b;
    std::vector<double> rho(ns);
    for (int q = 0; q < ns; ++q) rho[q] = m.density(m.scatterers[q], alt);
    // The tabulated lobes of a wavelength summed into one table with their weights at this
    // altitude (sca rho w), the wavelengths side by side (mixed[i * nl + l]), and its
    // integral over the sphere.
    std::vector<double> mixed, mixedIntegral(nl, 0.0);
    for (int q = 0; q < ns; ++q)
      for (int l = 0; l < nl; ++l)
        for (auto [li, w] : m.phase[q * nl + l].lobes) {
          if (m.lobes[li].table.empty()) continue;
          if (mixed.empty()) mixed.assign(static_cast<std::size_t>(nl) * kPhaseTableSize, 0.0);
          const double f = m.sca[q * nl + l] * rho[q] * w;
          const double* T = m.lobes[li].table.data();
          for (int i = 0; i < kPhaseTableSize; ++i) mixed[static_cast<std::size_t>(i) * nl + l] += f * T[i];
          mixedIntegral[l] += f * lobeIntegral[li];
        }
    const bool tabulated = !mixed.empty();

    // First per Sun (mu_s): the incoming light's moments (M0, M2) and its modes in azimuth
    // (alpha, every wavelength: [((is * nl + l) * nTh + lt) * nPh + k]).
    const std::size_t lightModes = static_cast<std::size_t>(nl) * ringModes;
    std::vector<double> M0(static_cast<std::size_t>(MUS) * nl, 0.0), M2(static_cast<std::size_t>(MUS) * nl * 6, 0.0);
    std::vector<double> alphaModes(nForm > 0 || tabulated ? MUS * lightModes : 0), muSOf(MUS), sinSOf(MUS);
    {
      std::vector<double> Lw(static_cast<std::size_t>(nl) * nDir), v(nl), E(nl);
      std::vector<RMuCell> rMuOf(nDir);  // a direction's (r, mu) cell: the same for every Sun
      for (int j = 0; j < nDir; ++j) rMuOf[j] = rMuCell(g, r, wz[j], groundD[z * nTh + j / nPh] >= 0.0);
      for (int is = 0; is < MUS; ++is) {
        muSOf[is] = g.texel(is, 0, z).muS, sinSOf[is] = std::sqrt(std::max(0.0, 1.0 - muSOf[is] * muSOf[is]));
        const double muS = muSOf[is], sinS = sinSOf[is];
        double* m0 = &M0[static_cast<std::size_t>(is) * nl];
        double* m2 = &M2[static_cast<std::size_t>(is) * nl * 6];
        // Incoming radiance per direction, times the solid angle: Lw[l][j].
        for (int j = 0; j < nDir; ++j) {
          const int lt = j / nPh;
          const double nu = clampCosine(wx[j] * sinS + wz[j] * muS);
          const bool ground = groundD[z * nTh + lt] >= 0.0;
          std::fill(v.begin(), v.end(), 0.0);
          B.incoming(order - 1, rMuOf[j], sNuCell(g, muS, nu), nu, v.data());
          if (ground) {
            const double dg = groundD[z * nTh + lt];
            const double muSg = clampCosine((r * muS + dg * nu) / b);
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
            m0[l] += L;
            double* M = &m2[l * 6];
            // xy and yz cancel with the mirror (M[3] = M[5] = 0)
            M[0] += wx[j] * wx[j] * L, M[1] += wy[j] * wy[j] * L, M[2] += wz[j] * wz[j] * L;
            M[4] += wx[j] * wz[j] * L;
          }
        }
        if (alphaModes.empty()) continue;
        for (int l = 0; l < nl; ++l)
          for (int lt = 0; lt < nTh; ++lt)
            cosineModes(&Lw[static_cast<std::size_t>(l) * nDir + static_cast<std::size_t>(lt) * nPh], am.phiModes.data(), nPh,
                        nPh, &alphaModes[is * lightModes + (static_cast<std::size_t>(l) * nTh + lt) * nPh]);
      }
    }

    // Then per view zenith (mu): each lobe's modes, gamma (closed-form lobe f:
    // [(f * nTh + lt) * nPh + k]; each wavelength's tabulated one: [(l * nTh + lt) * nPh + k])
    // and norm; per Sun their products with the light's summed over the rings (C); per view
    // the modes' cosines (cheb) and the sums.
    std::vector<double> gammaForm(static_cast<std::size_t>(nForm) * ringModes), normForm(nForm);
    std::vector<double> gammaMixed(tabulated ? lightModes : 0), normMixed(tabulated ? nl : 0);
    std::vector<double> cq(Q), pq(Q), tw(Q), cheb(nPh), lobeSum(m.lobes.size() * nl), J(nl);
    std::vector<int> ti(Q);
    std::vector<std::vector<double>> C(nForm);
    for (int f = 0; f < nForm; ++f) C[f].resize(m.lobeUsers[formLobes[f]].size() * nPh);
    std::vector<double> Cmixed(tabulated ? static_cast<std::size_t>(nl) * nPh : 0);
    for (int y = 0; y < MU; ++y) {
      const double vzY = g.texel(0, y, z).mu, szY = std::sqrt(std::max(0.0, 1.0 - vzY * vzY));
      std::fill(normForm.begin(), normForm.end(), 0.0);
      std::fill(normMixed.begin(), normMixed.end(), 0.0);
      for (int lt = 0; lt < nTh; ++lt) {
        const double wzl = wz[lt * nPh], sinL = std::sqrt(std::max(0.0, 1.0 - wzl * wzl));
        const double ringWdo = wdo[lt * nPh];
        for (int q = 0; q < Q; ++q) cq[q] = wzl * vzY + sinL * szY * am.qCos[q];
        for (int f = 0; f < nForm; ++f) {
          const Lobe& lobe = m.lobes[formLobes[f]];
          double* gm = &gammaForm[(static_cast<std::size_t>(f) * nTh + lt) * nPh];
          lobeValues(lobe.A, lobe.B, lobe.g, cq.data(), pq.data(), Q);
          cosineModes(pq.data(), am.qModes.data(), Q, nPh, gm);
          normForm[f] += ringWdo * gm[0];
        }
        if (!tabulated) continue;
        tablePositions(cq.data(), Q, ti.data(), tw.data());
        for (int l = 0; l < nl; ++l) {
          for (int q = 0; q < Q; ++q) {
            const double* row = &mixed[static_cast<std::size_t>(ti[q]) * nl + l];
            pq[q] = row[0] + tw[q] * (row[nl] - row[0]);
          }
          double* gm = &gammaMixed[(static_cast<std::size_t>(l) * nTh + lt) * nPh];
          cosineModes(pq.data(), am.qModes.data(), Q, nPh, gm);
          normMixed[l] += ringWdo * gm[0];
        }
      }
      for (int is = 0; is < MUS; ++is) {
        const double muS = muSOf[is], sinS = sinSOf[is];
        const double* alphaIs = alphaModes.empty() ? nullptr : &alphaModes[is * lightModes];
        const double* m0 = &M0[static_cast<std::size_t>(is) * nl];
        const double* m2 = &M2[static_cast<std::size_t>(is) * nl * 6];
        for (int f = 0; f < nForm; ++f) {
          const std::vector<int>& users = m.lobeUsers[formLobes[f]];
          modeProducts(alphaIs, users.data(), static_cast<int>(users.size()),
                       &gammaForm[static_cast<std::size_t>(f) * ringModes], 0, nTh, nPh, C[f].data());
        }
        if (tabulated)
          modeProducts(alphaIs, everyWavelength.data(), nl, gammaMixed.data(), ringModes, nTh, nPh, Cmixed.data());
        for (int k = 0; k < o.scatteringNu; ++k) {
          const int x = k * MUS + is;
          const ScatteringPoint p = points(x, y, z);
          const double sz = std::sqrt(std::max(0.0, 1.0 - p.mu * p.mu));
          double vx = sinS > 1e-12 ? std::clamp((p.nu - p.mu * muS) / sinS, -sz, sz) : sz;
          const double vy = std::sqrt(std::max(0.0, sz * sz - vx * vx)), vz = p.mu;
          // cos(m phi_v) by the Chebyshev recurrence; each lobe's sum over the modes
          // renormalised to its exact integral over the sphere (one norm for all users).
          const double c1 = sz > 1e-12 ? std::clamp(vx / sz, -1.0, 1.0) : 1.0;
          cheb[0] = 1.0;
          if (nPh > 1) cheb[1] = c1;
          for (int k2 = 2; k2 < nPh; ++k2) cheb[k2] = 2.0 * c1 * cheb[k2 - 1] - cheb[k2 - 2];
          const auto modeSum = [&](const double* c) {
            double sum = 0.0;
            for (int k2 = 0; k2 < nPh; ++k2) sum += c[k2] * cheb[k2];
            return sum;
          };
          for (int f = 0; f < nForm; ++f) {
            const int li = formLobes[f];
            const std::vector<int>& users = m.lobeUsers[li];
            const double scale = normForm[f] > 0.0 ? lobeIntegral[li] / normForm[f] : 1.0;
            for (std::size_t u = 0; u < users.size(); ++u) lobeSum[li * nl + users[u]] = scale * modeSum(&C[f][u * nPh]);
          }
          for (int l = 0; l < nl; ++l) {
            J[l] = 0.0;
            if (!tabulated) continue;
            J[l] = (normMixed[l] > 0.0 ? mixedIntegral[l] / normMixed[l] : 1.0) * modeSum(&Cmixed[static_cast<std::size_t>(l) * nPh]);
          }
          for (int q = 0; q < ns; ++q) {
            for (int l = 0; l < nl; ++l) {
              const PhaseModel& pm = m.phase[q * nl + l];
              double s = 0.0;
              if (pm.a != 0.0 || pm.b != 0.0) {
                const double* M = &m2[l * 6];
                const double vMv = vx * vx * M[0] + vy * vy * M[1] + vz * vz * M[2] +
                                   2.0 * (vx * vy * M[3] + vx * vz * M[4] + vy * vz * M[5]);
                s += pm.a * m0[l] + pm.b * vMv;
              }
              for (auto [li, w] : pm.lobes)
                if (m.lobes[li].table.empty()) s += w * lobeSum[li * nl + l];
              J[l] += m.sca[q * nl + l] * rho[q] * s;
            }
          }
          std::copy_n(J.data(), nl, density.at(x, y, z));
        }
      }
    }
  }, window.spilled() ? step : 0, between);
}

}  // namespace umbra::atmosphere::stages
