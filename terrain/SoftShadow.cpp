#include "SoftShadow.hpp"
#include "ParallelErrors.hpp"

#include "SolarDisc.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace umbra::terrain {
namespace {

/// Where the reference starts along the footprint [texels]: the local slope towards the Sun.
constexpr double kReferenceStartTexels = 1e-3;

constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();

/// The vertical plane through a receiver and a direction to the sky. Points of the plane
/// are r (cos phi a + sin phi b); its footprint on the grid is g0 + s dir (s in texels).
class Profile {
public:
  Profile(const HeightField& f, const MaximumMipmap& mip, int i, int j, glm::dvec3 towards, double lowerEdgeRad)
      : Profile(f, mip, glm::dvec2(i, j), f.receiverHeight(i, j), towards, lowerEdgeRad) {}
  /// A receiver at grid coordinates g (fractional) and height receiverHeightM.
  Profile(const HeightField& f, const MaximumMipmap& mip, glm::dvec2 g, double receiverHeightM, glm::dvec3 towards,
          double lowerEdgeRad)
      : f(f), mip(mip) {
    towards = glm::normalize(towards);
    a = f.direction(g.x, g.y);
    rp = f.bodyRadiusM + receiverHeightM;
    const glm::dvec3 horizontal = towards - glm::dot(towards, a) * a;
    const double len = glm::length(horizontal);
    sunElevation = std::atan2(glm::dot(towards, a), len);
    if (len < 1e-12) {
      degenerate = true;
      return;
    }
    b = horizontal / len;
    g0 = g;
    // Derivative of the gnomonic projection along the great circle towards b.
    dir = glm::normalize(glm::dvec2(b.x * a.z - a.x * b.z, b.y * a.z - a.y * b.z));
    sEnd = std::min(gridExit(), volumeExit(lowerEdgeRad));
  }

  /// Elevation above the receiver's horizontal of the point at radius r over footprint s.
  double elevation(double s, double r) const {
    double c, sn;
    angle(s, c, sn);
    return std::atan2(r * c - rp, r * sn);
  }
  /// Terrain height (bilinear) at footprint s; NaN over no data.
  double height(double s) const {
    const glm::dvec2 g = g0 + s * dir;
    return f.bilinear(g.x, g.y);
  }
  /// Where a search from `start` begins: the terrain's elevation there, -inf where the
  /// footprint has ended before it (the local slope at the receiver is always taken).
  double firstElevation(double start) const {
    return start <= kReferenceStartTexels || start < sEnd ? terrainElevation(start) : -kInf;
  }
  /// Elevation of the terrain at footprint s; -inf over no data.
  double terrainElevation(double s) const { return terrainElevation(s, height(s)); }
  double terrainElevation(double s, double h) const {
    return std::isnan(h) ? -kInf : elevation(s, f.bodyRadiusM + h);
  }
  /// The highest elevation any point of radius <= rMax over footprint [sa, sb] can have:
  /// from inside the circle r = rMax the elevation of its arc falls monotonically with
  /// phi; from outside it peaks at the tangent point phi = acos(rMax / rp).
  double elevationBound(double sa, double sb, double rMax) const {
    double ca, sa_;
    angle(sa, ca, sa_);
    const double ea = std::atan2(rMax * ca - rp, rMax * sa_);
    if (rp <= rMax) return ea;
    double cb, sb_;
    angle(sb, cb, sb_);
    const double ct = rMax / rp;
    if (cb <= ct && ct <= ca) return -std::acos(ct);
    return std::max(ea, std::atan2(rMax * cb - rp, rMax * sb_));
  }
  /// Clip footprint [sa, sb] to the box [x0, x1] x [y0, y1] (grid coordinates).
  bool clip(double x0, double x1, double y0, double y1, double& sa, double& sb) const {
    auto slab = [&](double g, double d, double lo, double hi) {
      if (d == 0.0) return g >= lo && g <= hi;
      double t1 = (lo - g) / d, t2 = (hi - g) / d;
      if (t1 > t2) std::swap(t1, t2);
      sa = std::max(sa, t1), sb = std::min(sb, t2);
      return true;
    };
    return slab(g0.x, dir.x, x0, x1) && slab(g0.y, dir.y, y0, y1) && sb > sa;
  }

  const HeightField& f;
  const MaximumMipmap& mip;
  glm::dvec3 a{0.0}, b{0.0};
  glm::dvec2 g0{0.0}, dir{0.0};
  double rp = 0.0, sunElevation = 0.0, sEnd = 0.0;
  bool degenerate = false;

private:
  void angle(double s, double& c, double& sn) const {
    const glm::dvec2 g = g0 + s * dir;
    const glm::dvec3 n = f.direction(g.x, g.y);
    c = glm::dot(n, a), sn = glm::dot(n, b);
  }
  double gridExit() const {
    double sa = 0.0, sb = kInf;
    return clip(0.0, f.width - 1.0, 0.0, f.height - 1.0, sa, sb) ? sb : 0.0;
  }
  /// Beyond this footprint distance no terrain up to the field's maximum height rises
  /// above `lowerEdge` (the disc's lower edge) seen from the receiver.
  double volumeExit(double lowerEdge) const {
    const double rMax = f.bodyRadiusM + mip.globalMax();
    if (lowerEdge <= -0.5 * kPi) return kInf;
    if (rp > rMax) return lowerEdge >= -std::acos(rMax / rp) ? 0.0 : kInf;
    // The ray from the receiver at elevation lowerEdge meets the circle r = rMax at X.
    const double sg = std::sin(lowerEdge), cg = std::cos(lowerEdge);
    const double lambda = -rp * sg + std::sqrt(std::max(0.0, rp * rp * sg * sg + rMax * rMax - rp * rp));
    const glm::dvec3 x = rp * a + lambda * (sg * a + cg * b);
    if (x.z <= 0.0) return kInf;
    const glm::dvec2 plane = f.bodyRadiusM * glm::dvec2(x.x, x.y) / x.z;
    const glm::dvec2 g(plane.x / f.spacingM + 0.5 * (f.width - 1), plane.y / f.spacingM + 0.5 * (f.height - 1));
    return std::max(0.0, glm::dot(g - g0, dir));
  }
};

/// Algorithm 1: the maximum-mipmap search for the highest horizon along the footprint.
class MipmapSearch {
public:
  MipmapSearch(const Profile& p, double lowerEdge, double upperEdge) : p(p), lo(lowerEdge), hi(upperEdge) {}

  double run(int levels, double start, long long& samples) {
    best = p.firstElevation(start);
    count = 1;
    const int top = std::clamp(levels - 1, 0, p.mip.levels() - 1);
    const double block = std::ldexp(1.0, top);
    const int nx = p.mip.width(top), ny = p.mip.height(top);
    const double cellsX = p.f.width - 1.0, cellsY = p.f.height - 1.0;
    // Concatenated intervals: one level-`top` texel of footprint after another.
    double s = start;
    while (s < p.sEnd && best < hi) {
      const glm::dvec2 g = p.g0 + s * p.dir;
      const int bi = blockIndex(g.x, p.dir.x, block, nx), bj = blockIndex(g.y, p.dir.y, block, ny);
      double sa = s, sb = p.sEnd;
      const bool inside = p.clip(bi * block, std::min((bi + 1) * block, cellsX), bj * block,
                                 std::min((bj + 1) * block, cellsY), sa, sb);
      double next = inside ? sb : s;
      if (inside) visit(top, bi, bj, s, sb);
      s = std::max(next, s + 1e-9);
    }
    samples = count;
    return best;
  }

private:
  static int blockIndex(double g, double d, double block, int n) {
    const double q = g / block;
    int k = static_cast<int>(std::floor(q));
    if (q == k && d < 0.0) --k;
    return std::clamp(k, 0, n - 1);
  }

  void visit(int level, int bi, int bj, double sa, double sb) {
    const double hMax = p.mip.max(level, bi, bj);
    if (hMax == -kInf) return;  // no data: casts no shadow
    ++count;
    if (p.elevationBound(sa, sb, p.f.bodyRadiusM + hMax) <= std::max(best, lo)) return;
    if (level == 0) {
      // The bilinear surface along the footprint is a parabola inside the cell.
      const double mid = 0.5 * (sa + sb);
      const Parabola h{mid, 0.5 * (sb - sa), p.height(sa), p.height(mid), p.height(sb)};
      count += 3;
      if (!std::isnan(h.a + h.m + h.b)) refine(h, sa, sb, 0);
      else best = std::max(best, p.terrainElevation(sb));  // part no data: its valid corners
      return;
    }
    // Children touched by the footprint, in order along it (up to three of four, Fig. 4b).
    struct Child {
      int i, j;
      double sa, sb;
    } children[4];
    int n = 0;
    const int m = level - 1;
    const double size = std::ldexp(1.0, m);
    const double cellsX = p.f.width - 1.0, cellsY = p.f.height - 1.0;
    for (int dj = 0; dj < 2; ++dj)
      for (int di = 0; di < 2; ++di) {
        const int ci = 2 * bi + di, cj = 2 * bj + dj;
        if (ci >= p.mip.width(m) || cj >= p.mip.height(m)) continue;
        double ca = sa, cb = sb;
        if (p.clip(ci * size, std::min((ci + 1) * size, cellsX), cj * size, std::min((cj + 1) * size, cellsY), ca, cb))
          children[n++] = {ci, cj, ca, cb};
      }
    for (int k = 1; k < n; ++k)  // in order along the footprint (insertion sort of <= 4)
      for (int q = k; q > 0 && children[q].sa < children[q - 1].sa; --q) std::swap(children[q], children[q - 1]);
    for (int k = 0; k < n && best < hi; ++k) visit(m, children[k].i, children[k].j, children[k].sa, children[k].sb);
  }

  /// Heights a (at centre - half), m (centre), b (centre + half) along one cell.
  struct Parabola {
    double centre, half, a, m, b;
    double at(double s) const {
      const double u = (s - centre) / half;
      return m + 0.5 * (b - a) * u + 0.5 * (a + b - 2.0 * m) * u * u;
    }
    double maxOver(double s0, double s1) const {
      double top = std::max(at(s0), at(s1));
      const double curvature = a + b - 2.0 * m;
      if (curvature < 0.0) {
        const double sv = centre - 0.5 * (b - a) / curvature * half;
        if (sv > s0 && sv < s1) top = std::max(top, at(sv));
      }
      return top;
    }
  };

  /// Below the texel: bisect the cell's stretch while its bound (the parabola's maximum)
  /// may still raise the horizon by more than kTolerance; near the receiver the elevation
  /// peaks inside a cell, not at the height's peak.
  void refine(const Parabola& h, double sa, double sb, int depth) {
    const double bound = p.elevationBound(sa, sb, p.f.bodyRadiusM + h.maxOver(sa, sb));
    ++count;
    if (bound <= std::max(best, lo)) return;
    best = std::max(best, p.terrainElevation(sb, h.at(sb)));
    ++count;
    if (bound - best <= kToleranceRad || depth >= 12 || best >= hi) return;
    const double mid = 0.5 * (sa + sb);
    refine(h, sa, mid, depth + 1);
    refine(h, mid, sb, depth + 1);
  }

  static constexpr double kToleranceRad = 2e-6;  ///< 4e-4 of the Sun's radius
  const Profile& p;
  double lo, hi;
  double best = -kInf;
  long long count = 0;
};

double uniformSearch(const Profile& p, int steps, double start, double hi, long long& samples) {
  double best = p.firstElevation(start);
  samples = 1;
  if (p.sEnd <= start) return best;
  const double step = (p.sEnd - start) / steps;
  for (int k = 1; k <= steps && best < hi; ++k, ++samples) best = std::max(best, p.terrainElevation(start + k * step));
  return best;
}

/// Cell by cell along the footprint (no mipmap). Inside a cell the bilinear surface along
/// the footprint is a parabola in s: relative to the receiver, z(s) = alpha + beta s +
/// gamma s^2, with gamma = (h00 - h10 - h01 + h11) dir.x dir.y. The tangent of the
/// elevation, (z(s) - k s^2) / (D s) (D the texel's length on the ground, k = D^2 / 2R the
/// sphere's drop), is stationary at s^2 = alpha / (gamma - k), a maximum where alpha < 0.
/// The exact elevation is taken there and at each cell's end: the highest point of the
/// bilinear surface along the footprint, not a sample of it. A cell with a no-data corner
/// counts at its end's height (as the DP).
double cellSearch(const Profile& p, double start, double hi, long long& samples) {
  const HeightField& f = p.f;
  double best = p.firstElevation(start);
  samples = 1;
  const double k = f.spacingM * f.spacingM / (2.0 * p.rp);
  const double base = p.rp - f.bodyRadiusM;
  double s = start;
  while (s < p.sEnd && best < hi) {
    // The next grid line the footprint crosses, on either axis.
    const glm::dvec2 g = p.g0 + s * p.dir;
    double next = p.sEnd;
    for (int a = 0; a < 2; ++a) {
      if (p.dir[a] == 0.0) continue;
      const double line = p.dir[a] > 0.0 ? std::floor(g[a]) + 1.0 : std::ceil(g[a]) - 1.0;
      next = std::min(next, s + (line - g[a]) / p.dir[a]);
    }
    next = std::max(next, s + 1e-9);
    const glm::dvec2 gm = p.g0 + 0.5 * (s + next) * p.dir;
    const int i = std::clamp(static_cast<int>(std::floor(gm.x)), 0, f.width - 2);
    const int j = std::clamp(static_cast<int>(std::floor(gm.y)), 0, f.height - 2);
    const double h00 = f.at(i, j), h10 = f.at(i + 1, j), h01 = f.at(i, j + 1), h11 = f.at(i + 1, j + 1);
    samples += 4;
    if (std::isnan(h00 + h10 + h01 + h11)) {
      best = std::max(best, p.terrainElevation(next));
    } else {
      // z(s) = e + ax fx + ay fy + x fx fy, fx = fx0 + dir.x s, fy = fy0 + dir.y s.
      const double e = h00 - base, ax = h10 - h00, ay = h01 - h00, x = h00 - h10 - h01 + h11;
      const double fx0 = p.g0.x - i, fy0 = p.g0.y - j;
      const auto z = [&](double t) {
        const double fx = fx0 + p.dir.x * t, fy = fy0 + p.dir.y * t;
        return e + ax * fx + ay * fy + x * fx * fy;
      };
      best = std::max(best, p.terrainElevation(next, base + z(next)));
      const double alpha = z(0.0), gamma = x * p.dir.x * p.dir.y;
      if (alpha < 0.0 && gamma - k < 0.0) {
        const double sPeak = std::sqrt(alpha / (gamma - k));
        if (sPeak > s && sPeak < next) best = std::max(best, p.terrainElevation(sPeak, base + z(sPeak)));
      }
    }
    s = next;
  }
  return best;
}

/// Reference: vertical strips x in (-1, 1) of the disc at x = sin(theta), theta at the
/// midpoints of equal steps (the strip heights sqrt(1 - x^2) vanish smoothly there).
double referenceFraction(const HeightField& f, const MaximumMipmap& mip, int i, int j, const SunDisc& sun,
                         const ShadowOptions& o, long long& samples) {
  const glm::dvec3 L = glm::normalize(sun.direction);
  const glm::dvec3 up = f.direction(i, j);
  const glm::dvec3 across = glm::cross(L, up);
  const double r = sun.angularRadiusRad, u = sun.limbDarkening;
  if (glm::length(across) < 1e-12) return glm::dot(L, up) > 0.0 ? 1.0 : 0.0;
  const glm::dvec3 w = glm::normalize(across);
  double flux = 0.0;
  samples = 0;
  const int n = o.referenceStrips;
  const double dTheta = kPi / n;
  for (int k = 0; k < n; ++k) {
    const double theta = -0.5 * kPi + (k + 0.5) * dTheta;
    const double x = std::sin(theta), q = std::cos(theta), dx = q * dTheta;
    const glm::dvec3 Lk = glm::normalize(L + std::tan(x * r) * w);
    const Profile p(f, mip, i, j, Lk, 0.0);
    const double e = p.sunElevation, lower = e - q * r, upper = e + q * r;
    const Profile strip(f, mip, i, j, Lk, lower);
    double horizon = strip.terrainElevation(kReferenceStartTexels), atS = kReferenceStartTexels;
    ++samples;
    for (double s = kReferenceStartTexels + o.referenceStepTexels; s < strip.sEnd + o.referenceStepTexels && horizon < upper;
         s += o.referenceStepTexels, ++samples) {
      const double e = strip.terrainElevation(std::min(s, strip.sEnd));
      if (e > horizon) horizon = e, atS = std::min(s, strip.sEnd);
    }
    // The exact peak near the highest sample: golden-section search within a step of it.
    if (horizon > lower && horizon < upper) {
      constexpr double g = 0.6180339887498949;
      double x0 = std::max(kReferenceStartTexels, atS - o.referenceStepTexels), x1 = std::min(strip.sEnd, atS + o.referenceStepTexels);
      double c = x1 - g * (x1 - x0), d = x0 + g * (x1 - x0);
      double ec = strip.terrainElevation(c), ed = strip.terrainElevation(d);
      for (int k = 0; k < 40; ++k, ++samples) {
        if (ec > ed) x1 = d, d = c, ed = ec, c = x1 - g * (x1 - x0), ec = strip.terrainElevation(c);
        else x0 = c, c = d, ec = ed, d = x0 + g * (x1 - x0), ed = strip.terrainElevation(d);
      }
      horizon = std::max({horizon, ec, ed});
    }
    // The strip's rays between y = (horizon - e) / r and q are visible.
    const double yLo = std::clamp((horizon - e) / r, -q, q);
    auto F = [q](double y) { return 0.5 * (y * std::sqrt(std::max(0.0, q * q - y * y)) + q * q * std::asin(std::clamp(y / q, -1.0, 1.0))); };
    flux += dx * ((1.0 - u) * (q - yLo) + u * (F(q) - F(yLo)));
  }
  return std::clamp(flux / (kPi * (1.0 - u / 3.0)), 0.0, 1.0);
}

} // namespace

ShadowMethod parseShadowMethod(const std::string& name) {
  if (name == "dp") return ShadowMethod::DynamicProgramming;
  if (name == "uniform") return ShadowMethod::Uniform;
  if (name == "reference") return ShadowMethod::Reference;
  if (name == "cells") return ShadowMethod::Cells;
  throw std::invalid_argument("unknown shadow method '" + name + "' (expected dp, uniform, cells or reference)");
}

const char* shadowMethodName(ShadowMethod m) {
  switch (m) {
    case ShadowMethod::DynamicProgramming: return "dp";
    case ShadowMethod::Uniform: return "uniform";
    case ShadowMethod::Reference: return "reference";
    case ShadowMethod::Cells: return "cells";
  }
  return "?";
}

void ShadowOptions::validate() const {
  if (levels < 1 || levels > 30) throw std::invalid_argument("levels (N') must be 1..30");
  if (uniformSteps < 1) throw std::invalid_argument("uniform steps must be >= 1");
  if (referenceStrips < 2) throw std::invalid_argument("reference strips must be >= 2");
  if (!(referenceStepTexels > 0.0) || referenceStepTexels > 16.0)
    throw std::invalid_argument("reference step must be in (0, 16] texels");
  if (!(fromTexels > 0.0 && toTexels > fromTexels)) throw std::invalid_argument("the footprint searched must run from > 0 to further on");
  if (!(windowRadii >= 1.0 && windowRadii <= 100.0)) throw std::invalid_argument("the search window must be 1..100 solar radii");
}

Horizon horizonTowardsSun(const HeightField& f, const MaximumMipmap& mip, int i, int j, const SunDisc& sun,
                          const ShadowOptions& o) {
  return horizonTowardsSunAt(f, mip, glm::dvec2(i, j), f.receiverHeight(i, j), sun, o);
}

Horizon horizonTowardsSunAt(const HeightField& f, const MaximumMipmap& mip, glm::dvec2 grid, double heightM,
                            const SunDisc& sun, const ShadowOptions& o) {
  const double r = sun.angularRadiusRad * o.windowRadii;
  // The lower edge decides where the search may stop; the Sun's elevation comes with the plane.
  const Profile probe(f, mip, grid, heightM, sun.direction, 0.0);
  Horizon h;
  h.sunElevationRad = probe.sunElevation;
  if (probe.degenerate) {
    h.degenerate = true;
    h.horizonElevationRad = -kInf;
    return h;
  }
  const double lo = probe.sunElevation - r, hi = probe.sunElevation + r;
  Profile p(f, mip, grid, heightM, sun.direction, lo);
  p.sEnd = std::min(p.sEnd, o.toTexels);
  if (o.method == ShadowMethod::Uniform)
    h.horizonElevationRad = uniformSearch(p, o.uniformSteps, o.fromTexels, hi, h.samples);
  else if (o.method == ShadowMethod::Cells)
    h.horizonElevationRad = cellSearch(p, o.fromTexels, hi, h.samples);
  else
    h.horizonElevationRad = MipmapSearch(p, lo, hi).run(o.levels, o.fromTexels, h.samples);
  return h;
}

double discFractionAboveHorizon(const Horizon& h, const SunDisc& sun) {
  if (h.degenerate) return h.sunElevationRad > 0.0 ? 1.0 : 0.0;
  // Eq. 6: the horizon's chord lies d disc radii below the disc's centre.
  return discFractionForOffset((h.sunElevationRad - h.horizonElevationRad) / sun.angularRadiusRad, sun);
}

double discFractionForOffset(double d, const SunDisc& sun) {
  return sun.limbDarkening > 0.0 ? eclipse::visibleFractionAboveHorizonLimbDarkened(d, sun.limbDarkening)
                                 : eclipse::visibleFractionAboveHorizon(d);
}

double visibleFraction(const HeightField& f, const MaximumMipmap& mip, int i, int j, const SunDisc& sun,
                       const ShadowOptions& o, long long* samples) {
  long long n = 0;
  double fraction;
  if (o.method == ShadowMethod::Reference) {
    fraction = referenceFraction(f, mip, i, j, sun, o, n);
  } else {
    const Horizon h = horizonTowardsSun(f, mip, i, j, sun, o);
    n = h.samples;
    fraction = discFractionAboveHorizon(h, sun);
  }
  if (samples) *samples = n;
  return fraction;
}

namespace {
void validateMapInputs(const HeightField& f, const SunDisc& sun, const ShadowOptions& o) {
  f.validate();
  o.validate();
  if (!(sun.angularRadiusRad > 0.0) || sun.angularRadiusRad > 0.5)
    throw std::invalid_argument("sun angular radius must be in (0, 0.5] rad");
  if (!(sun.limbDarkening >= 0.0 && sun.limbDarkening <= 1.0)) throw std::invalid_argument("limb darkening must be in [0, 1]");
  if (!(glm::length(sun.direction) > 0.0) || !std::isfinite(glm::length(sun.direction)))
    throw std::invalid_argument("sun direction must be a finite non-zero vector");
}

/// out[j * width + i] = atSample(i, j, samples looked at) for every sample, rows in parallel.
template <class T, class AtSample>
std::vector<T> everySample(const HeightField& f, const std::function<void(double)>& progress, ShadowMapStats* stats,
                           AtSample atSample) {
  std::vector<T> out(static_cast<std::size_t>(f.width) * f.height);
  std::atomic<int> rowsDone{0};
  long long total = 0;
  ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : total)
  for (int j = 0; j < f.height; ++j) {
    long long rowSamples = 0;
    errors.run([&] {
      for (int i = 0; i < f.width; ++i) {
        long long n = 0;
        out[static_cast<std::size_t>(j) * f.width + i] = atSample(i, j, n);
        rowSamples += n;
      }
    });
    total += rowSamples;
    const int done = ++rowsDone;
    if (progress && omp_get_thread_num() == 0) progress(double(done) / f.height);
  }
  errors.rethrow();
  if (stats) stats->samples = total;
  return out;
}
} // namespace

std::vector<double> visibleFractionMap(const HeightField& f, const MaximumMipmap& mip, const SunDisc& sun,
                                       const ShadowOptions& o, const std::function<void(double)>& progress,
                                       ShadowMapStats* stats) {
  validateMapInputs(f, sun, o);
  return everySample<double>(f, progress, stats, [&](int i, int j, long long& n) {
    return visibleFraction(f, mip, i, j, sun, o, &n);
  });
}

std::vector<Horizon> horizonMap(const HeightField& f, const MaximumMipmap& mip, const SunDisc& sun,
                                const ShadowOptions& o, const std::function<void(double)>& progress,
                                ShadowMapStats* stats) {
  validateMapInputs(f, sun, o);
  if (o.method == ShadowMethod::Reference)
    throw std::invalid_argument("horizonMap: the reference method has no single horizon");
  return everySample<Horizon>(f, progress, stats, [&](int i, int j, long long& n) {
    const Horizon h = horizonTowardsSun(f, mip, i, j, sun, o);
    n = h.samples;
    return h;
  });
}

} // namespace umbra::terrain
