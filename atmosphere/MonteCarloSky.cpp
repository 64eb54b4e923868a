#include "MonteCarloSky.hpp"

#include "ParallelErrors.hpp"
#include "Quadrature.hpp"

#include <glm/geometric.hpp>

#include <omp.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <stdexcept>

namespace umbra::atmosphere {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr std::int64_t kBlockPaths = 512;
/// Below this weight a path plays Russian roulette (survives with probability w / it).
constexpr double kRouletteWeight = 0.25;
/// The most components an atmosphere may have here (their densities live on the stack).
constexpr std::size_t kMaxComponents = 32;
using Densities = std::array<double, kMaxComponents>;

// ---- random numbers: xoshiro256** seeded by splitmix64 ----------------------------------

std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

class Random {
public:
  Random(std::uint64_t seed, std::uint64_t a, std::uint64_t b, std::uint64_t c) {
    std::uint64_t state = seed;
    state = splitmix64(state) ^ a;
    state = splitmix64(state) ^ b;
    state = splitmix64(state) ^ c;
    for (std::uint64_t& word : s_) word = splitmix64(state);
  }
  /// Uniform in [0, 1).
  double next() { return static_cast<double>(bits() >> 11) * 0x1.0p-53; }

private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t bits() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  std::uint64_t s_[4];
};

// ---- directions --------------------------------------------------------------------------

/// A unit vector at angle theta (cosine c) from `axis`, azimuth phi about it.
glm::dvec3 turn(const glm::dvec3& axis, double c, double phi) {
  const glm::dvec3 helper = std::abs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 e1 = glm::normalize(glm::cross(axis, helper));
  const glm::dvec3 e2 = glm::cross(axis, e1);
  const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
  return glm::normalize(c * axis + s * (std::cos(phi) * e1 + std::sin(phi) * e2));
}

/// Draws the scattering angle from a phase function's tabulation: cells of equal width in
/// theta, each with its share of the sphere's integral (4-point Gauss-Legendre in the cell),
/// theta uniform within the cell. No cell is left empty (a floor of 1e-9 of the mean), so
/// the drawn density is positive wherever p may be.
class PhaseSampler {
public:
  PhaseSampler(const PhaseFunction& p, int cells) : dTheta_(kPi / cells), cdf_(cells + 1, 0.0), mass_(cells) {
    const GaussLegendreRule rule(4);
    double total = 0.0;
    for (int i = 0; i < cells; ++i) {
      const double mid = (i + 0.5) * dTheta_;
      double m = 0.0;
      for (std::size_t k = 0; k < rule.x.size(); ++k) {
        const double theta = mid + 0.5 * dTheta_ * rule.x[k];
        m += 0.5 * dTheta_ * rule.w[k] * 2.0 * kPi * p(std::cos(theta)) * std::sin(theta);
      }
      mass_[i] = m;
      total += m;
    }
    const double floor = 1e-9 * total / cells;
    total = 0.0;
    for (int i = 0; i < cells; ++i) {
      mass_[i] = std::max(mass_[i], floor);
      total += mass_[i];
    }
    for (int i = 0; i < cells; ++i) {
      mass_[i] /= total;
      cdf_[i + 1] = cdf_[i] + mass_[i];
    }
    cdf_.back() = 1.0;
  }

  /// Draws cos theta; `density` gets the drawn density per steradian at that angle.
  double sample(double u1, double u2, double& density) const {
    const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u1);
    const std::size_t i = std::min<std::size_t>(mass_.size() - 1, static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, it - cdf_.begin() - 1)));
    const double theta = (static_cast<double>(i) + u2) * dTheta_;
    const double sinTheta = std::sin(theta);
    density = sinTheta > 0.0 ? mass_[i] / (dTheta_ * 2.0 * kPi * sinTheta) : 0.0;
    return std::cos(theta);
  }

private:
  double dTheta_;
  std::vector<double> cdf_, mass_;
};

/// Distance along x + t d (|d| = 1) to the sphere of radius R from inside it.
double distanceToSphereFromInside(const glm::dvec3& x, const glm::dvec3& d, double R) {
  const double b = glm::dot(x, d);
  const double disc = std::max(0.0, b * b - (glm::dot(x, x) - R * R));
  return std::max(0.0, -b + std::sqrt(disc));
}

/// Distance to the sphere of radius R from outside it, or infinity when the ray misses it.
double distanceToSphereFromOutside(const glm::dvec3& x, const glm::dvec3& d, double R) {
  const double b = glm::dot(x, d);
  if (b >= 0.0) return INFINITY;
  const double disc = b * b - (glm::dot(x, x) - R * R);
  if (disc < 0.0) return INFINITY;
  return std::max(0.0, -b - std::sqrt(disc));
}

/// One wavelength's optics and the state shared by its paths.
struct Channel {
  double majorant = 0.0;
  std::vector<double> extinction;   ///< per component, at relative density 1
  std::vector<double> scattering;   ///< per component
  std::vector<const PhaseFunction*> phases;
  std::vector<PhaseSampler> samplers;
  double groundAlbedo = 0.0;
};

class Tracer {
public:
  Tracer(const Atmosphere& atmosphere, const glm::dvec3& sun, const SunVisibility& visibility, int maxOrders)
      : atm_(atmosphere), sun_(sun), visibility_(visibility), maxOrders_(maxOrders),
        rb_(atmosphere.bottomRadiusM), rt_(atmosphere.topRadiusM) {}

  /// One path's radiance per unit solar irradiance.
  double path(const Channel& ch, glm::dvec3 x, glm::dvec3 d, Random& rng) const {
    double sum = 0.0, w = 1.0;
    const std::size_t nc = atm_.components.size();
    Densities density{};
    for (int order = 1; maxOrders_ == 0 || order <= maxOrders_; ++order) {
      // Free flight: delta tracking to a real collision, the ground or space.
      const double tGround = distanceToSphereFromOutside(x, d, rb_);
      const double tEnd = std::min(tGround, distanceToSphereFromInside(x, d, rt_));
      double t = 0.0, sigmaT = 0.0;
      bool collided = false;
      while (true) {
        t -= std::log1p(-rng.next()) / ch.majorant;
        if (t >= tEnd) break;
        sigmaT = extinctionAt(ch, x + t * d, density);
        if (rng.next() * ch.majorant < sigmaT) {
          collided = true;
          break;
        }
      }
      if (collided) {
        x += t * d;
        double sigmaS = 0.0;
        for (std::size_t c = 0; c < nc; ++c) sigmaS += density[c] * ch.scattering[c];
        if (!(sigmaS > 0.0)) break;  // absorbed
        w *= sigmaS / sigmaT;
        const double nu = glm::dot(d, sun_);
        double phase = 0.0;
        for (std::size_t c = 0; c < nc; ++c)
          if (ch.scattering[c] > 0.0) phase += density[c] * ch.scattering[c] * (*ch.phases[c])(nu);
        sum += w * (phase / sigmaS) * sunlight(ch, x, rng);
        // The next direction: a component by its share, an angle from its phase function.
        // (the last scattering one where rounding leaves the pick past them all)
        double pick = rng.next() * sigmaS;
        std::size_t c = nc;
        for (std::size_t k = 0; k < nc; ++k) {
          const double share = density[k] * ch.scattering[k];
          if (!(share > 0.0)) continue;
          c = k;
          pick -= share;
          if (pick < 0.0) break;
        }
        if (c == nc) break;  // (sigmaS > 0 leaves one: not reached)
        double q = 0.0;
        const double cosTheta = ch.samplers[c].sample(rng.next(), rng.next(), q);
        if (!(q > 0.0)) break;
        w *= (*ch.phases[c])(cosTheta) / q;
        d = turn(d, cosTheta, 2.0 * kPi * rng.next());
      } else if (tGround <= tEnd && std::isfinite(tGround)) {
        x = (x + tGround * d);
        x *= rb_ / glm::length(x);  // on the ground exactly
        const glm::dvec3 n = x / rb_;
        const double cosSun = glm::dot(n, sun_);
        if (cosSun > 0.0) sum += w * (ch.groundAlbedo / kPi) * cosSun * sunlight(ch, x, rng);
        if (!(ch.groundAlbedo > 0.0)) break;
        w *= ch.groundAlbedo;
        // Cosine-weighted about the normal.
        const double u = rng.next();
        d = turn(n, std::sqrt(1.0 - u), 2.0 * kPi * rng.next());
      } else {
        break;  // to space
      }
      if (w < kRouletteWeight) {
        if (rng.next() * kRouletteWeight >= w) break;
        w = kRouletteWeight;
      }
    }
    return sum;
  }

private:
  double extinctionAt(const Channel& ch, const glm::dvec3& x, Densities& density) const {
    const double h = glm::length(x) - rb_;
    double sigmaT = 0.0;
    for (std::size_t c = 0; c < atm_.components.size(); ++c) {
      density[c] = atm_.components[c].density.at(h);
      sigmaT += density[c] * ch.extinction[c];
    }
    if (sigmaT > ch.majorant)
      throw std::logic_error("Monte-Carlo sky: the extinction " + std::to_string(sigmaT) + " /m at altitude " +
                             std::to_string(h) + " m exceeds the majorant " + std::to_string(ch.majorant));
    return sigmaT;
  }

  /// The Sun's light at x per unit irradiance: the planet's shadow (the Sun's centre), the
  /// transmittance to space (ratio tracking) and the caller's visibility.
  double sunlight(const Channel& ch, const glm::dvec3& x, Random& rng) const {
    if (std::isfinite(distanceToSphereFromOutside(x, sun_, rb_ * (1.0 - 1e-12)))) return 0.0;
    const double v = visibility_ ? visibility_(x) : 1.0;
    if (!(v > 0.0)) return 0.0;
    const double tEnd = distanceToSphereFromInside(x, sun_, rt_);
    Densities density{};
    double T = 1.0, t = 0.0;
    while (true) {
      t -= std::log1p(-rng.next()) / ch.majorant;
      if (t >= tEnd) break;
      T *= 1.0 - extinctionAt(ch, x + t * sun_, density) / ch.majorant;
      if (T < 1e-6) {  // roulette on the transmittance, unbiased
        if (rng.next() >= 0.1) return 0.0;
        T *= 10.0;
      }
    }
    return T * v;
  }

  const Atmosphere& atm_;
  glm::dvec3 sun_;
  const SunVisibility& visibility_;
  int maxOrders_;
  double rb_, rt_;
};

}  // namespace

std::string MonteCarloSkyOptions::validate() const {
  if (paths < 1) return "paths: expected at least 1, got " + std::to_string(paths);
  if (maxOrders < 0) return "maxOrders: expected 0 (every order) or more, got " + std::to_string(maxOrders);
  if (threads < 0) return "threads: expected 0 (the default) or more, got " + std::to_string(threads);
  if (phaseSamplingCells < 16 || phaseSamplingCells > 1 << 20)
    return "phaseSamplingCells: expected 16 to 1048576, got " + std::to_string(phaseSamplingCells);
  return {};
}

glm::dvec3 checkedSkyObserver(const char* what, const Atmosphere& atmosphere, const glm::dvec3& observerM,
                              const std::vector<glm::dvec3>& viewDirections, const glm::dvec3& sunDirection) {
  const double r = glm::length(observerM);
  if (!(r >= atmosphere.bottomRadiusM * (1.0 - 1e-12) && r <= atmosphere.topRadiusM))
    throw std::invalid_argument(std::string(what) + ": the observer is " + std::to_string(r - atmosphere.bottomRadiusM) +
                                " m above the ground, outside the atmosphere (0 to " +
                                std::to_string(atmosphere.thicknessM()) + " m)");
  const auto unit = [](const glm::dvec3& v) { return std::abs(glm::length(v) - 1.0) < 1e-9; };
  if (!unit(sunDirection)) throw std::invalid_argument(std::string(what) + ": the Sun's direction is not a unit vector");
  for (const glm::dvec3& v : viewDirections)
    if (!unit(v)) throw std::invalid_argument(std::string(what) + ": a view direction is not a unit vector");
  return r < atmosphere.bottomRadiusM ? observerM * (atmosphere.bottomRadiusM / r) : observerM;
}

std::vector<double> extinctionMajorantPerM(const Atmosphere& atmosphere) {
  const double top = atmosphere.thicknessM();
  std::vector<double> majorant(atmosphere.wavelengthsNm.size(), 0.0);
  for (const Component& c : atmosphere.components) {
    double maxDensity = 0.0;
    const int steps = static_cast<int>(std::ceil(top / 10.0));
    for (int i = 0; i <= steps; ++i) maxDensity = std::max(maxDensity, c.density.at(top * i / steps));
    for (double k : c.density.kinksM())
      if (k >= 0.0 && k <= top) maxDensity = std::max(maxDensity, c.density.at(k));
    for (std::size_t w = 0; w < majorant.size(); ++w) majorant[w] += maxDensity * c.extinctionPerM(w);
  }
  for (double& m : majorant) m *= 1.01;
  return majorant;
}

MonteCarloSky monteCarloSkyRadiance(const Atmosphere& atmosphere, const glm::dvec3& observerM,
                                    const std::vector<glm::dvec3>& viewDirections, const glm::dvec3& sunDirection,
                                    const SunVisibility& visibility, const MonteCarloSkyOptions& options,
                                    const MonteCarloProgress& progress) {
  if (const std::string problem = options.validate(); !problem.empty())
    throw std::invalid_argument("Monte-Carlo sky: " + problem);
  const glm::dvec3 observer = checkedSkyObserver("Monte-Carlo sky", atmosphere, observerM, viewDirections, sunDirection);

  const auto start = std::chrono::steady_clock::now();
  const std::size_t nw = atmosphere.wavelengthsNm.size();
  const std::vector<double> majorants = extinctionMajorantPerM(atmosphere);
  std::vector<Channel> channels(nw);
  for (std::size_t w = 0; w < nw; ++w) {
    Channel& ch = channels[w];
    ch.majorant = std::max(majorants[w], 1e-30);
    ch.groundAlbedo = w < atmosphere.groundAlbedo.size() ? atmosphere.groundAlbedo[w] : 0.0;
    for (const Component& c : atmosphere.components) {
      ch.extinction.push_back(c.extinctionPerM(w));
      ch.scattering.push_back(c.scatteringPerM[w]);
      ch.phases.push_back(&c.phase(w));
      ch.samplers.emplace_back(c.phase(w), options.phaseSamplingCells);
    }
  }

  if (atmosphere.components.size() > kMaxComponents)
    throw std::invalid_argument("Monte-Carlo sky: the atmosphere has " + std::to_string(atmosphere.components.size()) +
                                " components, at most " + std::to_string(kMaxComponents) + " are supported");
  const Tracer tracer(atmosphere, sunDirection, visibility, options.maxOrders);
  const std::int64_t blocks = (options.paths + kBlockPaths - 1) / kBlockPaths;
  const std::int64_t tasks = static_cast<std::int64_t>(viewDirections.size() * nw) * blocks;
  std::vector<double> sums(static_cast<std::size_t>(tasks)), squares(static_cast<std::size_t>(tasks));
  std::atomic<std::int64_t> done{0};
  std::atomic<bool> cancelled{false};
  std::mutex progressLock;
  ParallelErrors errors;
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (std::int64_t task = 0; task < tasks; ++task) {
    errors.run([&] {
      if (cancelled.load(std::memory_order_relaxed)) return;
      const std::int64_t block = task % blocks;
      const std::size_t w = static_cast<std::size_t>((task / blocks) % static_cast<std::int64_t>(nw));
      const std::size_t dir = static_cast<std::size_t>(task / blocks / static_cast<std::int64_t>(nw));
      Random rng(options.seed, dir, w, static_cast<std::uint64_t>(block));
      const std::int64_t n = std::min(kBlockPaths, options.paths - block * kBlockPaths);
      double s = 0.0, s2 = 0.0;
      for (std::int64_t i = 0; i < n; ++i) {
        const double L = tracer.path(channels[w], observer, viewDirections[dir], rng);
        s += L;
        s2 += L * L;
      }
      sums[static_cast<std::size_t>(task)] = s;
      squares[static_cast<std::size_t>(task)] = s2;
      const std::int64_t finished = ++done;
      // One report at a time, from whichever thread finished (a busy lock skips a report).
      if (progress && progressLock.try_lock()) {
        const bool goOn = progress(static_cast<double>(finished) / static_cast<double>(tasks));
        progressLock.unlock();
        if (!goOn) cancelled = true;
      }
    });
  }
  errors.rethrow();
  if (cancelled) throw MonteCarloCancelled();

  MonteCarloSky sky;
  sky.pathsPerDirection = options.paths;
  const double N = static_cast<double>(options.paths);
  for (std::size_t dir = 0; dir < viewDirections.size(); ++dir) {
    MonteCarloRadiance out;
    for (std::size_t w = 0; w < nw; ++w) {
      double s = 0.0, s2 = 0.0;
      for (std::int64_t b = 0; b < blocks; ++b) {
        const std::size_t task = (dir * nw + w) * static_cast<std::size_t>(blocks) + static_cast<std::size_t>(b);
        s += sums[task];
        s2 += squares[task];
      }
      const double mean = s / N;
      const double variance = N > 1.0 ? std::max(0.0, (s2 / N - mean * mean) * N / (N - 1.0)) : 0.0;
      out.radiance.push_back(mean);
      out.standardError.push_back(std::sqrt(variance / N));
    }
    sky.directions.push_back(std::move(out));
  }
  sky.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sky;
}

}  // namespace umbra::atmosphere
