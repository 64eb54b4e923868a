#include "AtmosphericShadow.hpp"

#include "Colour.hpp"
#include "ParallelErrors.hpp"

#include "Atmosphere.hpp"
#include "Precompute.hpp"
#include "Quadrature.hpp"
#include "Refraction.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace umbra::eclipse {
namespace {

constexpr double kPi = 3.14159265358979323846;

double sq(double x) { return x * x; }

/// cos(a) - cos(b) without cancellation.
double cosDifference(double a, double b) { return 2.0 * std::sin(0.5 * (a + b)) * std::sin(0.5 * (b - a)); }

/// Gauss-Legendre nodes and weights on [0, 1], N points; with SunRow::integral's
/// substitution at each node t = pi x: (1 - cos t) / 2 and sin t.
template <int N>
struct GaussLegendre {  // on [0, 1]
  std::array<double, N> x{}, w{}, halfVersine{}, sine{};
  GaussLegendre() {
    const atmosphere::GaussLegendreRule rule(N);
    for (int i = 0; i < N; ++i) {
      x[i] = 0.5 * (1.0 - rule.x[i]), w[i] = 0.5 * rule.w[i];
      halfVersine[i] = 0.5 * (1.0 - std::cos(kPi * x[i])), sine[i] = std::sin(kPi * x[i]);
    }
  }
};
template <int N>
const GaussLegendre<N>& gaussLegendre() {
  static const GaussLegendre<N> g;
  return g;
}

/// One limb-view row and where the Sun is seen through it. Along the row the azimuth beta
/// enters only through s = sin(beta / 2), so the row integrates in s (dbeta = 2 ds /
/// sqrt(1 - s^2)): the quadrature nodes then need a square root, not a sine.
struct SunRow {
  double A = 0.0, B = 0.0, K = 1.0;  ///< sin^2(a/2) = A + B s^2; K = sin^2(phi_sun/2)
  double cosTheta = 1.0, sinTheta = 0.0, cosDelta = 1.0, sinDelta = 0.0;
  double limbDarkening = 0.6;
  double sBegin = 0.0, sEnd = 0.0;  ///< the chord of the solar disc in s; empty when equal
  bool empty() const { return sEnd <= sBegin; }
  double betaBegin() const { return 2.0 * std::asin(sBegin); }
  double betaEnd() const { return 2.0 * std::asin(sEnd); }

  /// Radiance of the Sun (relative: the disc's mean is 1) times the cosine towards the Sun,
  /// per unit s (the factor dbeta / ds). rho^2 = (A + B s^2) / K and the cosine
  /// cos theta cos delta + sin theta sin delta cos beta (cos beta = 1 - 2 s^2) are linear
  /// in s^2: rho2 = r0 + r1 s^2, cosine = c0 + c1 s^2 (coefficients()).
  double integrand(double s, double r0, double r1, double c0, double c1) const {
    const double s2 = s * s;
    const double rho2 = std::clamp(r0 + r1 * s2, 0.0, 1.0);
    const double cosine = std::max(c0 + c1 * s2, 0.0);
    return limbDarkenedLuminanceAtSquare(rho2, limbDarkening) * cosine * 2.0 / std::sqrt(std::max(1.0 - s2, 1e-300));
  }
  void coefficients(double& r0, double& r1, double& c0, double& c1) const {
    r0 = A / K, r1 = B / K;
    c0 = cosTheta * cosDelta + sinTheta * sinDelta, c1 = -2.0 * sinTheta * sinDelta;
  }
  /// Integral of the integrand over s in [a, b] inside the chord (the substitution
  /// s = a + (b - a)(1 - cos t) / 2 smooths the square roots at the disc's edge), with
  /// N Gauss-Legendre points (12 for a whole chord, 4 for a pixel's part of it).
  template <int N>
  double integral(double a, double b) const {
    a = std::max(a, sBegin), b = std::min(b, sEnd);
    if (b <= a) return 0.0;
    const GaussLegendre<N>& g = gaussLegendre<N>();
    double r0, r1, c0, c1;
    coefficients(r0, r1, c0, c1);
    double sum = 0.0;
#pragma omp simd reduction(+ : sum)
    for (int i = 0; i < N; ++i) sum += g.w[i] * integrand(a + (b - a) * g.halfVersine[i], r0, r1, c0, c1) * g.sine[i];
    return sum * kPi * (b - a) * 0.5;
  }
};

/// What the rows of a limb position share: the Sun's direction and size.
struct SunSeen {
  double separationRad, cosDelta, sinDelta, K;  ///< K = sin^2(phi_sun / 2)
  explicit SunSeen(const LimbPosition& p)
      : separationRad(p.separationRad), cosDelta(std::cos(p.separationRad)), sinDelta(std::sin(p.separationRad)),
        K(sq(std::sin(0.5 * p.sunAngularRadiusRad))) {}
};

/// The row at polar angle theta (in [0, pi / 2], given by its sine) whose light leaves
/// the atmosphere at polar angle exitPolarRad.
SunRow sunRow(double exitPolarRad, const SunSeen& sun, double sinTheta, double limbDarkening) {
  SunRow row;
  row.A = sq(std::sin(0.5 * (exitPolarRad - sun.separationRad)));
  row.B = std::sin(exitPolarRad) * sun.sinDelta;
  row.K = sun.K;
  row.sinTheta = sinTheta, row.cosTheta = std::sqrt(std::max(0.0, (1.0 - sinTheta) * (1.0 + sinTheta)));
  row.cosDelta = sun.cosDelta, row.sinDelta = sun.sinDelta;
  row.limbDarkening = limbDarkening;
  // A + B s2 <= K for s2 = sin^2(beta / 2) in [0, 1].
  double lo = 0.0, hi = 1.0;
  const double slack = row.K - row.A;
  if (std::abs(row.B) <= 1e-300) {
    if (slack < 0.0) return row;
  } else if (row.B > 0.0) {
    hi = std::min(1.0, slack / row.B);
  } else {
    lo = std::max(0.0, slack / row.B);
  }
  if (hi < lo || hi < 0.0 || lo > 1.0) return row;
  row.sBegin = std::sqrt(std::clamp(lo, 0.0, 1.0)), row.sEnd = std::sqrt(std::clamp(hi, 0.0, 1.0));
  return row;
}

/// The rows of a view: gamma edges, polar angles, solid angle per unit beta.
struct RowGeometry {
  std::vector<double> edge, sinEdge, theta, sinTheta, solidAnglePerBeta;  ///< edge: rows + 1
};
RowGeometry rowGeometry(const LimbPosition& p, int rows) {
  RowGeometry g;
  g.edge.resize(rows + 1), g.sinEdge.resize(rows + 1), g.theta.resize(rows), g.sinTheta.resize(rows);
  g.solidAnglePerBeta.resize(rows);
  const double span = p.atmosphereAngularRadiusRad - p.occluderAngularRadiusRad;
  // The edges and centres are the angles o + k h, h = span / (2 rows), k = 0 .. 2 rows: their
  // sines by rotating (cos, sin) by h (rounding grows like k: ~1e-13 at 512), not by a sine
  // each. A row's solid angle per unit beta, cos(edge_i) - cos(edge_i+1), is 2 sin(theta_i)
  // sin(h) (no cancellation).
  const double h = 0.5 * span / rows, ch = std::cos(h), sh = std::sin(h);
  double c = std::cos(p.occluderAngularRadiusRad), s = std::sin(p.occluderAngularRadiusRad);
  for (int k = 0; k <= 2 * rows; ++k) {
    if (k % 2 == 0) {
      g.edge[k / 2] = p.occluderAngularRadiusRad + span * (k / 2) / rows;
      g.sinEdge[k / 2] = s;
    } else {
      g.theta[k / 2] = p.occluderAngularRadiusRad + span * (k / 2 + 0.5) / rows;
      g.sinTheta[k / 2] = s;
      g.solidAnglePerBeta[k / 2] = 2.0 * s * sh;
    }
    const double cNext = c * ch - s * sh;
    s = s * ch + c * sh, c = cNext;
  }
  return g;
}

/// The scattering cells of a view: scatteringColumns x scatteringRows, the sines and
/// cosines of their centres' polar angles theta (rows) and azimuths beta (columns).
struct ScatteringCells {
  std::vector<double> cosTheta, sinTheta, cosBeta, sinBeta;
  double cosDelta = 1.0, sinDelta = 0.0;  ///< the Sun's separation
  ScatteringCells(const LimbPosition& p, const std::vector<double>& theta, int columns)
      : cosDelta(std::cos(p.separationRad)), sinDelta(std::sin(p.separationRad)) {
    for (double t : theta) cosTheta.push_back(std::cos(t)), sinTheta.push_back(std::sin(t));
    for (int q = 0; q < columns; ++q) {
      const double beta = kPi * (q + 0.5) / columns;
      cosBeta.push_back(std::cos(beta)), sinBeta.push_back(std::sin(beta));
    }
  }
};

/// The in-scattered radiance of cell (column q, row r), per channel, and the cosine towards
/// the Sun of its centre.
void scatteredRadiance(const AtmosphericShadowModel& m, const atmosphere::SkyRadianceLookup& sky,
                       const LimbPosition& p, const ScatteringCells& cells, int r, int q, double* out, double& cosine) {
  const double d = p.occluderDistanceM, rTop = m.atmosphereRadiusM();
  const double st = cells.sinTheta[r], ct = cells.cosTheta[r];
  const double b = std::min(d * st, rTop);
  // Observer at (-d, 0, 0), occluder at the origin, Sun direction (cos delta, sin delta, 0),
  // view direction w = (cos theta, sin theta cos beta, sin theta sin beta).
  const glm::dvec3 w(ct, st * cells.cosBeta[q], st * cells.sinBeta[q]);
  const glm::dvec3 s(cells.cosDelta, cells.sinDelta, 0.0);
  const double t = d * ct - std::sqrt(std::max(0.0, rTop * rTop - b * b));
  const glm::dvec3 x(-d + t * w.x, t * w.y, t * w.z);
  const glm::dvec3 n = x / std::sqrt(x.x * x.x + x.y * x.y + x.z * x.z);
  const double mu = -std::sqrt(std::max(0.0, rTop * rTop - b * b)) / rTop;
  const double muS = n.x * s.x + n.y * s.y;
  const double nu = w.x * s.x + w.y * s.y;
  cosine = std::max(nu, 0.0);
  sky(rTop, mu, muS, nu, out);
}

/// The Sun seen along polar angle theta: its chord (empty when the ray sees no Sun) and, per
/// channel, transmittance x terrain / (the Sun's solid angle) in `weight`.
SunRow sunAlong(const AtmosphericShadowModel& m, const LimbPosition& p, const SunSeen& sun, double theta,
                double sinTheta, double* weight) {
  double dev = 0.0, contact = 0.0;
  m.rays.at(p.occluderDistanceM * sinTheta, dev, contact, weight);
  const double terrain = m.terrain.transmission(contact);
  if (terrain <= 0.0) return {};
  const double scale = terrain / (4.0 * kPi * sun.K);
  for (int c = 0; c < m.rays.channels; ++c) weight[c] *= scale;
  return sunRow(theta - dev, sun, sinTheta, m.limbDarkening);
}

/// At most this many sub-rows per row (forEachSunSubRow).
constexpr int kMaxSubRows = 1024;

/// The refracted Sun through row i, integrated over the row's extent in theta. Near the
/// periapsis of the bright band the deviation changes so fast with the impact parameter that
/// the exit direction sweeps across much of the Sun within one row: a point sample at the
/// row's centre then either hits or misses the Sun's image at a given beta. So the row is cut
/// into sub-rows across which the exit direction moves by at most 1 / subRowsPerSunDiameter
/// of the Sun's diameter (one where the deviation is slow; one, the row's centre, when
/// subRowsPerSunDiameter is 0); body(row, weight, fraction) is called for each sub-row that
/// sees the Sun, `fraction` its share of the row's solid angle, `weight` as sunAlong's.
template <class Body>
void forEachSunSubRow(const AtmosphericShadowModel& m, const LimbPosition& p, const RowGeometry& g, int i,
                      double subRowsPerSunDiameter, double* weight, const Body& body) {
  const double lo = g.edge[i], hi = g.edge[i + 1];
  int n = 1;
  if (subRowsPerSunDiameter > 0.0) {
    // The exit direction's polar angle e = theta - deviation lies in [lo - devMax, hi - devMin]
    // over the row; the Sun (polar angle delta) is seen at some beta iff ||e| - delta| <= phi_sun,
    // so rows whose range of |e| misses [delta - phi_sun, delta + phi_sun] see no Sun.
    double devMin = 0.0, devMax = 0.0;
    m.rays.deviationRange(p.occluderDistanceM * g.sinEdge[i], p.occluderDistanceM * g.sinEdge[i + 1], devMin, devMax);
    const double eLo = lo - devMax, eHi = hi - devMin;
    const double aMin = eLo <= 0.0 && eHi >= 0.0 ? 0.0 : std::min(std::abs(eLo), std::abs(eHi));
    const double aMax = std::max(std::abs(eLo), std::abs(eHi));
    const double margin = 1.001 * p.sunAngularRadiusRad;
    if (aMax < p.separationRad - margin || aMin > p.separationRad + margin) return;
    const double sweep = (eHi - eLo) / (2.0 * p.sunAngularRadiusRad);
    n = std::clamp(static_cast<int>(std::ceil(sweep * subRowsPerSunDiameter)), 1, kMaxSubRows);
  }
  const SunSeen sun(p);
  for (int k = 0; k < n; ++k) {
    const double a = lo + (hi - lo) * k / n, b = lo + (hi - lo) * (k + 1) / n;
    const double theta = n == 1 ? g.theta[i] : 0.5 * (a + b);
    const SunRow row = sunAlong(m, p, sun, theta, n == 1 ? g.sinTheta[i] : std::sin(theta), weight);
    if (row.empty()) continue;
    body(row, static_cast<const double*>(weight), n == 1 ? 1.0 : cosDifference(a, b) / g.solidAnglePerBeta[i]);
  }
}

void checkLimbParams(const LimbViewParams& p) {
  if (p.columns < 1 || p.rows < 1 || p.scatteringColumns < 1 || p.scatteringRows < 1)
    throw std::invalid_argument("limb view sizes must be at least 1");
}

bool useScattering(const AtmosphericShadowModel& m) {
  return m.scattering && m.tables != nullptr && m.atmosphere != nullptr;
}

/// Runs body(k) for `share`'s texels k of [0, all) over OpenMP threads (dynamic
/// schedule), reporting progress from the calling thread; false when the callback cancelled.
template <class Body>
bool forEachTexel(int all, const TexelShare& share, const Progress& progress, const Body& body) {
  if (share.count < 1 || share.index < 0 || share.index >= share.count)
    throw std::invalid_argument("texel share: index outside 0..count-1");
  std::atomic<bool> cancelled{false};
  std::atomic<int> done{0};
  ParallelErrors errors;
  const int total = share.texels(all);
#pragma omp parallel for schedule(dynamic, 1)
  for (int n = 0; n < total; ++n) {
    if (cancelled.load()) continue;
    errors.run([&] {
      body(share.texel(n));
      const int n = ++done;
      if (progress) {
#pragma omp critical(umbra_progress)
        if (!progress(static_cast<double>(n) / total)) cancelled = true;
      }
    });
  }
  errors.rethrow();
  return !cancelled;
}

} // namespace

double TerrainModel::transmission(double contactAltitudeM) const {
  if (meanElevationM <= 0.0) return contactAltitudeM >= 0.0 ? 1.0 : 0.0;
  return std::clamp(contactAltitudeM / (2.0 * meanElevationM), 0.0, 1.0);
}

namespace {
std::string lowerCase(std::string name) {
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return name;
}
} // namespace

TerrainModel defaultTerrain(const std::string& occluderName) {
  TerrainModel t;
  if (lowerCase(occluderName) == "earth") t.meanElevationM = 240.0;
  return t;
}

int defaultScatteringNu(const std::string& occluderName, int otherwise) {
  return lowerCase(occluderName) == "mars" ? 32 : otherwise;
}

void LimbRayProfile::at(double b, double& dev, double& contact, double* T) const {
  if (std::isnan(b)) throw std::domain_error("limb ray profile lookup at a non-finite impact parameter");
  const int n = samples();
  const double x = std::clamp((b - occluderRadiusM) / (atmosphereRadiusM - occluderRadiusM), 0.0, 1.0) * (n - 1);
  const int k0 = std::min(static_cast<int>(x), n - 2);
  const double f = x - k0;
  dev = (1 - f) * deviationRad[k0] + f * deviationRad[k0 + 1];
  contact = (1 - f) * contactAltitudeM[k0] + f * contactAltitudeM[k0 + 1];
  const double* t0 = transmittance.data() + static_cast<std::size_t>(k0) * channels;
  for (int c = 0; c < channels; ++c) T[c] = (1 - f) * t0[c] + f * t0[c + channels];
}

void LimbRayProfile::deviationRange(double bLo, double bHi, double& lo, double& hi) const {
  const int n = samples();
  const double scale = (n - 1) / (atmosphereRadiusM - occluderRadiusM);
  auto deviation = [&](double b) {
    if (std::isnan(b)) throw std::domain_error("limb ray profile lookup at a non-finite impact parameter");
    const double x = std::clamp((b - occluderRadiusM) * scale, 0.0, n - 1.0);
    const int k = std::min(static_cast<int>(x), n - 2);
    return deviationRad[k] + (x - k) * (deviationRad[k + 1] - deviationRad[k]);
  };
  lo = std::min(deviation(bLo), deviation(bHi)), hi = std::max(deviation(bLo), deviation(bHi));
  // The nodes strictly inside (the profile is linear between them): two runs cover them.
  const int k0 = std::max(0, static_cast<int>(std::floor((std::min(bLo, bHi) - occluderRadiusM) * scale)) + 1);
  const int k1 = std::min(n - 1, static_cast<int>(std::ceil((std::max(bLo, bHi) - occluderRadiusM) * scale)) - 1);
  if (k1 < k0) return;
  if (deviationRunMin.size() < static_cast<std::size_t>(n))
    throw std::logic_error("limb ray profile: its deviations are not indexed (indexDeviations)");
  const int j = 31 - __builtin_clz(static_cast<unsigned>(k1 - k0 + 1));
  const std::size_t a = static_cast<std::size_t>(j) * n + k0, b = static_cast<std::size_t>(j) * n + k1 - (1 << j) + 1;
  lo = std::min({lo, deviationRunMin[a], deviationRunMin[b]});
  hi = std::max({hi, deviationRunMax[a], deviationRunMax[b]});
}

void LimbRayProfile::indexDeviations() {
  const int n = samples();
  int levels = 1;
  while ((2 << (levels - 1)) <= n) ++levels;  // runs of 1, 2, 4, ... up to n nodes
  deviationRunMin.assign(static_cast<std::size_t>(levels) * n, 0.0);
  deviationRunMax.assign(static_cast<std::size_t>(levels) * n, 0.0);
  std::copy(deviationRad.begin(), deviationRad.end(), deviationRunMin.begin());
  std::copy(deviationRad.begin(), deviationRad.end(), deviationRunMax.begin());
  for (int j = 1; j < levels; ++j) {
    const std::size_t row = static_cast<std::size_t>(j) * n, below = row - n, half = std::size_t{1} << (j - 1);
    for (std::size_t k = 0; k + 2 * half <= static_cast<std::size_t>(n); ++k) {
      deviationRunMin[row + k] = std::min(deviationRunMin[below + k], deviationRunMin[below + k + half]);
      deviationRunMax[row + k] = std::max(deviationRunMax[below + k], deviationRunMax[below + k + half]);
    }
  }
}

void refractedTransmittanceToTop(const atmosphere::AtmosphereTables& tables, double r, double mu, double contact,
                                 double* T) {
  const int n = static_cast<int>(tables.wavelengthCount());
  if (mu >= 0.0) return atmosphere::transmittanceToTop(tables, r, mu, T);
  if (contact < 0.0) return std::fill(T, T + n, 0.0);
  // Symmetric about the periapsis: the way out from it, twice, less the part above r.
  atmosphere::transmittanceToTop(tables, std::min(tables.bottomRadiusM + contact, r), 0.0, T);
  std::vector<double> above(n);
  atmosphere::transmittanceToTop(tables, r, -mu, above.data());
  for (int c = 0; c < n; ++c) T[c] = std::min(T[c] * T[c] / std::max(above[c], 1e-30), 1.0);
}

void screenByClouds(LimbRayProfile& rays, double cloudTopM, double cover) {
  if (!(cloudTopM >= 0.0) || !(cover >= 0.0 && cover <= 1.0))
    throw std::invalid_argument("clouds: the top must be >= 0 m and the cover within 0..1");
  for (int k = 0; k < rays.samples(); ++k)
    if (rays.contactAltitudeM[k] < cloudTopM)
      for (int c = 0; c < rays.channels; ++c) rays.transmittance[static_cast<std::size_t>(k) * rays.channels + c] *= 1.0 - cover;
}

LimbRayProfile limbRayProfile(const atmosphere::AtmosphereTables& tables,
                              const atmosphere::RefractionTable* refraction, int samples) {
  if (samples < 2) throw std::invalid_argument("limb ray profile needs at least 2 samples");
  LimbRayProfile p;
  p.occluderRadiusM = tables.bottomRadiusM;
  p.atmosphereRadiusM = tables.topRadiusM;
  p.wavelengthsNm = tables.wavelengthsNm;
  p.channels = static_cast<int>(tables.wavelengthCount());
  p.deviationRad.resize(samples), p.contactAltitudeM.resize(samples);
  p.transmittance.resize(static_cast<std::size_t>(samples) * p.channels);
  const double rTop = tables.topRadiusM, rBottom = tables.bottomRadiusM;
  for (int k = 0; k < samples; ++k) {
    const double b = rBottom + (rTop - rBottom) * k / (samples - 1);
    double dev = 0.0, contact = b - rBottom;
    if (refraction) {
      // The ray enters at the top with sin(z) = b / r_top, heading down.
      const double mu = -std::sqrt(std::max(0.0, rTop * rTop - b * b)) / rTop;
      const atmosphere::RefractionSample s = refraction->sample(rTop, mu);
      dev = s.deviationRad, contact = s.contactAltitudeM;
    }
    p.deviationRad[k] = dev, p.contactAltitudeM[k] = contact;
    double* T = p.transmittance.data() + static_cast<std::size_t>(k) * p.channels;
    refractedTransmittanceToTop(tables, rTop, -std::sqrt(std::max(0.0, rTop * rTop - b * b)) / rTop, contact, T);
  }
  p.indexDeviations();
  return p;
}

LimbRayProfile transparentLimbProfile(double rOcc, double rAtmo, const std::vector<double>& wavelengthsNm) {
  LimbRayProfile p;
  p.occluderRadiusM = rOcc, p.atmosphereRadiusM = rAtmo;
  p.wavelengthsNm = wavelengthsNm;
  p.channels = static_cast<int>(wavelengthsNm.size());
  const int n = 2;
  p.deviationRad.assign(n, 0.0);
  p.contactAltitudeM = {0.0, rAtmo - rOcc};
  p.transmittance.assign(static_cast<std::size_t>(n) * p.channels, 1.0);
  p.indexDeviations();
  return p;
}

std::string AtmosphericShadowModel::validate() const {
  if (!(system.sunRadiusM > 0 && system.occluderRadiusM > 0 && system.sunOccluderDistanceM > 0))
    return "Sun radius, occluder radius and distance must be positive";
  if (rays.samples() < 2 || rays.channels < 1) return "limb ray profile is empty";
  if (!(rays.atmosphereRadiusM > rays.occluderRadiusM)) return "atmosphere top must be above the ground";
  if (std::abs(rays.occluderRadiusM - system.occluderRadiusM) > 1e-6 * system.occluderRadiusM)
    return "occluder radius differs from the atmosphere's bottom radius";
  if (system.sunOccluderDistanceM <= system.sunRadiusM + rays.atmosphereRadiusM)
    return "Sun and occluder overlap";
  if (scattering && tables && tables->wavelengthCount() != static_cast<std::size_t>(rays.channels))
    return "atmosphere tables and ray profile have different wavelengths";
  return {};
}

/// Completes a position: a point inside the atmosphere (u -> 0) is seen from just above
/// its top, at the same v.
LimbPosition finishPosition(const AtmosphericShadowModel& m, LimbPosition p) {
  const double rTop = m.atmosphereRadiusM();
  if (p.occluderDistanceM < rTop * (1.0 + 1e-9)) {
    const double v = p.separationRad / (p.occluderAngularRadiusRad + p.sunAngularRadiusRad);
    p.occluderDistanceM = rTop * (1.0 + 1e-9);
    p.occluderAngularRadiusRad = angularRadiusRad(m.system.occluderRadiusM, p.occluderDistanceM);
    p.separationRad = v * (p.occluderAngularRadiusRad + p.sunAngularRadiusRad);
  }
  p.atmosphereAngularRadiusRad = angularRadiusRad(rTop, p.occluderDistanceM);
  return p;
}

LimbPosition limbPosition(const AtmosphericShadowModel& m, const LutCoords& coords) {
  const InverseMapping inv = inverseLutCoords(coords, m.system);
  LimbPosition p;
  p.sunAngularRadiusRad = inv.angles.sunAngularRadiusRad;
  p.occluderAngularRadiusRad = inv.angles.occluderAngularRadiusRad;
  p.separationRad = inv.angles.separationRad;
  p.occluderDistanceM = inv.occluderDistanceM;
  return finishPosition(m, p);
}

LimbPosition limbPositionBehind(const AtmosphericShadowModel& m, double distanceBehindM, double offsetM) {
  const glm::dvec3 sun(-m.system.sunOccluderDistanceM, 0.0, 0.0), occ(0.0);
  const glm::dvec3 point(distanceBehindM, offsetM, 0.0);
  const ShadowAngles a = shadowAngles(point, sun, m.system.sunRadiusM, occ, m.system.occluderRadiusM);
  LimbPosition p;
  p.sunAngularRadiusRad = a.sunAngularRadiusRad;
  p.occluderAngularRadiusRad = a.occluderAngularRadiusRad;
  p.separationRad = a.separationRad;
  p.occluderDistanceM = std::hypot(distanceBehindM, offsetM);
  return finishPosition(m, p);
}

LutCoords lutCoordsOf(const LimbPosition& p) {
  return lutCoords(ShadowAngles{p.sunAngularRadiusRad, p.occluderAngularRadiusRad, p.separationRad});
}

ProfileSample atmosphericShadowAt(const AtmosphericShadowModel& m, double distanceBehindM, double offsetM,
                                  const LimbViewParams& limb) {
  ProfileSample s;
  s.offsetM = offsetM;
  const std::vector<double> t = illuminanceAt(m, limbPositionBehind(m, distanceBehindM, offsetM), limb).total();
  s.rgb = rgbOfSpectralRatio(m.rays.wavelengthsNm, t.data());
  s.luminance = colour::luminance(s.rgb);
  return s;
}

std::vector<ProfileSample> atmosphericShadowProfile(const AtmosphericShadowModel& m, double distanceBehindM,
                                                    double maxOffsetM, int samples, const ShadowLut* lut,
                                                    const LimbViewParams& limb) {
  if (samples < 2) throw std::invalid_argument("profile needs at least 2 samples");
  if (const std::string e = m.validate(); !e.empty()) throw std::invalid_argument("atmospheric shadow: " + e);
  std::vector<ProfileSample> out(samples);
  ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 1)
  for (int k = 0; k < samples; ++k) errors.run([&] {
    const double offsetM = maxOffsetM * k / (samples - 1);
    if (!lut) {  // directly: also past v = 1, where the atmosphere still dims the Sun
      out[k] = atmosphericShadowAt(m, distanceBehindM, offsetM, limb);
      return;
    }
    ProfileSample& s = out[k];
    s.offsetM = offsetM;
    const LutCoords c = lutCoordsOf(limbPositionBehind(m, distanceBehindM, offsetM));
    // The LuT ends at v = 1 (the solid body's penumbra), as the renderer reads it.
    s.rgb = c.v >= 1.0 ? glm::dvec3(1.0) : lut->sample(c);
    s.luminance = colour::luminance(s.rgb);
  });
  errors.rethrow();
  return out;
}

std::vector<double> Illuminance::total() const {
  std::vector<double> t = indirect;
  for (double& x : t) x += direct;
  return t;
}

namespace {

/// The sky lookups of a model's views, prepared once for all of them; none without scattering.
std::unique_ptr<const atmosphere::SkyRadianceLookup> skyLookup(const AtmosphericShadowModel& m) {
  if (!useScattering(m)) return nullptr;
  return std::make_unique<const atmosphere::SkyRadianceLookup>(*m.tables, *m.atmosphere);
}

/// renderLimbView with the model's sky lookups (skyLookup).
LimbView limbView(const AtmosphericShadowModel& m, const atmosphere::SkyRadianceLookup* sky, const LimbPosition& p,
                  const LimbViewParams& params) {
  checkLimbParams(params);
  const int nc = m.rays.channels, R = params.rows, C = params.columns;
  LimbView view;
  view.columns = C, view.rows = R, view.channels = nc;
  view.radiance.assign(static_cast<std::size_t>(R) * C * nc, 0.0);
  view.solidAngleSr.resize(R);
  const RowGeometry g = rowGeometry(p, R);
  const double dBeta = kPi / C;
  // Per column: s = sin(beta / 2) at its left edge (C + 1 of them) and cos beta at its centre.
  std::vector<double> sEdge(C + 1), cosCentre(C);
  for (int j = 0; j <= C; ++j) sEdge[j] = std::sin(0.5 * j * dBeta);
  for (int j = 0; j < C; ++j) cosCentre[j] = std::cos((j + 0.5) * dBeta);
  std::vector<double> T(nc);
  for (int i = 0; i < R; ++i) {
    view.solidAngleSr[i] = g.solidAnglePerBeta[i] * dBeta;
    if (!m.refractedSun) continue;
    const double sub = params.subRowsPerSunDiameter;
    forEachSunSubRow(m, p, g, i, sub, T.data(), [&](const SunRow& row, const double* w, double fraction) {
      const int j0 = std::max(0, static_cast<int>(row.betaBegin() / dBeta));
      const int j1 = std::min(C - 1, static_cast<int>(row.betaEnd() / dBeta));
      for (int j = j0; j <= j1; ++j) {
        // The mean over the pixel's beta range; the cosine is divided back out (radiance).
        const double mean = row.integral<4>(sEdge[j], sEdge[j + 1]) / dBeta;
        const double cosine = row.cosTheta * row.cosDelta + row.sinTheta * row.sinDelta * cosCentre[j];
        const double L = fraction * mean / std::max(cosine, 1e-12);
        for (int c = 0; c < nc; ++c) view.at(i, j, c) += L * w[c];
      }
    });
  }
  if (sky) {
    const int SC = params.scatteringColumns, SR = params.scatteringRows;
    const ScatteringCells cells(p, rowGeometry(p, SR).theta, SC);
    std::vector<double> L(nc);
    for (int r = 0; r < SR; ++r)
      for (int q = 0; q < SC; ++q) {
        double cosine = 0.0;
        scatteredRadiance(m, *sky, p, cells, r, q, L.data(), cosine);
        for (int i = r * R / SR; i < (r + 1) * R / SR; ++i)
          for (int j = q * C / SC; j < (q + 1) * C / SC; ++j)
            for (int c = 0; c < nc; ++c) view.at(i, j, c) += L[c];
      }
  }
  return view;
}

/// illuminanceAt with the model's sky lookups (skyLookup).
Illuminance illuminance(const AtmosphericShadowModel& m, const atmosphere::SkyRadianceLookup* sky, const LimbPosition& p,
                        const LimbViewParams& params) {
  checkLimbParams(params);
  const int nc = m.rays.channels;
  Illuminance I;
  I.indirect.assign(nc, 0.0);
  std::vector<double> T(nc);
  if (m.refractedSun) {
    const RowGeometry g = rowGeometry(p, params.rows);
    const double sub = params.subRowsPerSunDiameter;
    for (int i = 0; i < params.rows; ++i)
      forEachSunSubRow(m, p, g, i, sub, T.data(), [&](const SunRow& row, const double* w, double fraction) {
        const double e = 2.0 * g.solidAnglePerBeta[i] * fraction * row.integral<12>(row.sBegin, row.sEnd);
        for (int c = 0; c < nc; ++c) I.indirect[c] += e * w[c];
      });
  }
  if (sky) {
    const int SC = params.scatteringColumns, SR = params.scatteringRows;
    const RowGeometry g = rowGeometry(p, SR);
    const ScatteringCells cells(p, g.theta, SC);
    std::vector<double> L(nc);
    for (int r = 0; r < SR; ++r)
      for (int q = 0; q < SC; ++q) {
        double cosine = 0.0;
        scatteredRadiance(m, *sky, p, cells, r, q, L.data(), cosine);
        const double w = 2.0 * g.solidAnglePerBeta[r] * (kPi / SC) * cosine;
        for (int c = 0; c < nc; ++c) I.indirect[c] += w * L[c];
      }
  }
  const double delta = p.separationRad, phiS = p.sunAngularRadiusRad;
  I.direct = delta >= p.atmosphereAngularRadiusRad + phiS
                 ? 1.0
                 : visibleFractionLimbDarkened(p.atmosphereAngularRadiusRad / phiS, delta / phiS, m.limbDarkening)
                       .value;
  return I;
}

} // namespace

LimbView renderLimbView(const AtmosphericShadowModel& m, const LimbPosition& p, const LimbViewParams& params) {
  return limbView(m, skyLookup(m).get(), p, params);
}

Illuminance illuminanceAt(const AtmosphericShadowModel& m, const LimbPosition& p, const LimbViewParams& params) {
  return illuminance(m, skyLookup(m).get(), p, params);
}

glm::dvec3 rgbOfSpectralRatio(const std::vector<double>& nm, const double* ratio) {
  const int n = static_cast<int>(nm.size());
  auto at = [&](double lambda) {
    if (n == 1) return ratio[0];
    // Nearest bracketing pair in the set's own order (ascending, or R, G, B).
    int best = -1;
    double bestSpan = 1e300;
    for (int a = 0; a < n; ++a) {
      if (nm[a] == lambda) return ratio[a];
      for (int b = 0; b < n; ++b)
        if (nm[a] < lambda && lambda < nm[b] && nm[b] - nm[a] < bestSpan) best = a * n + b, bestSpan = nm[b] - nm[a];
    }
    if (best < 0) {  // outside the set: the nearest sample
      int k = 0;
      for (int a = 1; a < n; ++a)
        if (std::abs(nm[a] - lambda) < std::abs(nm[k] - lambda)) k = a;
      return ratio[k];
    }
    const int a = best / n, b = best % n;
    const double f = (lambda - nm[a]) / (nm[b] - nm[a]);
    return (1 - f) * ratio[a] + f * ratio[b];
  };
  return {at(680.0), at(550.0), at(440.0)};
}

ShadowLut buildAtmosphericShadowLut(const AtmosphericShadowModel& m, const AtmosphericShadowLutParams& params,
                                    const LutExtent& requested, const Progress& progress, const TexelShare& share) {
  if (const std::string e = m.validate(); !e.empty()) throw std::invalid_argument("atmospheric shadow: " + e);
  if (params.width < 2 || params.height < 2) throw std::invalid_argument("shadow LuT size must be at least 2x2");
  checkLimbParams(params.limb);
  LutExtent ext = requested.empty() ? LutExtent{0, params.width, 0, params.height} : requested;
  if (ext.uBegin < 0 || ext.vBegin < 0 || ext.uEnd > params.width || ext.vEnd > params.height)
    throw std::invalid_argument("shadow LuT extent outside the table");
  checkLutRange(params.uMin, params.uMax, params.vMin, params.vMax, params.vLowFraction);
  if (params.vLowFraction > 0.0 && (ext.vBegin != 0 || ext.vEnd != params.height))
    throw std::invalid_argument("a shadow LuT with a split v axis is computed over its whole v extent");
  ShadowLut whole;  // the whole table's u of each column, v of each row
  whole.width = params.width, whole.height = params.height;
  whole.uMin = params.uMin, whole.uMax = params.uMax, whole.vMin = params.vMin, whole.vMax = params.vMax;
  whole.vLowFraction = params.vLowFraction;
  ShadowLut lut;
  lut.width = ext.uEnd - ext.uBegin;
  lut.height = ext.vEnd - ext.vBegin;
  const double span = params.uMax - params.uMin;
  lut.uMin = ext.uBegin == 0 ? params.uMin : params.uMin + span * ext.uBegin / params.width;
  lut.uMax = ext.uEnd == params.width ? params.uMax : params.uMin + span * ext.uEnd / params.width;
  const double vSpan = params.vMax - params.vMin;
  lut.vMin = ext.vBegin == 0 ? params.vMin : params.vMin + vSpan * ext.vBegin / params.height;
  lut.vMax = ext.vEnd == params.height ? params.vMax : params.vMin + vSpan * ext.vEnd / params.height;
  lut.vLowFraction = params.vLowFraction;
  lut.rgb.assign(static_cast<std::size_t>(lut.width) * lut.height * 3, 0.0f);
  const auto sky = skyLookup(m);  // one for every texel
  const bool finished = forEachTexel(lut.width * lut.height, share, progress, [&](int k) {
    const int i = k % lut.width, j = k / lut.width;
    const LutCoords c{whole.texelU(ext.uBegin + i), whole.texelV(ext.vBegin + j)};
    const std::vector<double> t = illuminance(m, sky.get(), limbPosition(m, c), params.limb).total();
    const glm::dvec3 rgb = rgbOfSpectralRatio(m.rays.wavelengthsNm, t.data());
    float* out = lut.rgb.data() + 3 * static_cast<std::size_t>(k);
    for (int q = 0; q < 3; ++q) out[q] = static_cast<float>(rgb[q]);
  });
  if (!finished) return {};
  return lut;
}

std::vector<double> layerAverages(const LimbView& view, int layers) {
  const int nc = view.channels, C = view.columns;
  std::vector<double> out(static_cast<std::size_t>(layers) * C * nc, 0.0);
  for (int layer = 0; layer < layers; ++layer) {
    const int r0 = layer * view.rows / layers, r1 = (layer + 1) * view.rows / layers;
    double omega = 0.0;
    for (int r = r0; r < r1; ++r) omega += view.solidAngleSr[r];
    for (int col = 0; col < C; ++col) {
      double* sum = out.data() + (static_cast<std::size_t>(layer) * C + col) * nc;
      for (int r = r0; r < r1; ++r)
        for (int q = 0; q < nc; ++q) sum[q] += view.at(r, col, q) * view.solidAngleSr[r];
      for (int q = 0; q < nc; ++q) sum[q] /= omega > 0.0 ? omega : 1.0;
    }
  }
  return out;
}

glm::dvec3 LimbLuminanceLut::texel(int i, int j, int k) const {
  const std::size_t o = ((static_cast<std::size_t>(k) * height + j) * width + i) * 3;
  return {rgb[o], rgb[o + 1], rgb[o + 2]};
}

LimbLuminanceLut buildLimbLuminanceLut(const AtmosphericShadowModel& m, const LimbLuminanceLutParams& params,
                                       const Progress& progress, const TexelShare& share) {
  if (const std::string e = m.validate(); !e.empty()) throw std::invalid_argument("limb luminance: " + e);
  if (params.width < 2 || params.height < 2 || params.columns < 1 || params.layers < 1 ||
      params.layers > params.limb.rows)
    throw std::invalid_argument("limb luminance LuT: sizes must be >= 2x2, columns >= 1, 1 <= layers <= limb rows");
  LimbViewParams lp = params.limb;
  lp.columns = params.columns;
  checkLimbParams(lp);
  LimbLuminanceLut lut;
  const LutRange& r = params.range;
  checkLutRange(r.uMin, r.uMax, r.vMin, r.vMax, r.vLowFraction);
  lut.width = params.width, lut.height = params.height, lut.columns = params.columns, lut.layers = params.layers;
  lut.range = r;
  lut.rgb.assign(static_cast<std::size_t>(lut.width) * lut.height * lut.depth() * 3, 0.0f);
  const auto sky = skyLookup(m);  // one for every texel
  const bool finished = forEachTexel(lut.width * lut.height, share, progress, [&](int k) {
    const int i = k % lut.width, j = k / lut.width;
    const LutCoords c{r.texelU(i, lut.width), r.texelV(j, lut.height)};
    const LimbView view = limbView(m, sky.get(), limbPosition(m, c), lp);
    const std::vector<double> avg = layerAverages(view, lut.layers);
    for (int d = 0; d < lut.depth(); ++d) {
      const double* spectral = avg.data() + static_cast<std::size_t>(d) * view.channels;
      const glm::dvec3 rgb = rgbOfSpectralRatio(m.rays.wavelengthsNm, spectral);
      const std::size_t o = ((static_cast<std::size_t>(d) * lut.height + j) * lut.width + i) * 3;
      for (int q = 0; q < 3; ++q) lut.rgb[o + q] = static_cast<float>(rgb[q]);
    }
  });
  if (!finished) return {};
  return lut;
}

} // namespace umbra::eclipse
