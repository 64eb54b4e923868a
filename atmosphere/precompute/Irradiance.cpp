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
  const int nl = B.nl, IW = B.IW;
  const int nIrTh = B.o.irradianceSamples / 2, nIrPh = 2 * B.o.irradianceSamples;
  const double dI = kPi / B.o.irradianceSamples;
  Table2D& nextE = B.nextE;
  BatchResult& out = B.out;
  B.run.run("indirect irradiance", 0.1, B.IH, [&, nl, IW, nIrTh, nIrPh, dI, order](int y) {
    std::vector<double> v(nl);
    for (int x = 0; x < IW; ++x) {
      double r, muS;
      B.irradianceTexel(x, y, r, muS);
      const double sinS = std::sqrt(std::max(0.0, 1.0 - muS * muS));
      std::vector<double> E(nl, 0.0);
      for (int jt = 0; jt < nIrTh; ++jt) {
        const double th = (jt + 0.5) * dI, cz = std::cos(th), sth = std::sin(th);
        for (int ip = 0; ip < nIrPh; ++ip) {
          const double ph = (ip + 0.5) * dI;
          const double nu = clampCosine(std::cos(ph) * sth * sinS + cz * muS);
          std::fill(v.begin(), v.end(), 0.0);
          B.incoming(order - 1, r, cz, muS, nu, false, v.data());
          const double w = cz * sth * dI * dI;
          for (int l = 0; l < nl; ++l) E[l] += v[l] * w;
        }
      }
      std::copy_n(E.data(), nl, nextE.at(x, y));
      double* acc = out.irradiance.at(x, y);
      for (int l = 0; l < nl; ++l) acc[l] += E[l];
    }
  });
}

}  // namespace umbra::atmosphere::stages
