#include "EclipsedSky.hpp"

#include "ParallelErrors.hpp"
#include "Quadrature.hpp"
#include "TextureCoords.hpp"

#include <glm/geometric.hpp>

#include <omp.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace umbra::atmosphere {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr std::size_t kMaxSkyWavelengths = 64;
constexpr std::size_t kMaxComponents = 32;
using Spectrum = std::array<double, kMaxSkyWavelengths>;
using Densities = std::array<double, kMaxComponents>;

/// A phase function tabulated in x = sin(theta / 2) = sqrt((1 - cos theta) / 2), uniform,
/// linear between samples: x follows theta near the forward peak (0.056 deg a cell there).
class PhaseTable {
public:
  static constexpr int kCells = 2048;
  explicit PhaseTable(const PhaseFunction& p) : values_(kCells + 1) {
    for (int i = 0; i <= kCells; ++i) {
      const double x = static_cast<double>(i) / kCells;
      values_[static_cast<std::size_t>(i)] = p(1.0 - 2.0 * x * x);
    }
  }
  double operator()(double cosTheta) const {
    const double f = std::sqrt(std::clamp(0.5 * (1.0 - cosTheta), 0.0, 1.0)) * kCells;
    const int i = std::min(static_cast<int>(f), kCells - 1);
    const double t = f - i;
    return values_[static_cast<std::size_t>(i)] * (1.0 - t) + values_[static_cast<std::size_t>(i) + 1] * t;
  }

private:
  std::vector<double> values_;
};

/// The atmosphere's optics, flattened: [component * wavelengths + wavelength].
struct Optics {
  std::size_t nc = 0, nw = 0;
  std::vector<double> extinction, scattering, albedo;
  std::vector<PhaseTable> phases;
  const Atmosphere* atm = nullptr;

  explicit Optics(const Atmosphere& a) : nc(a.components.size()), nw(a.wavelengthsNm.size()), atm(&a) {
    for (const Component& c : a.components)
      for (std::size_t w = 0; w < nw; ++w) {
        extinction.push_back(c.extinctionPerM(w));
        scattering.push_back(c.scatteringPerM[w]);
        phases.emplace_back(c.phase(w));
      }
    for (std::size_t w = 0; w < nw; ++w) albedo.push_back(w < a.groundAlbedo.size() ? a.groundAlbedo[w] : 0.0);
  }
  void densities(double altitudeM, Densities& d) const {
    const double h = std::max(0.0, altitudeM);
    for (std::size_t c = 0; c < nc; ++c) d[c] = atm->components[c].density.at(h);
  }
};

/// A point's horizontal frame: `up` the local vertical, e1 the fixed reference direction
/// laid into the point's horizontal plane, e2 = up x e1 (continuous over the observer's
/// surroundings, so neighbouring points' directions of the same index are close).
struct Frame {
  glm::dvec3 up, e1, e2;
};
Frame frameAt(const glm::dvec3& p, const glm::dvec3& reference) {
  Frame f;
  f.up = glm::normalize(p);
  f.e1 = glm::normalize(reference - glm::dot(reference, f.up) * f.up);
  f.e2 = glm::cross(f.up, f.e1);
  return f;
}

/// The incoming directions: Gauss-Legendre in mu on [0, 1] and mirrored on [-1, 0], uniform
/// in azimuth; weights sum to 4 pi.
struct Directions {
  std::vector<double> mu, sinTheta, cosPhi, sinPhi, weight;
  Directions(int zenith, int azimuths) {
    const GaussLegendreRule rule(zenith / 2);
    std::vector<double> m, w;
    for (std::size_t i = 0; i < rule.x.size(); ++i) {
      m.push_back(0.5 * (1.0 + rule.x[i]));
      w.push_back(0.5 * rule.w[i]);
      m.push_back(-0.5 * (1.0 + rule.x[i]));
      w.push_back(0.5 * rule.w[i]);
    }
    for (std::size_t i = 0; i < m.size(); ++i)
      for (int j = 0; j < azimuths; ++j) {
        const double phi = 2.0 * kPi * (j + 0.5) / azimuths;
        mu.push_back(m[i]);
        sinTheta.push_back(std::sqrt(std::max(0.0, 1.0 - m[i] * m[i])));
        cosPhi.push_back(std::cos(phi));
        sinPhi.push_back(std::sin(phi));
        weight.push_back(w[i] * 2.0 * kPi / azimuths);
      }
  }
  std::size_t size() const { return mu.size(); }
  glm::dvec3 at(std::size_t k, const Frame& f) const {
    return mu[k] * f.up + sinTheta[k] * (cosPhi[k] * f.e1 + sinPhi[k] * f.e2);
  }
};

/// The light field's places: a fan of rays from the observer, elevation 90 deg sign(t) t^2
/// for t uniform in [-1, 1] (dense at the horizon) times uniform azimuths, each to the top or
/// the ground, with `samples` points at s = L ((k + 1/2) / samples)^2; and the observer's
/// own place, the last point, which stands for every point of a ray shorter than
/// kCollapseM (those that meet the ground at the feet of an observer on it).
class Fan {
public:
  struct Cell {
    std::array<std::size_t, 8> points{};
    std::array<double, 8> weights{};
  };

  static constexpr double kCollapseM = 1000.0;

  Fan(const glm::dvec3& observer, const Frame& frame, int elevations, int azimuths, int samples, double rb, double rt)
      : observer_(observer), frame_(frame), ne_(elevations), na_(azimuths), ns_(samples) {
    for (int i = 0; i < ne_; ++i)
      for (int j = 0; j < na_; ++j) {
        const double t = -1.0 + 2.0 * i / (ne_ - 1);
        const double e = 0.5 * kPi * (t < 0.0 ? -t * t : t * t), a = 2.0 * kPi * j / na_;
        const glm::dvec3 d = std::cos(e) * (std::cos(a) * frame.e1 + std::sin(a) * frame.e2) + std::sin(e) * frame.up;
        const double r = std::clamp(glm::length(observer), rb, rt), mu = glm::dot(d, frame.up);
        directions_.push_back(d);
        ground_.push_back(rayIntersectsGround(rb, r, mu));
        lengths_.push_back(ground_.back() ? distanceToBottomBoundaryM(rb, r, mu) : distanceToTopBoundaryM(rt, r, mu));
      }
  }
  std::size_t rays() const { return directions_.size(); }
  std::size_t size() const { return rays() * static_cast<std::size_t>(ns_) + 1; }
  std::size_t observerPoint() const { return size() - 1; }
  /// Whether point p stands for itself (not a point of a collapsed ray).
  bool computed(std::size_t p) const {
    return p == observerPoint() || lengths_[p / static_cast<std::size_t>(ns_)] >= kCollapseM;
  }
  /// Point p = ray * samples + k; the last: the observer.
  glm::dvec3 point(std::size_t p) const {
    if (p == observerPoint()) return observer_;
    const std::size_t ray = p / static_cast<std::size_t>(ns_);
    const double u = (static_cast<double>(p % static_cast<std::size_t>(ns_)) + 0.5) / ns_;
    return observer_ + lengths_[ray] * u * u * directions_[ray];
  }

  /// The 8 points around y and their weights: the direction cell of y seen from the
  /// observer, and along each of its 4 rays the two points around y's distance. A ray that
  /// ends on the ground short of y's distance does not count (air seen just above the
  /// horizon is not the air under the observer's feet), unless no ray of the cell reaches.
  Cell locate(const glm::dvec3& y) const {
    const glm::dvec3 v = y - observer_;
    const double s = glm::length(v);
    const glm::dvec3 d = s > 1e-3 ? v / s : frame_.up;
    const double e = std::asin(std::clamp(glm::dot(d, frame_.up), -1.0, 1.0));
    const double t = (e < 0.0 ? -1.0 : 1.0) * std::sqrt(std::abs(e) / (0.5 * kPi));
    const double fi = 0.5 * (t + 1.0) * (ne_ - 1);
    const int i0 = std::clamp(static_cast<int>(std::floor(fi)), 0, ne_ - 2);
    const double fe = std::clamp(fi - i0, 0.0, 1.0);
    double a = std::atan2(glm::dot(d, frame_.e2), glm::dot(d, frame_.e1));
    if (a < 0.0) a += 2.0 * kPi;
    const double fa = a / (2.0 * kPi) * na_;
    const int j0 = std::min(static_cast<int>(std::floor(fa)), na_ - 1), j1 = (j0 + 1) % na_;
    const double ga = std::clamp(fa - j0, 0.0, 1.0);
    const std::size_t rays[4] = {static_cast<std::size_t>(i0) * na_ + j0, static_cast<std::size_t>(i0) * na_ + j1,
                                 static_cast<std::size_t>(i0 + 1) * na_ + j0, static_cast<std::size_t>(i0 + 1) * na_ + j1};
    double rayWeights[4] = {(1 - fe) * (1 - ga), (1 - fe) * ga, fe * (1 - ga), fe * ga};
    double kept = 0.0;
    for (int c = 0; c < 4; ++c)
      if (!(ground_[rays[c]] && s > lengths_[rays[c]])) kept += rayWeights[c];
    if (kept > 0.0)
      for (int c = 0; c < 4; ++c)
        rayWeights[c] = ground_[rays[c]] && s > lengths_[rays[c]] ? 0.0 : rayWeights[c] / kept;
    Cell cell;
    for (int c = 0; c < 4; ++c) {
      const double L = lengths_[rays[c]];
      const double u = L > 0.0 ? std::sqrt(std::min(1.0, s / L)) : 0.0;
      const double fk = std::clamp(u * ns_ - 0.5, 0.0, static_cast<double>(ns_ - 1));
      const int k0 = std::min(static_cast<int>(fk), ns_ - 2);
      const double gk = fk - k0;
      if (L < kCollapseM) {
        cell.points[2 * c] = cell.points[2 * c + 1] = observerPoint();
      } else {
        cell.points[2 * c] = rays[c] * static_cast<std::size_t>(ns_) + static_cast<std::size_t>(k0);
        cell.points[2 * c + 1] = cell.points[2 * c] + 1;
      }
      cell.weights[2 * c] = rayWeights[c] * (1.0 - gk);
      cell.weights[2 * c + 1] = rayWeights[c] * gk;
    }
    return cell;
  }

private:
  glm::dvec3 observer_;
  Frame frame_;
  int ne_, na_, ns_;
  std::vector<glm::dvec3> directions_;
  std::vector<double> lengths_;
  std::vector<bool> ground_;
};

/// Marching along rays through the shell: transmittance by the midpoint rule in steps
/// s = L (j / steps)^2, the Sun's light from the tables' transmittance and the caller's V.
class Integrator {
public:
  Integrator(const AtmosphereTables& tables, const Atmosphere& atm, const glm::dvec3& sun, const SunVisibility& visibility)
      : tables_(tables), optics_(atm), sun_(sun), visibility_(visibility), rb_(atm.bottomRadiusM), rt_(atm.topRadiusM) {}

  const Optics& optics() const { return optics_; }

  /// The radiance arriving at x from direction d (the light travelling along -d):
  /// the integral of T(x, y) source(y) ds plus T(x, g) ground(g) where the ray ends on the
  /// ground g. `source(y, densities, S)` fills the scattering source [W m^-3 sr^-1 per unit
  /// irradiance] at y, `ground(g, R)` the ground's radiance.
  template <class Source, class Ground>
  void march(const glm::dvec3& x, const glm::dvec3& d, int steps, Source&& source, Ground&& ground, Spectrum& L) const {
    const std::size_t nw = optics_.nw, nc = optics_.nc;
    const double r = std::clamp(glm::length(x), rb_, rt_), mu = std::clamp(glm::dot(x, d) / glm::length(x), -1.0, 1.0);
    const bool endsOnGround = rayIntersectsGround(rb_, r, mu);
    const double length = endsOnGround ? distanceToBottomBoundaryM(rb_, r, mu) : distanceToTopBoundaryM(rt_, r, mu);
    Spectrum tau{}, S{};
    Densities dens{};
    std::fill(L.begin(), L.begin() + static_cast<std::ptrdiff_t>(nw), 0.0);
    for (int j = 0; j < steps; ++j) {
      const double a = static_cast<double>(j) / steps, b = static_cast<double>(j + 1) / steps;
      const double ds = length * (b * b - a * a), s = 0.5 * length * (a * a + b * b);
      const glm::dvec3 y = x + s * d;
      optics_.densities(glm::length(y) - rb_, dens);
      source(y, dens, S);
      for (std::size_t w = 0; w < nw; ++w) {
        double sigmaT = 0.0;
        for (std::size_t c = 0; c < nc; ++c) sigmaT += dens[c] * optics_.extinction[c * nw + w];
        L[w] += std::exp(-(tau[w] + 0.5 * sigmaT * ds)) * S[w] * ds;
        tau[w] += sigmaT * ds;
      }
    }
    if (endsOnGround) {
      glm::dvec3 g = x + length * d;
      g *= rb_ / glm::length(g);
      ground(g, S);
      for (std::size_t w = 0; w < nw; ++w) L[w] += std::exp(-tau[w]) * S[w];
    }
  }

  /// Single scattering's source at y for light leaving along -d: sum_c sigma_c p_c(nu)
  /// times the Sun's light there.
  void singleSource(const glm::dvec3& y, const glm::dvec3& d, const Densities& dens, Spectrum& S) const {
    const std::size_t nw = optics_.nw;
    Spectrum T{};
    const double V = sunAt(y, T);
    const double nu = glm::dot(d, sun_);
    for (std::size_t w = 0; w < nw; ++w) {
      double src = 0.0;
      if (V > 0.0)
        for (std::size_t c = 0; c < optics_.nc; ++c) {
          const double sc = optics_.scattering[c * nw + w];
          if (sc > 0.0) src += dens[c] * sc * optics_.phases[c * nw + w](nu);
        }
      S[w] = src * V * T[w];
    }
  }

  /// The ground's radiance from the Sun alone at g (Lambertian, the Sun's centre's cosine).
  void directGround(const glm::dvec3& g, Spectrum& R) const {
    Spectrum T{};
    const double V = sunAt(g, T);
    const double muS = std::max(0.0, glm::dot(g, sun_) / glm::length(g));
    for (std::size_t w = 0; w < optics_.nw; ++w) R[w] = optics_.albedo[w] / kPi * muS * V * T[w];
  }

  /// The Sun's transmittance to y per wavelength into T, and V(y) (0 with T where the
  /// ground hides the Sun's centre).
  double sunAt(const glm::dvec3& y, Spectrum& T) const {
    const double ry = glm::length(y), r = std::clamp(ry, rb_, rt_);
    const double muS = std::clamp(glm::dot(y, sun_) / ry, -1.0, 1.0);
    if (rayIntersectsGround(rb_, r, muS)) {
      std::fill(T.begin(), T.begin() + static_cast<std::ptrdiff_t>(optics_.nw), 0.0);
      return 0.0;
    }
    const double V = visibility_ ? visibility_(y) : 1.0;
    if (V > 0.0)
      transmittanceToTop(tables_, r, muS, T.data());
    else
      std::fill(T.begin(), T.begin() + static_cast<std::ptrdiff_t>(optics_.nw), 0.0);
    return V;
  }

private:
  const AtmosphereTables& tables_;
  Optics optics_;
  glm::dvec3 sun_;
  const SunVisibility& visibility_;
  double rb_, rt_;
};

/// A row of phase weights w_q p(omega_q . omega) scaled to sum to 1, the phase function's
/// integral: a forward peak narrower than a direction's cell would otherwise put more than
/// all the scattered light into the directions next to the incoming one.
void normalise(double* row, std::size_t n) {
  double sum = 0.0;
  for (std::size_t q = 0; q < n; ++q) sum += row[q];
  if (sum > 0.0)
    for (std::size_t q = 0; q < n; ++q) row[q] /= sum;
}

/// The field's interpolation at a cell: sum of weights times the points' values, n values
/// a point from `values` (n per point).
template <class Value>
void interpolate(const Fan::Cell& cell, const std::vector<Value>& values, std::size_t n, double* out) {
  std::fill(out, out + n, 0.0);
  for (int c = 0; c < 8; ++c) {
    const double wgt = cell.weights[static_cast<std::size_t>(c)];
    if (wgt == 0.0) continue;
    const Value* in = &values[cell.points[static_cast<std::size_t>(c)] * n];
    for (std::size_t i = 0; i < n; ++i) out[i] += wgt * in[i];
  }
}

}  // namespace

std::string EclipsedSkyOptions::validate() const {
  const auto range = [](const char* name, int v, int lo, int hi) -> std::string {
    if (v < lo || v > hi)
      return std::string(name) + ": expected " + std::to_string(lo) + " to " + std::to_string(hi) + ", got " + std::to_string(v);
    return {};
  };
  for (const std::string& p :
       {range("viewSamples", viewSamples, 2, 4096), range("fieldElevations", fieldElevations, 3, 257),
        range("fieldAzimuths", fieldAzimuths, 1, 512), range("fieldSamples", fieldSamples, 2, 1024),
        range("incomingZenith", incomingZenith, 2, 256), range("incomingAzimuths", incomingAzimuths, 1, 512),
        range("incomingSamples", incomingSamples, 2, 4096), range("orders", orders, 1, 64),
        range("diffuseZenith", diffuseZenith, 2, 256), range("diffuseAzimuths", diffuseAzimuths, 1, 512),
        range("threads", threads, 0, 4096)})
    if (!p.empty()) return p;
  if (fieldElevations % 2 == 0)
    return "fieldElevations: expected an odd number (the horizon one of them), got " + std::to_string(fieldElevations);
  if (incomingZenith % 2 != 0 || diffuseZenith % 2 != 0)
    return "incomingZenith, diffuseZenith: expected even numbers (half on each side of the horizon)";
  return {};
}

EclipsedSkyOptions draftEclipsedSkyOptions() {
  EclipsedSkyOptions o;
  o.fieldElevations = 13, o.fieldAzimuths = 8, o.fieldSamples = 12;
  o.incomingZenith = 8, o.incomingAzimuths = 8, o.incomingSamples = 16;
  o.orders = 3, o.diffuseZenith = 6, o.diffuseAzimuths = 6, o.viewSamples = 32;
  return o;
}

EclipsedSky eclipsedSkyRadiance(const AtmosphereTables& tables, const Atmosphere& atmosphere,
                                const glm::dvec3& observerM, const std::vector<glm::dvec3>& viewDirections,
                                const glm::dvec3& sunDirection, const SunVisibility& visibility,
                                const EclipsedSkyOptions& options, const EclipsedSkyProgress& progress) {
  if (const std::string problem = options.validate(); !problem.empty())
    throw std::invalid_argument("eclipsed sky: " + problem);
  const std::size_t nw = atmosphere.wavelengthsNm.size();
  if (nw > kMaxSkyWavelengths) throw std::invalid_argument("eclipsed sky: at most 64 wavelengths, got " + std::to_string(nw));
  if (atmosphere.components.size() > kMaxComponents)
    throw std::invalid_argument("eclipsed sky: at most 32 components, got " + std::to_string(atmosphere.components.size()));
  if (tables.wavelengthsNm != atmosphere.wavelengthsNm || tables.bottomRadiusM != atmosphere.bottomRadiusM ||
      tables.topRadiusM != atmosphere.topRadiusM)
    throw std::invalid_argument("eclipsed sky: the tables are not the atmosphere's (radii or wavelengths differ)");
  const glm::dvec3 observer = checkedSkyObserver("eclipsed sky", atmosphere, observerM, viewDirections, sunDirection);

  const auto start = std::chrono::steady_clock::now();
  const Integrator integrator(tables, atmosphere, sunDirection, visibility);
  const Optics& optics = integrator.optics();
  const std::size_t nc = optics.nc;

  // The observer's frame: e1 towards the Sun's azimuth (any horizontal direction under an
  // overhead Sun); every point's frame lays the same e1 into its own horizontal.
  const glm::dvec3 up0 = glm::normalize(observer);
  glm::dvec3 reference = sunDirection - glm::dot(sunDirection, up0) * up0;
  if (glm::length(reference) < 1e-6)
    reference = glm::cross(up0, std::abs(up0.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0));
  reference = glm::normalize(reference);
  const Fan fan(observer, frameAt(observer, reference), options.fieldElevations, options.fieldAzimuths,
                options.fieldSamples, atmosphere.bottomRadiusM, atmosphere.topRadiusM);
  const std::size_t P = fan.size();
  const Directions incoming(options.incomingZenith, options.incomingAzimuths);
  const Directions diffuse(options.diffuseZenith, options.diffuseAzimuths);
  const std::size_t K = incoming.size(), KD = diffuse.size();

  // Field 1: the once-scattered light arriving at every field point from K directions.
  // Fields 2..orders: the light scattered 2, 3, ... times on its way (from an isotropic
  // source sigma_s(y) Lbar(y), Lbar the mean of the previous order's light at y), summed,
  // from KD directions; the orders beyond as the geometric series of the last two.
  std::vector<float> single(P * K * nw), diffuseSum(P * KD * nw, 0.0f);
  std::vector<double> mean(P * nw), previousMean(P * nw), meanSum(P * nw, 0.0);
  std::vector<float> order(P * KD * nw);

  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  std::size_t computedPoints = 0;
  for (std::size_t p = 0; p < P; ++p) computedPoints += fan.computed(p) ? 1 : 0;
  const double units = static_cast<double>(computedPoints) *
                           (static_cast<double>(K) + (options.orders - 1) * static_cast<double>(KD)) +
                       static_cast<double>(viewDirections.size()) * 64.0;
  std::atomic<std::int64_t> done{0};
  std::atomic<bool> cancelled{false};
  const auto report = [&](double amount) {
    const double total = static_cast<double>(done += static_cast<std::int64_t>(amount));
    if (progress && omp_get_thread_num() == 0 && !cancelled.load() && !progress(std::min(1.0, total / units)))
      cancelled = true;
  };
  ParallelErrors errors;
  // fn(p, x, frame) for every field point that stands for itself, in parallel.
  const auto forEachFieldPoint = [&](const auto& fn) {
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads)
    for (std::int64_t pi = 0; pi < static_cast<std::int64_t>(P); ++pi) {
      errors.run([&] {
        const std::size_t p = static_cast<std::size_t>(pi);
        if (cancelled.load(std::memory_order_relaxed) || !fan.computed(p)) return;
        const glm::dvec3 x = fan.point(p);
        fn(p, x, frameAt(x, reference));
      });
    }
    errors.rethrow();
    if (cancelled) throw EclipsedSkyCancelled();
  };

  forEachFieldPoint([&](std::size_t p, const glm::dvec3& x, const Frame& f) {
    Spectrum L{};
    double* m = &mean[p * nw];
    std::fill(m, m + nw, 0.0);
    for (std::size_t q = 0; q < K; ++q) {
      const glm::dvec3 omega = incoming.at(q, f);
      integrator.march(
          x, omega, options.incomingSamples,
          [&](const glm::dvec3& y, const Densities& dens, Spectrum& S) { integrator.singleSource(y, omega, dens, S); },
          [&](const glm::dvec3& g, Spectrum& R) { integrator.directGround(g, R); }, L);
      for (std::size_t w = 0; w < nw; ++w) {
        single[(p * K + q) * nw + w] = static_cast<float>(L[w]);
        m[w] += incoming.weight[q] * L[w] / (4.0 * kPi);
      }
    }
    for (std::size_t w = 0; w < nw; ++w) meanSum[p * nw + w] = m[w];
    report(static_cast<double>(K));
  });

  // The previous order's light filtered by each component's phase function towards each
  // of the KD directions: F_c(p, q') = integral p_c(omega . omega_q') L(p, omega) d omega,
  // [point][q'][component][wavelength]; a march along omega_q' takes its source
  // sum_c density_c sigma_c F_c(y, q') from it (the frames of neighbouring points nearly
  // agree, so q' is the same direction there).
  std::vector<float> filtered(P * KD * nc * nw);
  const auto filter = [&](const std::vector<float>& field, const Directions& from) {
    const std::size_t KF = from.size();
    std::vector<double> phase(nc * nw * KD * KF);  // [c][w][q'][q], weights included
    for (std::size_t c = 0; c < nc; ++c)
      for (std::size_t w = 0; w < nw; ++w)
        for (std::size_t qo = 0; qo < KD; ++qo) {
          double* row = &phase[((c * nw + w) * KD + qo) * KF];
          for (std::size_t q = 0; q < KF; ++q) {
            const double cosTheta = diffuse.mu[qo] * from.mu[q] + diffuse.sinTheta[qo] * from.sinTheta[q] *
                                    (diffuse.cosPhi[qo] * from.cosPhi[q] + diffuse.sinPhi[qo] * from.sinPhi[q]);
            row[q] = from.weight[q] * optics.phases[c * nw + w](cosTheta);
          }
          normalise(row, KF);
        }
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::int64_t pi = 0; pi < static_cast<std::int64_t>(P); ++pi) {
      const std::size_t p = static_cast<std::size_t>(pi);
      if (!fan.computed(p)) continue;
      for (std::size_t qo = 0; qo < KD; ++qo)
        for (std::size_t c = 0; c < nc; ++c)
          for (std::size_t w = 0; w < nw; ++w) {
            const double* row = &phase[((c * nw + w) * KD + qo) * KF];
            const float* L = &field[p * KF * nw + w];
            double sum = 0.0;
            for (std::size_t q = 0; q < KF; ++q) sum += row[q] * L[q * nw];
            filtered[((p * KD + qo) * nc + c) * nw + w] = static_cast<float>(sum);
          }
    }
  };

  for (int n = 2; n <= options.orders; ++n) {
    previousMean.swap(mean);
    if (n == 2)
      filter(single, incoming);
    else
      filter(order, diffuse);
    forEachFieldPoint([&](std::size_t p, const glm::dvec3& x, const Frame& f) {
      Spectrum L{}, Lbar{};
      double* m = &mean[p * nw];
      std::fill(m, m + nw, 0.0);
      std::vector<double> F(nc * nw);
      std::size_t towards = 0;  // the march's direction
      const auto source = [&](const glm::dvec3& y, const Densities& dens, Spectrum& S) {
        const Fan::Cell cell = fan.locate(y);
        std::fill(F.begin(), F.end(), 0.0);
        for (std::size_t k = 0; k < 8; ++k) {
          if (cell.weights[k] == 0.0) continue;
          const float* in = &filtered[(cell.points[k] * KD + towards) * nc * nw];
          for (std::size_t i = 0; i < nc * nw; ++i) F[i] += cell.weights[k] * in[i];
        }
        for (std::size_t w = 0; w < nw; ++w) {
          double J = 0.0;
          for (std::size_t c = 0; c < nc; ++c) J += dens[c] * optics.scattering[c * nw + w] * F[c * nw + w];
          S[w] = J;
        }
      };
      // The ground under a sky of mean radiance Lbar over its upper half: E = 2 pi Lbar.
      const auto ground = [&](const glm::dvec3& g, Spectrum& R) {
        interpolate(fan.locate(g), previousMean, nw, Lbar.data());
        for (std::size_t w = 0; w < nw; ++w) R[w] = 2.0 * optics.albedo[w] * Lbar[w];
      };
      for (std::size_t q = 0; q < KD; ++q) {
        towards = q;
        integrator.march(x, diffuse.at(q, f), options.incomingSamples, source, ground, L);
        for (std::size_t w = 0; w < nw; ++w) {
          order[(p * KD + q) * nw + w] = static_cast<float>(L[w]);
          m[w] += diffuse.weight[q] * L[w] / (4.0 * kPi);
        }
      }
      report(static_cast<double>(KD));
    });
    // The order is added to the sums; the last one carries the rest, L_n (1 + q + q^2 + ...)
    // with q the ratio of the field's total mean radiance of the last two orders (at most
    // 0.9): the orders' decay is the whole air's (a point in the umbra, lit by light that
    // diffuses in, may see an order outshine the one before).
    std::vector<double> carry(nw, 1.0);
    if (n == options.orders)
      for (std::size_t w = 0; w < nw; ++w) {
        double last = 0.0, before = 0.0;
        for (std::size_t p = 0; p < P; ++p) last += mean[p * nw + w], before += previousMean[p * nw + w];
        if (before > 0.0) carry[w] = 1.0 / (1.0 - std::clamp(last / before, 0.0, 0.9));
      }
    for (std::size_t p = 0; p < P; ++p)
      for (std::size_t w = 0; w < nw; ++w) {
        for (std::size_t q = 0; q < KD; ++q)
          diffuseSum[(p * KD + q) * nw + w] += static_cast<float>(carry[w] * order[(p * KD + q) * nw + w]);
        meanSum[p * nw + w] += carry[w] * mean[p * nw + w];
      }
  }

  // The view rays: single scattering, plus sigma_s integral p L_in with L_in the field's,
  // interpolated between the 8 field points around each step; the ground lit by the Sun
  // and by the field's mean light.
  EclipsedSky sky;
  sky.radiance.assign(viewDirections.size(), std::vector<double>(nw, 0.0));
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads)
  for (std::int64_t v = 0; v < static_cast<std::int64_t>(viewDirections.size()); ++v) {
    errors.run([&] {
      if (cancelled.load(std::memory_order_relaxed)) return;
      const glm::dvec3 d = viewDirections[static_cast<std::size_t>(v)];
      // The phase functions' weights towards the view, sum over the field's directions:
      // pw[(c * nw + w) * (K + KD) + q] = weight_q p_c(omega_q . d), in the frame of the step
      // where they were last found (again once the local vertical has turned by 0.25 deg).
      std::vector<double> L1(K * nw), LD(KD * nw), pw(nc * nw * (K + KD));
      glm::dvec3 phaseUp(0.0);
      Spectrum single1{}, L{}, Lbar{};
      const auto source = [&](const glm::dvec3& y, const Densities& dens, Spectrum& S) {
        integrator.singleSource(y, d, dens, single1);
        const Fan::Cell cell = fan.locate(y);
        interpolate(cell, single, K * nw, L1.data());
        interpolate(cell, diffuseSum, KD * nw, LD.data());
        const Frame f = frameAt(y, reference);
        if (glm::dot(f.up, phaseUp) < 0.99999) {
          phaseUp = f.up;
          const double du = glm::dot(d, f.up), d1 = glm::dot(d, f.e1), d2 = glm::dot(d, f.e2);
          for (std::size_t c = 0; c < nc; ++c)
            for (std::size_t w = 0; w < nw; ++w) {
              const PhaseTable& ph = optics.phases[c * nw + w];
              double* row = &pw[(c * nw + w) * (K + KD)];
              for (std::size_t q = 0; q < K; ++q)
                row[q] = incoming.weight[q] *
                         ph(incoming.mu[q] * du + incoming.sinTheta[q] * (incoming.cosPhi[q] * d1 + incoming.sinPhi[q] * d2));
              for (std::size_t q = 0; q < KD; ++q)
                row[K + q] = diffuse.weight[q] *
                             ph(diffuse.mu[q] * du + diffuse.sinTheta[q] * (diffuse.cosPhi[q] * d1 + diffuse.sinPhi[q] * d2));
              normalise(row, K);
              normalise(row + K, KD);
            }
        }
        for (std::size_t w = 0; w < nw; ++w) {
          double J = 0.0;
          for (std::size_t c = 0; c < nc; ++c) {
            const double sc = dens[c] * optics.scattering[c * nw + w];
            if (!(sc > 0.0)) continue;
            const double* row = &pw[(c * nw + w) * (K + KD)];
            double sum = 0.0;
            for (std::size_t q = 0; q < K; ++q) sum += row[q] * L1[q * nw + w];
            for (std::size_t q = 0; q < KD; ++q) sum += row[K + q] * LD[q * nw + w];
            J += sc * sum;
          }
          S[w] = single1[w] + J;
        }
      };
      const auto ground = [&](const glm::dvec3& g, Spectrum& R) {
        integrator.directGround(g, R);
        interpolate(fan.locate(g), meanSum, nw, Lbar.data());
        for (std::size_t w = 0; w < nw; ++w) R[w] += 2.0 * optics.albedo[w] * Lbar[w];
      };
      integrator.march(observer, d, options.viewSamples, source, ground, L);
      for (std::size_t w = 0; w < nw; ++w) sky.radiance[static_cast<std::size_t>(v)][w] = L[w];
      report(64.0);
    });
  }
  errors.rethrow();
  if (cancelled) throw EclipsedSkyCancelled();
  sky.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sky;
}

}  // namespace umbra::atmosphere
