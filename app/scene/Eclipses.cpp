#include "scene/Eclipses.hpp"

#include "scene/DeltaT.hpp"
#include "scene/EclipseEphemerides.hpp"
#include "scene/Ephemeris.hpp"

#include "ShadowLut.hpp"  // kLightSpeedMps
#include "ShadowMapping.hpp"  // outlinePolarRatio, outlineRadiusFactor
#include "SolarDisc.hpp"  // visibleFractionUniform

#include <erfa.h>
#include <glm/geometric.hpp>
#include <glm/glm.hpp>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <regex>
#include <set>
#include <stdexcept>

namespace umbra::scene {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kArcsec = kPi / (180.0 * 3600.0);
constexpr double kAuM = 149597870700.0;
constexpr double kDayS = 86400.0;
constexpr double kSynodicMonthDays = 29.530588861;
constexpr double kNewMoonJd = 2451550.09766;  ///< the mean new moon of 2000-01-06 (Meeus, ch. 49)
/// The span the search takes: ELP and ERFA's series are summed this far out, Delta T
/// extrapolated (and the Saros numbering holds) within a few thousand years of today.
constexpr double kFirstJd = 625673.5;   // -3000-01-01
constexpr double kLastJd = 3547272.5;   // +5000-01-01

/// ELP's Moon summed at every call and ERFA's Earth: for a single instant.
struct PreciseEphemerides {
  static glm::dvec3 moonGeocentricM(double tt) { return moonGeocentricElpM(tt); }
  static glm::dvec3 earthHeliocentricM(double tt) { return scene::earthHeliocentricM(tt); }
};

/// Meeus' Moon and ERFA's Earth, for the quick screen of every syzygy.
struct QuickEphemerides {
  static glm::dvec3 moonGeocentricM(double tt) { return moonGeocentricMeeusM(tt); }
  static glm::dvec3 earthHeliocentricM(double tt) { return scene::earthHeliocentricM(tt); }
};

/// The Sun and the Moon as seen from the Earth's centre at a TT instant (GCRS axes, m):
/// each where it was one light time back, seen from where the Earth is then (light time
/// and aberration together, as Besselian elements take them: the aberration moves the
/// Moon by ~40 km, the Earth's 1.3 s of orbit).
struct Apparent {
  glm::dvec3 moonM, sunM;
};

template <class E>
Apparent apparentAt(const E& ephemerides, double tt) {
  Apparent a;
  const glm::dvec3 m0 = ephemerides.moonGeocentricM(tt);
  a.moonM = ephemerides.moonGeocentricM(tt - glm::length(m0) / eclipse::kLightSpeedMps / kDayS);
  const glm::dvec3 e0 = ephemerides.earthHeliocentricM(tt);
  a.sunM = -ephemerides.earthHeliocentricM(tt - glm::length(e0) / eclipse::kLightSpeedMps / kDayS);
  return a;
}

// ---------------------------------------------------------------------------------------
// The Earth's orientation over one eclipse: GCRS -> CIRS (precession-nutation, fixed over
// the eclipse's hours: the pole moves by milliarcseconds), then the Earth Rotation Angle
// at UT1. Polar motion (< 0.5 arcsecond, 15 m) is left out.

class EarthOrientation {
public:
  EarthOrientation(double tt, double deltaTSeconds) : deltaTDays(deltaTSeconds / kDayS) { eraC2i06a(tt, 0.0, c2i); }
  /// ITRS components of a GCRS vector at TT instant `tt`.
  glm::dvec3 toEarthFixed(const glm::dvec3& v, double tt) const {
    double r[3][3], c[3][3];
    std::copy(&c2i[0][0], &c2i[0][0] + 9, &c[0][0]);  // ERFA 2.0 takes no const
    eraCr(c, r);
    eraRz(eraEra00(tt - deltaTDays, 0.0), r);
    double p[3] = {v.x, v.y, v.z}, q[3];
    eraRxp(r, p, q);
    return {q[0], q[1], q[2]};
  }

private:
  double c2i[3][3];
  double deltaTDays;
};

/// Seconds of Delta T and their source at a TT instant, or the search's fixed value.
DeltaT deltaTFor(const EclipseSearch& search, double tt) {
  if (search.deltaTSeconds) return DeltaT{*search.deltaTSeconds, "given", true};
  return deltaTAtYear(decimalYear(tt));
}

// ---------------------------------------------------------------------------------------
// Minimum and roots on a bracket.

/// The argument of a unimodal function's minimum on [a, b], to `tolerance` days (1 ms).
template <class F>
double argMin(F f, double a, double b, double tolerance = 1e-8) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = f(c), fd = f(d);
  while (b - a > tolerance) {
    if (fc < fd) {
      b = d, d = c, fd = fc;
      c = b - g * (b - a), fc = f(c);
    } else {
      a = c, c = d, fc = fd;
      d = a + g * (b - a), fd = f(d);
    }
  }
  return 0.5 * (a + b);
}

/// The root of f on [a, b] where f(a) and f(b) differ in sign (bisection to 1e-8 day), or
/// none when they do not.
template <class F>
std::optional<double> root(F f, double a, double b) {
  double fa = f(a);
  const double fb = f(b);
  if (!(fa * fb <= 0.0)) return std::nullopt;
  while (b - a > 1e-8) {
    const double m = 0.5 * (a + b), fm = f(m);
    if ((fm <= 0.0) == (fa <= 0.0)) a = m, fa = fm;
    else b = m;
  }
  return 0.5 * (a + b);
}

// ---------------------------------------------------------------------------------------
// Solar eclipses: the fundamental plane (Besselian elements), lengths in Earth equatorial
// radii, vectors in the Earth-fixed frame.

struct Fundamental {
  glm::dvec3 moon;           ///< the Moon's centre
  glm::dvec3 ex, ey, ez;     ///< the plane's axes: ez along the shadow's axis towards the Sun
  double x = 0.0, y = 0.0, z = 0.0;  ///< the Moon's centre in them
  double tanF1 = 0.0, tanF2 = 0.0;   ///< the penumbral and umbral cones' half-angles
  double l1 = 0.0, l2 = 0.0;         ///< their radii on the plane (l2 < 0: the umbra's, total)
  double rho1 = 1.0;                 ///< the Earth's outline's minor semi-axis on the plane
  /// The axis' distance from the Earth's outline's centre, the outline made a unit circle.
  double scaledDistance() const { return std::hypot(x, y / rho1); }
};

struct SolarContext {
  const EclipseConstants& k;
  EclipseEphemerides<> ephemerides;
  EarthOrientation earth;
  double sunRadiusM;

  Fundamental at(double tt) const {
    const Apparent a = apparentAt(ephemerides, tt);
    const double re = k.earthEquatorialRadiusM;
    Fundamental f;
    f.moon = earth.toEarthFixed(a.moonM, tt) / re;
    const glm::dvec3 sun = earth.toEarthFixed(a.sunM, tt) / re;
    const glm::dvec3 g = sun - f.moon;
    const double gLength = glm::length(g);
    f.ez = g / gLength;
    f.ex = glm::normalize(glm::cross(glm::dvec3(0.0, 0.0, 1.0), f.ez));
    f.ey = glm::cross(f.ez, f.ex);
    f.x = glm::dot(f.moon, f.ex), f.y = glm::dot(f.moon, f.ey), f.z = glm::dot(f.moon, f.ez);
    const double rs = sunRadiusM / re;
    const double sinF1 = (rs + k.moonRadiusPenumbral) / gLength, sinF2 = (rs - k.moonRadiusUmbral) / gLength;
    const double cosF1 = std::sqrt(1.0 - sinF1 * sinF1), cosF2 = std::sqrt(1.0 - sinF2 * sinF2);
    f.tanF1 = sinF1 / cosF1, f.tanF2 = sinF2 / cosF2;
    f.l1 = f.z * f.tanF1 + k.moonRadiusPenumbral / cosF1;
    f.l2 = f.z * f.tanF2 - k.moonRadiusUmbral / cosF2;
    f.rho1 = eclipse::outlinePolarRatio(f.ez.z, k.earthFlattening);
    return f;
  }

  /// Where the axis meets the ellipsoid on the Sun's side (Earth radii), if it does.
  std::optional<glm::dvec3> axisOnGround(const Fundamental& f) const {
    const double zScale = 1.0 / (1.0 - k.earthFlattening);
    const glm::dvec3 o(f.moon.x, f.moon.y, f.moon.z * zScale), d(f.ez.x, f.ez.y, f.ez.z * zScale);
    const double a = glm::dot(d, d), b = 2.0 * glm::dot(o, d), c = glm::dot(o, o) - 1.0;
    const double disc = b * b - 4.0 * a * c;
    if (disc < 0.0) return std::nullopt;
    const double s = (-b + std::sqrt(disc)) / (2.0 * a);
    return f.moon + s * f.ez;
  }
};

/// The Sun's radius in metres for the constants' angular radius at 1 au.
double sunRadiusM(const EclipseConstants& k) { return std::tan(k.sunRadiusArcsecAt1Au * kArcsec) * kAuM; }

/// The fundamental plane over the 0.35 day either side of `tt`.
SolarContext solarContext(const EclipseConstants& k, double tt, double deltaTSeconds) {
  return SolarContext{k, EclipseEphemerides<>(tt, 0.35), EarthOrientation(tt, deltaTSeconds), sunRadiusM(k)};
}

/// An observer's place against the shadow: distance from the axis (delta), the penumbra's
/// and the umbra's radii at its plane (L1, L2), Earth radii.
struct Local {
  double delta = 0.0, L1 = 0.0, L2 = 0.0;
  double magnitude() const { return (L1 - delta) / (L1 + L2); }
  /// < 0 inside the umbra or antumbra.
  double centralDepth() const { return delta - std::abs(L2); }
};

Local localAt(const Fundamental& f, const glm::dvec3& observer) {
  const glm::dvec3 r = observer - f.moon;
  const double along = glm::dot(r, f.ez);
  const double zeta = glm::dot(observer, f.ez);
  Local l;
  l.delta = glm::length(r - along * f.ez);
  l.L1 = f.l1 - zeta * f.tanF1;
  l.L2 = f.l2 - zeta * f.tanF2;
  return l;
}

/// The ellipsoid's point nearest to `p` (Earth radii in and out), through geodetic
/// coordinates.
glm::dvec3 ontoGround(const glm::dvec3& p, const EclipseConstants& k) {
  const double re = k.earthEquatorialRadiusM;
  double xyz[3] = {p.x * re, p.y * re, p.z * re};
  double lon = 0.0, lat = 0.0, h = 0.0, out[3];
  eraGc2gde(re, k.earthFlattening, xyz, &lon, &lat, &h);
  eraGd2gce(re, k.earthFlattening, lon, lat, 0.0, out);
  return glm::dvec3(out[0], out[1], out[2]) / re;
}

glm::dvec3 geodeticUp(const glm::dvec3& p, const EclipseConstants& k, double* latDeg = nullptr, double* lonDeg = nullptr) {
  const double re = k.earthEquatorialRadiusM;
  double xyz[3] = {p.x * re, p.y * re, p.z * re};
  double lon = 0.0, lat = 0.0, h = 0.0;
  eraGc2gde(re, k.earthFlattening, xyz, &lon, &lat, &h);
  if (latDeg) *latDeg = lat * 180.0 / kPi;
  if (lonDeg) *lonDeg = lon * 180.0 / kPi;
  return {std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat)};
}

/// The span of totality or annularity at a fixed place near `tt` (its C2 and C3), if any.
std::optional<std::pair<double, double>> centralPhase(const SolarContext& c, const glm::dvec3& place, double tt) {
  const auto depth = [&](double t) { return localAt(c.at(t), place).centralDepth(); };
  const double window = 0.02;  // days: 29 min, more than any eclipse's central phase
  const double mid = argMin(depth, tt - window, tt + window);
  if (!(depth(mid) < 0.0)) return std::nullopt;
  const auto c2 = root(depth, mid - window, mid), c3 = root(depth, mid, mid + window);
  if (!c2 || !c3) return std::nullopt;
  return std::make_pair(*c2, *c3);
}

/// The point `arc` (radians) from `place` along the great circle towards the unit tangent
/// `across`, on the ground (Earth radii).
glm::dvec3 alongGround(const glm::dvec3& place, const glm::dvec3& across, double arc, const EclipseConstants& k) {
  return ontoGround(std::cos(arc) * place + std::sin(arc) * glm::length(place) * across, k);
}

/// The least over time, near `tt`, of a place's depth in the umbra (central) or the
/// penumbra, and when: < 0 when the place sees that phase with the Sun up. The Sun below
/// the horizon adds to the depth, so that only the place's Sun-up part of the eclipse counts.
struct Deepest {
  double depth = 0.0, tt = 0.0;
};

Deepest deepest(const SolarContext& c, const glm::dvec3& place, double tt, bool central) {
  const glm::dvec3 up = geodeticUp(place, c.k);
  const double window = central ? 0.01 : 0.1;  // days: the central phase passes in minutes, the partial in hours
  const auto depth = [&](double t) {
    const Fundamental f = c.at(t);
    const Local l = localAt(f, place);
    return (central ? l.centralDepth() : l.delta - l.L1) + 10.0 * std::max(0.0, -glm::dot(up, f.ez));
  };
  const double t = argMin(depth, tt - window, tt + window, 1e-6);  // 0.1 s: the depth is flat there
  return {depth(t), t};
}

/// How far (radians of arc) from `place` towards `across` the umbra's (central) or the
/// penumbra's limit lies: where the deepest depth turns positive, to 0.13 km. NaN when it
/// lies beyond `maxArc`.
double limitArc(const SolarContext& c, const glm::dvec3& place, const glm::dvec3& across, double tt, bool central,
                double maxArc) {
  const auto inside = [&](double arc) { return deepest(c, alongGround(place, across, arc, c.k), tt, central).depth < 0.0; };
  double in = 0.0, out = maxArc;
  if (inside(out)) return std::numeric_limits<double>::quiet_NaN();
  while (out - in > 2e-5) {
    const double m = 0.5 * (in + out);
    (inside(m) ? in : out) = m;
  }
  return 0.5 * (in + out);
}

/// The unit tangent at `place` to the left of the central line's motion at `tt` (north of
/// it for a shadow moving east), or none where the axis leaves the ground.
std::optional<glm::dvec3> acrossCentralLine(const SolarContext& c, const glm::dvec3& place, double tt) {
  const double dt = 10.0 / kDayS;
  const auto before = c.axisOnGround(c.at(tt - dt)), after = c.axisOnGround(c.at(tt + dt));
  if (!before || !after) return std::nullopt;
  return glm::normalize(glm::cross(geodeticUp(place, c.k), *after - *before));
}

/// The path's width through `place` (on the central line at `tt`), across the line (Earth
/// radii); NaN when an edge cannot be found.
double pathWidth(const SolarContext& c, const glm::dvec3& place, double tt) {
  const auto across = acrossCentralLine(c, place, tt);
  if (!across) return std::numeric_limits<double>::quiet_NaN();
  const double maxArc = 0.6;  // 3800 km: wider than any path
  return limitArc(c, place, *across, tt, true, maxArc) + limitArc(c, place, -*across, tt, true, maxArc);
}

// ---------------------------------------------------------------------------------------
// Lunar eclipses: angles at the Earth's centre.

struct LunarAt {
  double separation = 0.0;        ///< of the Moon's centre from the shadow's axis (rad)
  double penumbra = 0.0, umbra = 0.0, moonRadius = 0.0;  ///< angular radii (rad)
  double axisDistance = 0.0;      ///< the Moon's centre from the axis, Earth radii; + north
};

/// The Earth's shadow at the Moon. With a pole (the true pole, GCRS) the Earth's outline is
/// the ellipse the Moon sees, its radius taken towards the Moon's centre, where the contacts
/// and the magnitudes are measured; without, a sphere as the rules are published.
template <class E>
LunarAt lunarAt(const E& ephemerides, double tt, const EclipseSearch& s, const glm::dvec3* pole = nullptr) {
  const Apparent a = apparentAt(ephemerides, tt);
  const EclipseConstants& k = s.constants;
  const double re = k.earthEquatorialRadiusM;
  const double moonDistance = glm::length(a.moonM), sunDistance = glm::length(a.sunM);
  const glm::dvec3 axis = -a.sunM / sunDistance, m = a.moonM / moonDistance;
  const glm::dvec3 offset = a.moonM - glm::dot(a.moonM, axis) * axis;
  LunarAt l;
  l.separation = std::atan2(glm::length(glm::cross(m, axis)), glm::dot(m, axis));
  const double moonParallax = std::asin(re / moonDistance), sunParallax = std::asin(re / sunDistance);
  const double sunRadius = std::atan(k.sunRadiusArcsecAt1Au * kArcsec * kAuM / sunDistance);
  // The outline's radius towards the Moon over the equatorial radius (1 at the equator,
  // 1 - f cos^2(delta) or so towards the projected pole).
  const double outline = pole ? eclipse::outlineRadiusFactor(axis, offset, {*pole, k.earthFlattening}) : 0.0;
  switch (s.lunarRule) {
  case LunarShadowRule::Danjon: {
    const double f = pole ? (1.0 + 1.0 / 85.0) * outline : 1.01;
    l.penumbra = f * moonParallax + sunRadius + sunParallax;
    l.umbra = f * moonParallax - sunRadius + sunParallax;
    break;
  }
  case LunarShadowRule::Chauvenet: {
    const double f = pole ? outline : 0.998340;
    l.penumbra = 1.02 * (f * moonParallax + sunRadius + sunParallax);
    l.umbra = 1.02 * (f * moonParallax - sunRadius + sunParallax);
    break;
  }
  case LunarShadowRule::Physical: {
    const double meanRadius = re * (1.0 - k.earthFlattening / 3.0);  // the sphere of equal volume, nearly
    const double f = (pole ? outline : meanRadius / re) + s.physicalEnlargementM / re;
    l.penumbra = f * moonParallax + sunRadius + sunParallax;
    l.umbra = f * moonParallax - sunRadius + sunParallax;
    break;
  }
  }
  l.moonRadius = std::asin(k.moonRadiusPenumbral * re / moonDistance);
  l.axisDistance = glm::length(offset) / re * (offset.z < 0.0 ? -1.0 : 1.0);
  return l;
}

// ---------------------------------------------------------------------------------------
// The search: every syzygy in the span, a quick screen with Meeus' Moon, then the
// eclipse's circumstances with ELP's.

/// The ecliptic longitude (J2000) of a GCRS vector.
double eclipticLongitude(const glm::dvec3& v) {
  return std::atan2(std::cos(kObliquityJ2000Rad) * v.y + std::sin(kObliquityJ2000Rad) * v.z, v.x);
}

/// The instant near `tt` when the Moon's longitude is the Sun's (+ offset), Meeus' Moon.
double syzygy(double tt, double offsetRad) {
  const QuickEphemerides quick;
  const double meanRate = 2.0 * kPi / kSynodicMonthDays;  // rad/day of elongation
  for (int i = 0; i < 8; ++i) {
    const Apparent a = apparentAt(quick, tt);
    const double e = std::remainder(eclipticLongitude(a.moonM) - eclipticLongitude(a.sunM) - offsetRad, 2.0 * kPi);
    tt -= e / meanRate;
    if (std::abs(e) < 1e-7) break;
  }
  return tt;
}

/// The Saros series of the eclipse at lunation `index` (new moons counted from 2000-01-06;
/// a lunar eclipse takes its full moon's), from a reference eclipse: eclipses a saros (223
/// lunations) apart share a series, an inex (358) apart are in consecutive ones.
int sarosSeries(long index, long referenceIndex, int referenceSeries) {
  const long dn = index - referenceIndex;
  // b = dn * 358^-1 (mod 223); 358^-1 = 38 (mod 223). Of the b that fit, the one with the
  // eclipse nearest the reference's place in its series (series run ~70 saroses).
  long b = ((38 * (dn % 223)) % 223 + 223) % 223;
  const long centre = std::lround(static_cast<double>(dn) / 358.0);
  while (b < centre - 111) b += 223;
  while (b > centre + 111) b -= 223;
  return referenceSeries + static_cast<int>(b);
}

long lunationIndex(double tt, double offsetMonths) {
  return std::lround((tt - kNewMoonJd) / kSynodicMonthDays - offsetMonths);
}

void checkSpan(const EclipseSearch& s) {
  if (s.lunarRule == LunarShadowRule::Physical && !(s.physicalEnlargementM >= 0.0 && s.physicalEnlargementM < 1e6))
    throw std::invalid_argument("eclipse search: the physical edge's enlargement must be within 0..1000 km");
  if (!(std::isfinite(s.fromTt) && std::isfinite(s.toTt)))
    throw std::invalid_argument("eclipse search: the span's ends are not finite");
  if (!(s.toTt >= s.fromTt))
    throw std::invalid_argument("eclipse search: the span ends before it starts (" + formatJulianDate(s.fromTt, 0) +
                                " to " + formatJulianDate(s.toTt, 0) + ")");
  if (s.fromTt < kFirstJd || s.toTt > kLastJd)
    throw std::invalid_argument("eclipse search: the span " + formatJulianDate(s.fromTt, 0) + " to " +
                                formatJulianDate(s.toTt, 0) + " leaves -3000..+5000, where the ephemerides hold");
  if (s.deltaTSeconds && !std::isfinite(*s.deltaTSeconds))
    throw std::invalid_argument("eclipse search: Delta T is not finite");
}

/// The syzygies of the span (offset 0: new moons; 0.5: full moons), screened with
/// Meeus' Moon by `candidate`, then analysed in parallel by `analyse` (ELP's Moon).
template <class Eclipse, class Candidate, class Analyse>
std::vector<Eclipse> searchSyzygies(const EclipseSearch& s, double offsetMonths, Candidate candidate, Analyse analyse) {
  checkSpan(s);
  const long first = static_cast<long>(std::floor((s.fromTt - kNewMoonJd) / kSynodicMonthDays - offsetMonths)) - 1;
  const long last = static_cast<long>(std::ceil((s.toTt - kNewMoonJd) / kSynodicMonthDays - offsetMonths)) + 1;
  std::vector<double> seeds;
  for (long n = first; n <= last; ++n) {
    const double t = syzygy(kNewMoonJd + (n + offsetMonths) * kSynodicMonthDays, 2.0 * kPi * offsetMonths);
    if (candidate(t)) seeds.push_back(t);
  }
  std::vector<std::optional<Eclipse>> found(seeds.size());
  std::atomic<long> done{0};
  const long total = static_cast<long>(seeds.size());
#pragma omp parallel for schedule(dynamic)
  for (long i = 0; i < total; ++i) {
    found[static_cast<size_t>(i)] = analyse(seeds[static_cast<size_t>(i)]);
    const long d = ++done;
#ifdef _OPENMP
    if (omp_get_thread_num() == 0)
#endif
      if (s.progress) s.progress(static_cast<double>(d) / static_cast<double>(total));
  }
  std::vector<Eclipse> out;
  for (auto& e : found)
    if (e && e->greatestTt >= s.fromTt && e->greatestTt <= s.toTt) out.push_back(*e);
  if (s.progress) s.progress(1.0);
  return out;
}

}  // namespace

const char* typeName(SolarEclipseType type) {
  switch (type) {
  case SolarEclipseType::Partial: return "partial";
  case SolarEclipseType::Annular: return "annular";
  case SolarEclipseType::Total: return "total";
  case SolarEclipseType::Hybrid: return "hybrid";
  }
  return "";
}

const char* typeName(LunarEclipseType type) {
  switch (type) {
  case LunarEclipseType::Penumbral: return "penumbral";
  case LunarEclipseType::Partial: return "partial";
  case LunarEclipseType::Total: return "total";
  }
  return "";
}

std::vector<SolarEclipse> findSolarEclipses(const EclipseSearch& s) {
  const EclipseConstants& k = s.constants;
  const QuickEphemerides quick;
  // Screen: the axis within 1.62 Earth radii of the centre at conjunction (the penumbra
  // reaches 1.58 at most, and the least distance is within 1 % of the conjunction's).
  const auto candidate = [&](double t) {
    const Apparent a = apparentAt(quick, t);
    const glm::dvec3 ez = glm::normalize(a.sunM - a.moonM);
    return glm::length(a.moonM - glm::dot(a.moonM, ez) * ez) / k.earthEquatorialRadiusM < 1.62;
  };
  const long referenceIndex = lunationIndex(2457987.2686, 0.0);  // 2017-08-21, Saros 145
  const auto analyse = [&](double seed) -> std::optional<SolarEclipse> {
    const DeltaT dt = deltaTFor(s, seed);
    const SolarContext c = solarContext(k, seed, dt.seconds);
    const double tg = argMin([&](double t) { const Fundamental f = c.at(t); return f.x * f.x + f.y * f.y; },
                             seed - 0.2, seed + 0.2);
    const Fundamental f = c.at(tg);
    const double r1 = f.scaledDistance();
    if (!(r1 < 1.0 + f.l1)) return std::nullopt;
    SolarEclipse e;
    e.greatestTt = tg;
    e.deltaTSeconds = dt.seconds;
    e.deltaTSource = dt.source;
    e.gamma = std::hypot(f.x, f.y) * (f.y < 0.0 ? -1.0 : 1.0);
    e.saros = sarosSeries(lunationIndex(tg, 0.0), referenceIndex, 145);
    glm::dvec3 point;
    if (const auto ground = c.axisOnGround(f); ground && r1 < 1.0) {
      e.central = true;
      point = *ground;
      const Local l = localAt(f, point);
      e.magnitude = (l.L1 - l.L2) / (l.L1 + l.L2);
      e.type = l.L2 < 0.0 ? SolarEclipseType::Total : SolarEclipseType::Annular;
      if (e.type == SolarEclipseType::Total) {
        // Hybrid: annular where the central line meets the Earth's limb (farther from the Moon).
        const auto edge = [&](double t) { return c.at(t).scaledDistance() - 1.0; };
        for (const auto& end : {root(edge, tg - 0.2, tg), root(edge, tg, tg + 0.2)})
          if (end && c.at(*end).l2 > 0.0) e.type = SolarEclipseType::Hybrid;
      }
      if (const auto phase = centralPhase(c, point, tg)) e.centralDurationS = (phase->second - phase->first) * kDayS;
      const double width = pathWidth(c, point, tg);
      if (std::isfinite(width)) e.pathWidthKm = width * k.earthEquatorialRadiusM / 1000.0;
    } else {
      // The point of the Earth's outline nearest the axis, where the Sun is on the horizon.
      const glm::dvec3 towards = glm::normalize(f.x * f.ex + f.y * f.ey);
      const double b2 = (1.0 - k.earthFlattening) * (1.0 - k.earthFlattening);
      const glm::dvec3 n(towards.x, towards.y, towards.z * b2);
      point = n / std::sqrt(towards.x * towards.x + towards.y * towards.y + towards.z * towards.z * b2);
      const double delta = r1 - 1.0;
      e.magnitude = (f.l1 - delta) / (f.l1 + f.l2);
      if (r1 < 1.0 + std::abs(f.l2)) e.type = f.l2 < 0.0 ? SolarEclipseType::Total : SolarEclipseType::Annular;
    }
    const glm::dvec3 up = geodeticUp(point, k, &e.latitudeDeg, &e.longitudeDeg);
    e.sunAltitudeDeg = std::asin(std::clamp(glm::dot(up, f.ez), -1.0, 1.0)) * 180.0 / kPi;
    // Contacts: the axis' scaled distance against the cones' radii, on either side of greatest.
    const auto contacts = [&](auto target, Contact& first, Contact& last) {
      const auto g = [&](double t) { const Fundamental q = c.at(t); return q.scaledDistance() - target(q); };
      if (!(g(tg) < 0.0)) return;
      first = root(g, tg - 0.3, tg), last = root(g, tg, tg + 0.3);
    };
    contacts([](const Fundamental& q) { return 1.0 + q.l1; }, e.p1, e.p4);
    contacts([](const Fundamental& q) { return q.l1 - 1.0; }, e.p2, e.p3);
    contacts([](const Fundamental& q) { return 1.0 + std::abs(q.l2); }, e.u1, e.u4);
    contacts([](const Fundamental& q) { return 1.0 - std::abs(q.l2); }, e.u2, e.u3);
    return e;
  };
  return searchSyzygies<SolarEclipse>(s, 0.0, candidate, analyse);
}

std::vector<LunarEclipse> findLunarEclipses(const EclipseSearch& s) {
  const QuickEphemerides quick;
  const auto candidate = [&](double t) {
    const LunarAt l = lunarAt(quick, t, s);
    return l.separation < 1.04 * (l.penumbra + l.moonRadius);  // the least separation is within 1 % of this
  };
  const long referenceIndex = lunationIndex(2458327.3492, 0.5);  // 2018-07-27, Saros 129
  const auto analyse = [&](double seed) -> std::optional<LunarEclipse> {
    const EclipseEphemerides<> ephemerides(seed, 0.35);
    double npb[3][3];
    eraPnm06a(seed, 0.0, npb);  // its third row: the true pole of date in GCRS
    const glm::dvec3 pole(npb[2][0], npb[2][1], npb[2][2]);
    const auto at = [&](double t) { return lunarAt(ephemerides, t, s, s.oblateShadow ? &pole : nullptr); };
    const double tg = argMin([&](double t) { return at(t).separation; }, seed - 0.2, seed + 0.2);
    const LunarAt l = at(tg);
    LunarEclipse e;
    e.greatestTt = tg;
    e.penumbralMagnitude = (l.penumbra + l.moonRadius - l.separation) / (2.0 * l.moonRadius);
    e.umbralMagnitude = (l.umbra + l.moonRadius - l.separation) / (2.0 * l.moonRadius);
    if (!(e.penumbralMagnitude > 0.0)) return std::nullopt;
    e.type = e.umbralMagnitude >= 1.0 ? LunarEclipseType::Total
             : e.umbralMagnitude > 0.0 ? LunarEclipseType::Partial
                                       : LunarEclipseType::Penumbral;
    const DeltaT dt = deltaTFor(s, tg);
    e.deltaTSeconds = dt.seconds;
    e.deltaTSource = dt.source;
    e.gamma = l.axisDistance;
    e.saros = sarosSeries(lunationIndex(tg, 0.5), referenceIndex, 129);
    const auto contacts = [&](auto radius, Contact& first, Contact& last) {
      const auto g = [&](double t) { const LunarAt q = at(t); return q.separation - radius(q); };
      if (!(g(tg) < 0.0)) return;
      first = root(g, tg - 0.3, tg), last = root(g, tg, tg + 0.3);
    };
    contacts([](const LunarAt& q) { return q.penumbra + q.moonRadius; }, e.p1, e.p4);
    contacts([](const LunarAt& q) { return q.umbra + q.moonRadius; }, e.u1, e.u4);
    contacts([](const LunarAt& q) { return q.umbra - q.moonRadius; }, e.u2, e.u3);
    return e;
  };
  return searchSyzygies<LunarEclipse>(s, 0.5, candidate, analyse);
}

LocalSolarEclipse localSolarEclipse(const SolarEclipse& eclipse, const GeoPlace& place, const EclipseConstants& k) {
  if (!(std::abs(place.latitudeDeg) <= 90.0) || !std::isfinite(place.longitudeDeg) ||
      !(place.heightM >= -500.0 && place.heightM <= 100e3))
    throw std::invalid_argument("local eclipse: the place must have a latitude within -90..90 deg, a finite longitude and "
                                "a height within -500 m..100 km");
  const SolarContext c = solarContext(k, eclipse.greatestTt, eclipse.deltaTSeconds);
  const double re = k.earthEquatorialRadiusM;
  double xyz[3];
  if (eraGd2gce(re, k.earthFlattening, place.longitudeDeg * kPi / 180.0, place.latitudeDeg * kPi / 180.0, place.heightM,
                xyz) != 0)
    throw std::invalid_argument("local eclipse: the place is not on the Earth");
  const glm::dvec3 p = glm::dvec3(xyz[0], xyz[1], xyz[2]) / re;
  const glm::dvec3 up = geodeticUp(p, k);
  // East and north; at a pole any pair square to the vertical (azimuths then count from it).
  glm::dvec3 east = glm::cross(glm::dvec3(0.0, 0.0, 1.0), up);
  east = glm::length(east) > 1e-9 ? glm::normalize(east) : glm::dvec3(0.0, 1.0, 0.0);
  const glm::dvec3 north = glm::cross(up, east);
  const auto instant = [&](double t) {
    const glm::dvec3 sun = c.at(t).ez;
    LocalInstant i;
    i.tt = t;
    i.sunAltitudeDeg = std::asin(std::clamp(glm::dot(sun, up), -1.0, 1.0)) * 180.0 / kPi;
    i.sunAzimuthDeg = std::fmod(std::atan2(glm::dot(sun, east), glm::dot(sun, north)) * 180.0 / kPi + 360.0, 360.0);
    return i;
  };
  const auto local = [&](double t) { return localAt(c.at(t), p); };
  const double tg = eclipse.greatestTt;
  const double t = argMin([&](double u) { return local(u).delta; }, tg - 0.2, tg + 0.2);
  LocalSolarEclipse e;
  e.greatest = instant(t);
  const Local l = local(t);
  e.eclipsed = l.delta < l.L1;
  if (!e.eclipsed) return e;
  const bool central = l.delta < std::abs(l.L2);
  e.magnitude = central ? (l.L1 - l.L2) / (l.L1 + l.L2) : l.magnitude();
  const double sunRadius = 0.5 * (l.L1 + l.L2), moonRadius = 0.5 * (l.L1 - l.L2);
  e.obscuration = 1.0 - eclipse::visibleFractionUniform(moonRadius / sunRadius, l.delta / sunRadius);
  const auto contacts = [&](auto edge, std::optional<LocalInstant>& first, std::optional<LocalInstant>& last) {
    const auto g = [&](double u) { const Local q = local(u); return q.delta - edge(q); };
    if (const auto r = root(g, t - 0.2, t)) first = instant(*r);
    if (const auto r = root(g, t, t + 0.2)) last = instant(*r);
  };
  contacts([](const Local& q) { return q.L1; }, e.c1, e.c4);
  if (central) {
    e.phase = l.L2 < 0.0 ? SolarEclipseType::Total : SolarEclipseType::Annular;
    contacts([](const Local& q) { return std::abs(q.L2); }, e.c2, e.c3);
    if (e.c2 && e.c3) e.centralDurationS = (e.c3->tt - e.c2->tt) * kDayS;
  }
  return e;
}

SolarEclipsePath solarEclipsePath(const SolarEclipse& eclipse, double stepSeconds, const EclipseConstants& k) {
  if (!eclipse.central)
    throw std::invalid_argument(std::string("the ") + typeName(eclipse.type) + " eclipse of " +
                                formatJulianDate(eclipse.greatestTt, 0) + " TT is not central: it has no path");
  if (!(stepSeconds >= 1.0 && stepSeconds <= 3600.0))
    throw std::invalid_argument("eclipse path: the step must be within 1..3600 s");
  const SolarContext c = solarContext(k, eclipse.greatestTt, eclipse.deltaTSeconds);
  const double tg = eclipse.greatestTt;
  // The central line runs while the axis meets the Earth.
  const auto edge = [&](double t) { return c.at(t).scaledDistance() - 1.0; };
  const double start = root(edge, tg - 0.25, tg).value_or(tg), end = root(edge, tg, tg + 0.25).value_or(tg);
  const double step = stepSeconds / kDayS;
  std::vector<double> times;
  for (double t = start + 1e-6; t < end; t += step) times.push_back(t);  // 0.1 s in: the axis on the ground
  times.push_back(end - 1e-6);
  struct Sample {
    std::optional<CentralLinePoint> point;
    std::optional<glm::dvec3> north, south, northPenumbra, southPenumbra;
  };
  std::vector<Sample> samples(times.size());
  // A limit's point `arc` across the line; none where the band ends at sunrise or sunset
  // (the Sun on the horizon when the point sees the most of the eclipse) rather than at the
  // shadow's edge.
  const auto limitPoint = [&](const glm::dvec3& place, const glm::dvec3& across, double t, bool central,
                              double& arc) -> std::optional<glm::dvec3> {
    arc = limitArc(c, place, across, t, central, central ? 0.6 : 1.2);
    if (!std::isfinite(arc)) return std::nullopt;
    const glm::dvec3 q = alongGround(place, across, arc, c.k);
    if (glm::dot(geodeticUp(q, c.k), c.at(deepest(c, q, t, central).tt).ez) < 0.01) return std::nullopt;
    return q;
  };
#pragma omp parallel for schedule(dynamic)
  for (long i = 0; i < static_cast<long>(times.size()); ++i) {
    const double t = times[static_cast<size_t>(i)];
    const auto ground = c.axisOnGround(c.at(t));
    if (!ground) continue;
    Sample& s = samples[static_cast<size_t>(i)];
    CentralLinePoint point;
    point.tt = t;
    const glm::dvec3 up = geodeticUp(*ground, k, &point.place.latitudeDeg, &point.place.longitudeDeg);
    point.sunAltitudeDeg = std::asin(std::clamp(glm::dot(up, c.at(t).ez), -1.0, 1.0)) * 180.0 / kPi;
    if (const auto phase = centralPhase(c, *ground, t)) point.durationS = (phase->second - phase->first) * kDayS;
    if (const auto across = acrossCentralLine(c, *ground, t)) {
      double northArc = 0.0, southArc = 0.0, unused = 0.0;
      s.north = limitPoint(*ground, *across, t, true, northArc);
      s.south = limitPoint(*ground, -*across, t, true, southArc);
      s.northPenumbra = limitPoint(*ground, *across, t, false, unused);
      s.southPenumbra = limitPoint(*ground, -*across, t, false, unused);
      if (s.north && s.south) point.widthKm = (northArc + southArc) * k.earthEquatorialRadiusM / 1000.0;
    }
    s.point = point;
  }
  SolarEclipsePath path;
  const auto place = [&](const glm::dvec3& q) {
    GeoPlace g;
    geodeticUp(q, k, &g.latitudeDeg, &g.longitudeDeg);
    return g;
  };
  for (const Sample& s : samples) {
    if (s.point) path.centralLine.push_back(*s.point);
    if (s.north) path.northernLimit.push_back(place(*s.north));
    if (s.south) path.southernLimit.push_back(place(*s.south));
    if (s.northPenumbra) path.northernPenumbralLimit.push_back(place(*s.northPenumbra));
    if (s.southPenumbra) path.southernPenumbralLimit.push_back(place(*s.southPenumbra));
  }
  return path;
}

LunarShadowGeometry lunarShadowGeometry(double tt) {
  const Apparent a = apparentAt(PreciseEphemerides{}, tt);
  const glm::dvec3 axis = -glm::normalize(a.sunM);
  double npb[3][3];
  eraPnm06a(tt, 0.0, npb);  // GCRS -> true equator and equinox of date: its third row is the pole
  const glm::dvec3 pole(npb[2][0], npb[2][1], npb[2][2]);
  const glm::dvec3 ey = glm::normalize(pole - glm::dot(pole, axis) * axis);
  const glm::dvec3 ex = glm::cross(ey, axis);
  LunarShadowGeometry g;
  g.moonDistanceM = glm::dot(a.moonM, axis);
  g.sunDistanceM = glm::length(a.sunM);
  g.moonOffsetXM = glm::dot(a.moonM, ex);
  g.moonOffsetYM = glm::dot(a.moonM, ey);
  g.axisDeclinationRad = std::asin(std::clamp(glm::dot(axis, pole), -1.0, 1.0));
  return g;
}

double eclipseInstantUt(const std::string& date, const std::string& at) {
  static const std::regex kAt(R"(\s*(greatest|[PU][1-4])\s*(?:([+-])\s*(\d+(?:\.\d*)?)\s*(s|min|h))?\s*)");
  std::smatch m;
  if (!std::regex_match(at, m, kAt))
    throw std::invalid_argument("eclipse instant '" + at + "': expected greatest, P1..P4 or U1..U4, with an offset or "
                                "not (U2+10min, greatest-30s, P4+1h)");
  static const std::regex kDay(R"(\s*-?\d{1,5}-\d{2}-\d{2}\s*)");
  if (!std::regex_match(date, kDay)) throw std::invalid_argument("eclipse date '" + date + "': expected YYYY-MM-DD");
  const double day = parseUtDate(date);
  EclipseSearch search;
  search.fromTt = ttFromUt1(day);
  search.toTt = ttFromUt1(day + 1.0);
  const std::string name = m[1];
  Contact instant;
  double deltaT = 0.0;
  std::string kind;
  if (const auto solar = findSolarEclipses(search); !solar.empty()) {
    const SolarEclipse& e = solar.front();
    const std::map<std::string, Contact> contacts{{"greatest", e.greatestTt}, {"P1", e.p1}, {"P2", e.p2}, {"P3", e.p3},
                                                  {"P4", e.p4}, {"U1", e.u1}, {"U2", e.u2}, {"U3", e.u3}, {"U4", e.u4}};
    instant = contacts.at(name), deltaT = e.deltaTSeconds, kind = std::string("the ") + typeName(e.type) + " solar eclipse";
  } else if (const auto lunar = findLunarEclipses(search); !lunar.empty()) {
    const LunarEclipse& e = lunar.front();
    const std::map<std::string, Contact> contacts{{"greatest", e.greatestTt}, {"P1", e.p1}, {"U1", e.u1}, {"U2", e.u2},
                                                  {"U3", e.u3}, {"U4", e.u4}, {"P4", e.p4}};
    const auto c = contacts.find(name);
    instant = c == contacts.end() ? Contact{} : c->second;
    deltaT = e.deltaTSeconds, kind = std::string("the ") + typeName(e.type) + " lunar eclipse";
  } else {
    throw std::invalid_argument("no eclipse on " + date);
  }
  if (!instant) throw std::invalid_argument(kind + " of " + date + " has no " + name);
  double offsetS = 0.0;
  if (m[2].matched) {
    const double unit = m[4] == "h" ? 3600.0 : m[4] == "min" ? 60.0 : 1.0;
    offsetS = (m[2] == "-" ? -1.0 : 1.0) * std::stod(m[3]) * unit;
  }
  return ut1FromTt(*instant, deltaT) + offsetS / kDayS;
}

std::vector<std::vector<GeoPlace>> partialEclipseOutline(const SolarEclipse& eclipse, double stepDeg,
                                                         const EclipseConstants& k) {
  if (!(stepDeg >= 0.1 && stepDeg <= 10.0)) throw std::invalid_argument("eclipse outline: the step must be within 0.1..10 deg");
  const SolarContext c = solarContext(k, eclipse.greatestTt, eclipse.deltaTSeconds);
  // The plane every 30 s over the penumbra's time on the Earth (or 3 h either side of greatest):
  // near its least, a place's depth is flat, and 30 s moves it by 0.2 km at most.
  const double from = eclipse.p1.value_or(eclipse.greatestTt - 0.125) - 0.002;
  const double to = eclipse.p4.value_or(eclipse.greatestTt + 0.125) + 0.002;
  std::vector<Fundamental> planes;
  for (double t = from; t <= to; t += 30.0 / kDayS) planes.push_back(c.at(t));
  const double re = k.earthEquatorialRadiusM, deg = kPi / 180.0;
  // The place's least depth in the penumbra while the Sun is up (1 when it never is): < 0
  // where the partial eclipse is seen.
  const auto depth = [&](double latDeg, double lonDeg) {
    double xyz[3];
    eraGd2gce(re, k.earthFlattening, lonDeg * deg, latDeg * deg, 0.0, xyz);
    const glm::dvec3 p = glm::dvec3(xyz[0], xyz[1], xyz[2]) / re;
    const glm::dvec3 up(std::cos(latDeg * deg) * std::cos(lonDeg * deg), std::cos(latDeg * deg) * std::sin(lonDeg * deg),
                        std::sin(latDeg * deg));
    double least = 1.0;
    for (const Fundamental& f : planes)
      if (glm::dot(up, f.ez) >= 0.0) {
        const Local l = localAt(f, p);
        least = std::min(least, l.delta - l.L1);
      }
    return least;
  };
  const int nLat = static_cast<int>(std::lround(180.0 / stepDeg)) + 1, nLon = static_cast<int>(std::lround(360.0 / stepDeg));
  const double dLat = 180.0 / (nLat - 1), dLon = 360.0 / nLon;
  const auto latOf = [&](int i) { return -90.0 + i * dLat; };
  const auto lonOf = [&](int j) { return -180.0 + ((j % nLon + nLon) % nLon) * dLon; };
  std::vector<double> v(static_cast<size_t>(nLat) * nLon);
#pragma omp parallel for schedule(dynamic)
  for (int i = 0; i < nLat; ++i)
    for (int j = 0; j < nLon; ++j) v[static_cast<size_t>(i) * nLon + j] = depth(latOf(i), lonOf(j));
  const auto at = [&](int i, int j) { return v[static_cast<size_t>(i) * nLon + (j % nLon + nLon) % nLon]; };
  // Marching squares. An edge's id: 2 (i nLon + j) for (i,j)-(i,j+1), + 1 for (i,j)-(i+1,j).
  const auto hEdge = [&](int i, int j) { return 2L * (static_cast<long>(i) * nLon + (j % nLon + nLon) % nLon); };
  const auto vEdge = [&](int i, int j) { return hEdge(i, j) + 1; };
  std::map<long, std::vector<long>> links;  // edge -> the edges it is joined to
  const auto join = [&](long a, long b) { links[a].push_back(b), links[b].push_back(a); };
  for (int i = 0; i + 1 < nLat; ++i)
    for (int j = 0; j < nLon; ++j) {
      const bool a = at(i, j) < 0.0, b = at(i, j + 1) < 0.0, cc = at(i + 1, j + 1) < 0.0, d = at(i + 1, j) < 0.0;
      const int mask = a | (b << 1) | (cc << 2) | (d << 3);
      if (mask == 0 || mask == 15) continue;
      const long south = hEdge(i, j), east = vEdge(i, j + 1), north = hEdge(i + 1, j), west = vEdge(i, j);
      std::vector<long> cut;
      if (a != b) cut.push_back(south);
      if (b != cc) cut.push_back(east);
      if (cc != d) cut.push_back(north);
      if (d != a) cut.push_back(west);
      if (cut.size() == 2) {
        join(cut[0], cut[1]);
      } else {  // a saddle: the cell's centre decides which corners connect
        const bool centre = depth(latOf(i) + 0.5 * dLat, lonOf(j) + 0.5 * dLon) < 0.0;
        if (centre == a) join(south, east), join(north, west);
        else join(south, west), join(north, east);
      }
    }
  // Where the contour crosses an edge: bisection along it.
  const auto crossing = [&](long edge) {
    const long cell = edge / 2;
    const int i = static_cast<int>(cell / nLon), j = static_cast<int>(cell % nLon);
    double lat0 = latOf(i), lon0 = -180.0 + j * dLon;
    double lat1 = (edge % 2) ? lat0 + dLat : lat0, lon1 = (edge % 2) ? lon0 : lon0 + dLon;
    const bool inside0 = depth(lat0, lon0) < 0.0;
    for (int n = 0; n < 24 && (std::abs(lat1 - lat0) + std::abs(lon1 - lon0)) > 1e-3; ++n) {
      const double lat = 0.5 * (lat0 + lat1), lon = 0.5 * (lon0 + lon1);
      if ((depth(lat, lon) < 0.0) == inside0) lat0 = lat, lon0 = lon;
      else lat1 = lat, lon1 = lon;
    }
    GeoPlace g;
    g.latitudeDeg = 0.5 * (lat0 + lat1);
    g.longitudeDeg = std::remainder(0.5 * (lon0 + lon1), 360.0);
    return g;
  };
  std::vector<std::vector<GeoPlace>> lines;
  std::set<long> done;
  const auto walk = [&](long start) {
    std::vector<GeoPlace> line;
    long previous = -1, edge = start;
    while (edge >= 0 && !done.count(edge)) {
      done.insert(edge);
      line.push_back(crossing(edge));
      long next = -1;
      for (long e : links[edge])
        if (e != previous && !done.count(e)) next = e;
      if (next < 0 && line.size() > 2 && std::find(links[edge].begin(), links[edge].end(), start) != links[edge].end())
        line.push_back(line.front());  // a closed line
      previous = edge, edge = next;
    }
    if (line.size() >= 2) lines.push_back(line);
  };
  for (const auto& [edge, to] : links)
    if (to.size() == 1 && !done.count(edge)) walk(edge);  // open lines first, from an end
  for (const auto& [edge, to] : links)
    if (!done.count(edge)) walk(edge);                     // then the closed ones
  return lines;
}

std::string formatJulianDate(double jd, int secondDecimals) {
  secondDecimals = std::clamp(secondDecimals, 0, 3);
  const double ticksPerDay = kDayS * std::pow(10.0, secondDecimals);
  double day = std::floor(jd - 0.5) + 0.5;  // the midnight before
  double ticks = std::round((jd - day) * ticksPerDay);
  if (ticks >= ticksPerDay) day += 1.0, ticks -= ticksPerDay;
  int y = 0, m = 0, d = 0;
  double fraction = 0.0;
  if (!std::isfinite(jd) || eraJd2cal(day, 0.0, &y, &m, &d, &fraction) != 0) return "(out of range)";
  const double seconds = ticks / std::pow(10.0, secondDecimals);
  const int hh = static_cast<int>(seconds / 3600.0), mm = static_cast<int>((seconds - hh * 3600.0) / 60.0);
  const double ss = seconds - hh * 3600.0 - mm * 60.0;
  char buffer[64];
  char year[16];
  if (y < 0) std::snprintf(year, sizeof year, "-%04d", -y);
  else std::snprintf(year, sizeof year, "%04d", y);
  if (secondDecimals == 0)
    std::snprintf(buffer, sizeof buffer, "%s-%02d-%02dT%02d:%02d:%02.0f", year, m, d, hh, mm, ss);
  else
    std::snprintf(buffer, sizeof buffer, "%s-%02d-%02dT%02d:%02d:%0*.*f", year, m, d, hh, mm, secondDecimals + 3,
                  secondDecimals, ss);
  return buffer;
}

double parseUtDate(const std::string& text) {
  static const std::regex kDate(R"(\s*(-?\d{1,5})-(\d{2})-(\d{2})(?:[T ](\d{2}):(\d{2})(?::(\d{2}(?:\.\d*)?))?Z?)?\s*)");
  std::smatch m;
  if (!std::regex_match(text, m, kDate))
    throw std::invalid_argument("invalid date '" + text + "': expected YYYY-MM-DD or YYYY-MM-DDTHH:MM[:SS]");
  double jd0 = 0.0, jd1 = 0.0;
  const int status = eraCal2jd(std::stoi(m[1]), std::stoi(m[2]), std::stoi(m[3]), &jd0, &jd1);
  if (status == -1) throw std::invalid_argument("invalid date '" + text + "': year before -4799");
  if (status == -2) throw std::invalid_argument("invalid date '" + text + "': month out of range");
  if (status == -3) throw std::invalid_argument("invalid date '" + text + "': day out of range");
  const int hh = m[4].matched ? std::stoi(m[4]) : 0, mm = m[5].matched ? std::stoi(m[5]) : 0;
  const double ss = m[6].matched ? std::stod(m[6]) : 0.0;
  if (hh > 23 || mm > 59 || ss >= 60.0) throw std::invalid_argument("invalid date '" + text + "': time out of range");
  return jd0 + jd1 + (hh * 3600.0 + mm * 60.0 + ss) / kDayS;
}

}  // namespace umbra::scene
