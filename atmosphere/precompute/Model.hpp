#pragma once
// The atmosphere restricted to what the precomputation's integrals need: each component's
// density profile and extinction, the scatterers' coefficients and phase functions (as
// closed-form lobes, or tables where no closed form fits), and the column densities along a
// path (Simpson's rule, split where a profile has a kink) that give the optical depth.
#include "Atmosphere.hpp"
#include "Precompute.hpp"
#include "precompute/Parametrisation.hpp"  // kPi
#include "precompute/Paths.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace umbra::atmosphere::stages {


struct Lobe {  // A (1 + B c^2) / (1 + g^2 - 2 g c)^{3/2}, or a table uniform in c
  double A = 0.0, B = 0.0, g = 0.0;
  std::vector<double> table;
};

struct PhaseModel {
  double a = 0.0, b = 0.0;                    // a + b c^2
  std::vector<std::pair<int, double>> lobes;  // (lobe index, weight)
};

constexpr int kPhaseTableSize = 8192;

struct Model {
  const Atmosphere& atm;
  const PrecomputeOptions& o;
  double b, t, thickness;
  int nl, nc;
  std::vector<const DensityProfile*> profile;  // per component
  std::vector<double> ext;                     // [c * nl + l]
  std::vector<int> scatterers;                 // component indices
  std::vector<double> sca;                     // [s * nl + l] of the scatterers
  std::vector<PhaseModel> phase;               // [s * nl + l]
  std::vector<Lobe> lobes;
  std::vector<std::vector<int>> lobeUsers;     // per lobe: the wavelengths that use it
  std::vector<double> kinkRadii;               // where a profile's derivative jumps

  Model(const Atmosphere& a, const PrecomputeOptions& opt)
      : atm(a), o(opt), b(a.bottomRadiusM), t(a.topRadiusM), thickness(a.topRadiusM - a.bottomRadiusM),
        nl(static_cast<int>(a.wavelengthsNm.size())), nc(static_cast<int>(a.components.size())) {
    for (int c = 0; c < nc; ++c) {
      const Component& comp = a.components[c];
      profile.push_back(&comp.density);
      for (int l = 0; l < nl; ++l) ext.push_back(comp.extinctionPerM(l));
      if (comp.scatters()) scatterers.push_back(c);
      for (double h : comp.density.kinksM())
        if (h > 0.0 && h < thickness) kinkRadii.push_back(b + h);
    }
    std::map<std::string, int> lobeIndex;
    for (int c : scatterers) {
      const Component& comp = a.components[c];
      for (int l = 0; l < nl; ++l) {
        sca.push_back(comp.scatteringPerM[l]);
        phase.push_back(phaseModel(comp.phase(l), l, lobeIndex));
      }
    }
  }

  int addLobe(const Lobe& lobe, int l, const std::string& key, std::map<std::string, int>& index) {
    auto it = index.find(key);
    int i;
    if (it == index.end()) {
      i = static_cast<int>(lobes.size());
      lobes.push_back(lobe);
      lobeUsers.emplace_back();
      index[key] = i;
    } else {
      i = it->second;
    }
    if (std::find(lobeUsers[i].begin(), lobeUsers[i].end(), l) == lobeUsers[i].end()) lobeUsers[i].push_back(l);
    return i;
  }

  /// Where cosine c falls in a tabulated lobe: between entries i and i + 1, weight w on i + 1.
  static void tablePosition(double c, int& i, double& w) {
    const double f = (std::clamp(c, -1.0, 1.0) + 1.0) * 0.5 * (kPhaseTableSize - 1);
    i = std::min(static_cast<int>(f), kPhaseTableSize - 2);
    w = f - i;
  }
  static double evalLobe(const Lobe& lobe, double c) {
    if (!lobe.table.empty()) {
      int i;
      double w;
      tablePosition(c, i, w);
      return (1 - w) * lobe.table[i] + w * lobe.table[i + 1];
    }
    const double d = 1.0 + lobe.g * lobe.g - 2.0 * lobe.g * c;
    return lobe.A * (1.0 + lobe.B * c * c) / (d * std::sqrt(d));
  }

  PhaseModel phaseModel(const PhaseFunction& p, int l, std::map<std::string, int>& index) {
    PhaseModel m;
    using K = PhaseFunction::Kind;
    auto hg = [](double g) { return Lobe{(1.0 - g * g) / (4.0 * kPi), 0.0, g, {}}; };
    switch (p.kind()) {
      case K::Isotropic:
      case K::Rayleigh:
      case K::Penndorf:
        m.a = p(0.0), m.b = p(1.0) - p(0.0);
        break;
      case K::HenyeyGreenstein:
        m.lobes.push_back({addLobe(hg(p.g()), l, "hg" + std::to_string(p.g()), index), 1.0});
        break;
      case K::DoubleHenyeyGreenstein:
        m.lobes.push_back({addLobe(hg(p.g()), l, "hg" + std::to_string(p.g()), index), p.alpha()});
        m.lobes.push_back({addLobe(hg(p.g2()), l, "hg" + std::to_string(p.g2()), index), 1.0 - p.alpha()});
        break;
      case K::CornetteShanks: {
        const double g = p.g();
        Lobe cs{3.0 / (8.0 * kPi) * (1.0 - g * g) / (2.0 + g * g), 1.0, g, {}};
        m.lobes.push_back({addLobe(cs, l, "cs" + std::to_string(g), index), 1.0});
        break;
      }
      case K::Tabulated:
        break;
    }
    // Check the closed form against the function; fall back to a table when they differ
    // (or the function is tabulated).
    bool ok = p.kind() != K::Tabulated;
    for (int i = 0; ok && i <= 16; ++i) {
      const double c = -1.0 + i / 8.0;
      double v = m.a + m.b * c * c;
      for (auto [li, w] : m.lobes) v += w * evalLobe(lobes[li], c);
      if (std::abs(v - p(c)) > 1e-9 * std::max(1.0, std::abs(p(c)))) ok = false;
    }
    if (!ok) {
      m = PhaseModel{};
      Lobe tab;
      tab.table.resize(kPhaseTableSize);
      for (int i = 0; i < kPhaseTableSize; ++i) tab.table[i] = p(-1.0 + 2.0 * i / (kPhaseTableSize - 1));
      // keyed by the table's bytes: equal tables share a lobe, different ones (e.g. one
      // Lorenz-Mie table per wavelength, all with the same sample count) never do
      const std::string key(reinterpret_cast<const char*>(tab.table.data()), tab.table.size() * sizeof(double));
      m.lobes.push_back({addLobe(tab, l, "table:" + key, index), 1.0});
    }
    return m;
  }

  double density(int c, double altitudeM) const {
    return profile[c]->at(std::clamp(altitudeM, 0.0, thickness));
  }

  /// Per-component column densities (integral of rho_c ds) along a path from s0 to s1,
  /// Simpson's rule with n (even) intervals; added to col[0..nc). On straight paths the
  /// interval is split where the ray crosses the profiles' kinks (tent, tabulated, the
  /// boundary layer's steps), so that piecewise-smooth profiles are integrated to rounding.
  void columns(const Path& path, double s0, double s1, int n, std::size_t& seg, double* col) const {
    if (!(s1 > s0)) return;
    if (!kinkRadii.empty()) {
      std::vector<double> cuts{s0, s1};
      if (path.knots.size() == 2) {
        const double r = path.knots[0].y, mu = path.knots[0].ty;
        for (double R : kinkRadii) {
          const double disc = r * r * (mu * mu - 1.0) + R * R;
          if (disc < 0.0) continue;
          for (double sgn : {-1.0, 1.0}) {
            const double s = -r * mu + sgn * std::sqrt(disc);
            if (s > s0 && s < s1) cuts.push_back(s);
          }
        }
      } else {
        // Traced: sign changes of r - R_k on a grid finer than the knots, then bisection.
        std::size_t c = 0;
        auto radiusAt = [&](double sv) {
          double x, y;
          path.position(sv, c, x, y);
          return std::sqrt(x * x + y * y);
        };
        std::size_t inside = 0;
        for (const Knot& k : path.knots) inside += (k.s > s0 && k.s < s1);
        const int M = static_cast<int>(4 * inside + 8);
        // A grid interval is looked at only where the knots around it come near a kink: between
        // two knots L apart the path dips below its ends by at most about L^2 / (8 r) (a
        // straight chord; refraction bends it less than that); the margin is 4 times that and
        // a metre. Elsewhere no radius is evaluated, and the cuts are the same.
        // Radius bounds of the knot segments from q0 on that [s0, s1] overlaps (a view ray asks
        // for one short interval at a time: only those segments are looked at).
        const std::vector<Knot>& knots = path.knots;
        std::size_t q0 = 0;
        while (q0 + 2 < knots.size() && knots[q0 + 1].s <= s0) ++q0;
        std::vector<double> segLo, segHi;
        for (std::size_t q = q0; q + 1 < knots.size() && knots[q].s < s1; ++q) {
          const Knot &a = knots[q], &e = knots[q + 1];
          const double ra = std::sqrt(a.x * a.x + a.y * a.y), re = std::sqrt(e.x * e.x + e.y * e.y);
          const double margin = 1.0 + (e.s - a.s) * (e.s - a.s) / (2.0 * std::max(std::min(ra, re), 1.0));
          segLo.push_back(std::min(ra, re) - margin), segHi.push_back(std::max(ra, re) + margin);
        }
        std::size_t j = 0;  // the segment q0 + j holding the interval's start
        auto nearKink = [&](double sa, double sb) {
          if (segLo.empty()) return true;
          while (j + 1 < segLo.size() && knots[q0 + j + 1].s <= sa) ++j;
          double lo = segLo[j], hi = segHi[j];
          for (std::size_t q = j + 1; q < segLo.size() && knots[q0 + q].s < sb; ++q)
            lo = std::min(lo, segLo[q]), hi = std::max(hi, segHi[q]);
          for (double R : kinkRadii)
            if (R >= lo && R <= hi) return true;
          return false;
        };
        double sa = s0, ra = std::nan("");
        for (int i = 1; i <= M; ++i) {
          const double sb = s0 + (s1 - s0) * i / M;
          if (!nearKink(sa, sb)) {
            sa = sb, ra = std::nan("");
            continue;
          }
          if (std::isnan(ra)) ra = radiusAt(sa);
          const double rb = radiusAt(sb);
          for (double R : kinkRadii) {
            if (ra == R && sa > s0) cuts.push_back(sa);
            if ((ra - R) * (rb - R) >= 0.0) continue;
            double lo = sa, hi = sb, flo = ra - R;
            for (int it = 0; it < 60 && hi - lo > 1e-7; ++it) {
              const double mid = 0.5 * (lo + hi), fm = radiusAt(mid) - R;
              if ((fm < 0.0) == (flo < 0.0)) lo = mid, flo = fm; else hi = mid;
            }
            cuts.push_back(0.5 * (lo + hi));
          }
          sa = sb, ra = rb;
        }
      }
      if (cuts.size() > 2) {
        std::sort(cuts.begin(), cuts.end());
        for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
          const double len = cuts[i + 1] - cuts[i];
          if (!(len > 0.0)) continue;
          int k = static_cast<int>(std::ceil(n * len / (s1 - s0) / 2.0)) * 2;
          simpson(path, cuts[i], cuts[i + 1], std::max(2, k), seg, col);
        }
        return;
      }
    }
    simpson(path, s0, s1, n, seg, col);
  }
  void simpson(const Path& path, double s0, double s1, int n, std::size_t& seg, double* col) const {
    const double h = (s1 - s0) / n;
    for (int i = 0; i <= n; ++i) {
      const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
      // The ends a hair inside: at a cut where a profile jumps (the mixing layer's top) the
      // density is the piece's own.
      const double at = i == 0 ? s0 + 1e-9 * h : i == n ? s1 - 1e-9 * h : s0 + i * h;
      double x, y;
      path.position(at, seg, x, y);
      const double alt = std::sqrt(x * x + y * y) - b;
      for (int c = 0; c < nc; ++c) col[c] += w * h / 3.0 * density(c, alt);
    }
  }
  void opticalDepth(const double* col, double* tau) const {
    for (int l = 0; l < nl; ++l) {
      double s = 0.0;
      for (int c = 0; c < nc; ++c) s += ext[c * nl + l] * col[c];
      tau[l] = s;
    }
  }
};

}  // namespace umbra::atmosphere::stages
