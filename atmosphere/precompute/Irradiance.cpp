// The irradiance at the ground and in the air, per (r, mu_s): the direct E_0 (the Sun's
// transmittance times the cosine of its visible disc) and, for each order, the indirect
// E_(k-1), the incoming L_(k-1) integrated over the upper hemisphere (midpoint rule in
// theta and phi).
#include "precompute/Batch.hpp"
#include "precompute/Kernels.hpp"
#include "precompute/Paths.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace umbra::atmosphere::stages {

void computeDirectIrradiance(Batch& B) {
  const ShellRadii& shell = B.shell;
  const double alpha = B.alpha;
  const int IW = B.IW, IH = B.IH;
  BatchResult& out = B.out;
  const Table2D& Ttab = out.transmittance;
  out.directIrradiance.resize(IW, IH, B.nl);
  out.irradiance.resize(IW, IH, B.nl);
  B.run.run("direct irradiance", 0.05, IH, [&, IW, alpha](int y) {
    for (int x = 0; x < IW; ++x) {
      double r, muS;
      B.irradianceTexel(x, y, r, muS);
      directIrradianceAt(Ttab, shell, alpha, r, muS, out.directIrradiance.at(x, y));
    }
  });
}

void computeIndirectIrradiance(Batch& B, int order) {
  const ScatterGeometry g = B.g;  // a copy: the stores into the tables cannot alias it
  const int nl = B.nl, IW = B.IW;
  const int nIrTh = B.o.irradianceSamples / 2, nIrPh = 2 * B.o.irradianceSamples;
  const double dI = kPi / B.o.irradianceSamples;
  const std::size_t nDir = static_cast<std::size_t>(nIrTh) * nIrPh;
  Table2D& nextE = B.nextE;
  BatchResult& out = B.out;
  std::vector<double> cosTh(nIrTh), sinTh(nIrTh);
  for (int jt = 0; jt < nIrTh; ++jt) {
    const double th = (jt + 0.5) * dI;
    cosTh[jt] = std::cos(th), sinTh[jt] = std::sin(th);
  }
  // The directions' (mu_s, nu) cells of each Sun column: the same at every radius and order.
  std::vector<SNuCell>& sNu = B.irradianceSNu;
  std::vector<double>& nuOf = B.irradianceNu;
  if (sNu.empty()) {
    sNu.resize(IW * nDir), nuOf.resize(IW * nDir);
    for (int x = 0; x < IW; ++x) {
      double r, muS;
      B.irradianceTexel(x, 0, r, muS);
      const double sinS = std::sqrt(std::max(0.0, 1.0 - muS * muS));
      for (int jt = 0; jt < nIrTh; ++jt)
        for (int ip = 0; ip < nIrPh; ++ip) {
          const double ph = (ip + 0.5) * dI;
          const std::size_t j = x * nDir + static_cast<std::size_t>(jt) * nIrPh + ip;
          nuOf[j] = clampCosine(std::cos(ph) * sinTh[jt] * sinS + cosTh[jt] * muS);
          sNu[j] = sNuCell(g, muS, nuOf[j]);
        }
    }
  }
  // Row (radius) by row, a step each when L_(k-1) spills: a row reads the two r slices
  // around its radius; those below the next row's leave memory, the next row's come in.
  SliceWindow window(B.incomingTables(order - 1));
  const auto between = [&](int done) {
    if (done >= IW * B.IH) return window(B.R, B.R);
    double r, muS;
    B.irradianceTexel(0, done / IW, r, muS);
    window(B.sliceAt(r), B.sliceAt(r) + 2);
  };
  B.run.run("indirect irradiance", 0.1, IW * B.IH, [&, g, nl, IW, nIrTh, nIrPh, dI, nDir, order](int i) {
    const int x = i % IW, y = i / IW;
    double r, muS;
    B.irradianceTexel(x, y, r, muS);
    std::vector<RMuCell> rMu(nIrTh);
    for (int jt = 0; jt < nIrTh; ++jt) rMu[jt] = rMuCell(g, r, cosTh[jt], false);
    std::vector<double> v(nl), E(nl, 0.0);
    for (int jt = 0; jt < nIrTh; ++jt) {
      const double w = cosTh[jt] * sinTh[jt] * dI * dI;
      for (int ip = 0; ip < nIrPh; ++ip) {
        const std::size_t j = x * nDir + static_cast<std::size_t>(jt) * nIrPh + ip;
        std::fill(v.begin(), v.end(), 0.0);
        B.incoming(order - 1, rMu[jt], sNu[j], nuOf[j], v.data());
        for (int l = 0; l < nl; ++l) E[l] += v[l] * w;
      }
    }
    std::copy_n(E.data(), nl, nextE.at(x, y));
    double* acc = out.irradiance.at(x, y);
    for (int l = 0; l < nl; ++l) acc[l] += E[l];
  }, window.spilled() ? IW : 0, between);
}

}  // namespace umbra::atmosphere::stages
