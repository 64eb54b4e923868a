#pragma once
// Eclipse predictions: every solar and lunar eclipse in a span of time, with its type,
// greatest eclipse, gamma, magnitudes, contacts and Saros series.
//
// Geometry in Terrestrial Time (the ephemerides' time); the Earth's rotation and every time
// reported as UT in UT1 = TT - Delta T (scene/DeltaT.hpp). Positions: the Sun from ERFA's
// Earth (epv00), the Moon from ELP 2000-82B (moonGeocentricElpM), both apparent (light time
// and aberration, as Besselian elements take them); the Earth an ellipsoid (WGS84). The
// constants are NASA's (EclipseConstants); a time is a Julian date, TT unless named UT.
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace umbra::scene {

/// The constants of the predictions: those of NASA's eclipse canons (Espenak & Meeus).
struct EclipseConstants {
  double earthEquatorialRadiusM = 6378137.0;
  double earthFlattening = 1.0 / 298.257;
  /// The Moon's radius in Earth equatorial radii: its mean limb for penumbral (exterior)
  /// contacts, annular phases and lunar eclipses (0.272488), and a mean minimum radius,
  /// below the limb's mountains, for the umbra of total eclipses (0.272281).
  double moonRadiusPenumbral = 0.272488;
  double moonRadiusUmbral = 0.272281;
  /// The Sun's angular radius at 1 au (arcseconds).
  double sunRadiusArcsecAt1Au = 959.63;
};

/// How the Earth's atmosphere enlarges its shadow at the Moon.
enum class LunarShadowRule {
  Danjon,     ///< the Earth's radius enlarged by 1/85 (NASA's canon, the Connaissance des Temps)
  Chauvenet,  ///< the shadow's radii enlarged by 1/50, the oblate Earth's mean radius (the Astronomical Almanac)
  Physical,   ///< the Earth's radius enlarged by EclipseSearch::physicalEnlargementM: the umbra's edge
              ///< where an atmosphere's shadow profile is steepest (umbraEdgeEnlargementM)
};

enum class SolarEclipseType { Partial, Annular, Total, Hybrid };
enum class LunarEclipseType { Penumbral, Partial, Total };

const char* typeName(SolarEclipseType type);
const char* typeName(LunarEclipseType type);

/// A contact: its TT Julian date, when the eclipse has it.
using Contact = std::optional<double>;

struct SolarEclipse {
  SolarEclipseType type = SolarEclipseType::Partial;
  bool central = false;             ///< the shadow's axis meets the Earth
  double greatestTt = 0.0;          ///< the axis closest to the Earth's centre
  double deltaTSeconds = 0.0;       ///< TT - UT1 used
  std::string deltaTSource;
  double gamma = 0.0;               ///< the axis' least distance from the Earth's centre, equatorial radii; + north
  double magnitude = 0.0;           ///< central: the Moon's diameter over the Sun's; else the Sun's diameter covered
  double latitudeDeg = 0.0, longitudeDeg = 0.0;  ///< of greatest eclipse (geodetic; east positive)
  double sunAltitudeDeg = 0.0;      ///< there
  std::optional<double> centralDurationS;        ///< of totality or annularity there (central eclipses)
  std::optional<double> pathWidthKm;             ///< of the umbra or antumbra there (central eclipses)
  Contact p1, p2, p3, p4;           ///< the penumbra's exterior (1, 4) and interior (2, 3) contacts with the Earth
  Contact u1, u2, u3, u4;           ///< the umbra's (antumbra's), the same
  int saros = 0;
};

struct LunarEclipse {
  LunarEclipseType type = LunarEclipseType::Penumbral;
  double greatestTt = 0.0;          ///< the Moon's centre closest to the shadow's axis
  double deltaTSeconds = 0.0;
  std::string deltaTSource;
  double gamma = 0.0;               ///< that distance in Earth equatorial radii; + Moon north of the axis
  double umbralMagnitude = 0.0, penumbralMagnitude = 0.0;
  Contact p1, u1, u2, u3, u4, p4;
  int saros = 0;
};

/// The Earth's shadow where the Moon is, at a TT instant (apparent places, as the search's):
/// the Moon's centre on the shadow's cross-section, x towards the projected east and y along
/// the Earth's projected north pole, from the axis.
struct LunarShadowGeometry {
  double moonDistanceM = 0.0;      ///< along the shadow's axis, from the Earth's centre
  double sunDistanceM = 0.0;
  double moonOffsetXM = 0.0, moonOffsetYM = 0.0;
  double axisDeclinationRad = 0.0;  ///< of the shadow's axis (the antisolar point), true equator of date
};

LunarShadowGeometry lunarShadowGeometry(double tt);

struct EclipseSearch {
  double fromTt = 0.0, toTt = 0.0;  ///< greatest eclipses in [from, to]
  std::optional<double> deltaTSeconds;  ///< fixed Delta T (s); otherwise deltaTAtYear
  LunarShadowRule lunarRule = LunarShadowRule::Danjon;
  double physicalEnlargementM = 0.0;  ///< LunarShadowRule::Physical: added to the Earth's mean radius
  /// The Earth's outline an ellipse, as the Moon sees it (flattening, the axis' declination),
  /// in every rule; false: a sphere (the rules as published, 1.01 and 0.998340 standing for it).
  bool oblateShadow = false;
  EclipseConstants constants;
  std::function<void(double)> progress;  ///< fraction done, from the calling thread
};

/// Every solar eclipse whose greatest eclipse falls in the search's span, in time order.
/// Throws std::invalid_argument for a span that is empty, reversed, not finite or outside
/// -3000..+5000 (Julian dates the ephemerides' series are summed over).
std::vector<SolarEclipse> findSolarEclipses(const EclipseSearch& search);
/// Every lunar eclipse, the same.
std::vector<LunarEclipse> findLunarEclipses(const EclipseSearch& search);

/// A place on the Earth: geodetic latitude and longitude (degrees, east positive) and height
/// above the ellipsoid (m).
struct GeoPlace {
  double latitudeDeg = 0.0, longitudeDeg = 0.0, heightM = 0.0;
};

/// An instant of a local eclipse and where the Sun stands then (geometric altitude; azimuth
/// from north through east).
struct LocalInstant {
  double tt = 0.0;
  double sunAltitudeDeg = 0.0, sunAzimuthDeg = 0.0;
};

/// A solar eclipse seen from one place. The contacts are the Moon's mean limb on the Sun's:
/// C1 and C4 exterior, C2 and C3 interior (totality or annularity); the Sun may be below
/// the horizon at any of them (its altitude says so).
struct LocalSolarEclipse {
  bool eclipsed = false;  ///< the penumbra passes over the place (whether the Sun is up or not)
  SolarEclipseType phase = SolarEclipseType::Partial;  ///< what the place sees: partial, total or annular
  std::optional<LocalInstant> c1, c2, c3, c4;
  LocalInstant greatest;  ///< the Moon's centre closest to the Sun's
  double magnitude = 0.0;    ///< the Sun's diameter covered (central: the Moon's diameter over the Sun's)
  double obscuration = 0.0;  ///< the Sun's disc area covered
  std::optional<double> centralDurationS;
};

/// The eclipse as seen from `place`. Throws std::invalid_argument for a place off the
/// Earth's range of latitudes or heights (-90..90 deg, -500 m..100 km).
LocalSolarEclipse localSolarEclipse(const SolarEclipse& eclipse, const GeoPlace& place,
                                    const EclipseConstants& constants = {});

/// A point of the central line: the axis on the ground at a time, and the duration of
/// totality or annularity there.
struct CentralLinePoint {
  double tt = 0.0;
  GeoPlace place;
  double sunAltitudeDeg = 0.0;
  double durationS = 0.0;
  std::optional<double> widthKm;  ///< the path's width across the line there, where both limits are found
};

/// A central eclipse's path on the Earth, sampled every `stepSeconds` of its central line:
/// the line, the northern and southern limits of the umbra or antumbra (the edges of the
/// band where the central phase is seen), and of the penumbra over the same times (where
/// the partial eclipse ends, on the Sun's side of the sunrise and sunset line).
struct SolarEclipsePath {
  std::vector<CentralLinePoint> centralLine;
  std::vector<GeoPlace> northernLimit, southernLimit;
  std::vector<GeoPlace> northernPenumbralLimit, southernPenumbralLimit;
};

/// Throws std::invalid_argument for an eclipse that is not central, or a step outside
/// 1..3600 s.
SolarEclipsePath solarEclipsePath(const SolarEclipse& eclipse, double stepSeconds = 60.0,
                                  const EclipseConstants& constants = {});

/// The instant `at` of the eclipse whose greatest eclipse falls on `date` (UT, YYYY-MM-DD),
/// as a UT1 Julian date: "greatest" or a contact ("P1", "U2": a lunar eclipse's P1 U1 U2 U3
/// U4 P4, a solar eclipse's global P1-P4 and U1-U4), with an offset or not ("U2+10min",
/// "greatest-30s", "P4+1h"). Delta T as deltaTAtYear. Throws std::invalid_argument naming
/// the date or the contact that is missing.
double eclipseInstantUt(const std::string& date, const std::string& at);

/// The outline of where a solar eclipse is seen at all (any partial phase with the Sun up):
/// the contour where the greatest local eclipse, over the Sun-up part of the eclipse, just
/// reaches the Sun's limb. It joins the northern and southern limits of the partial eclipse
/// and the curves where it begins or ends at sunrise or sunset. Found on a latitude-longitude
/// grid of `stepDeg`, each crossing placed along its cell's edge to 0.001 deg; the lines
/// come in pieces where the grid's edges cut them (the poles' rows). For any eclipse, central
/// or not. Throws std::invalid_argument for a step outside 0.1..10 deg.
std::vector<std::vector<GeoPlace>> partialEclipseOutline(const SolarEclipse& eclipse, double stepDeg = 1.0,
                                                         const EclipseConstants& constants = {});

/// A TT (or UT1) Julian date as "2017-08-21T18:25:29.9" (proleptic Gregorian calendar;
/// years before 1 as astronomers count them: 0 is 1 BC).
std::string formatJulianDate(double jd, int secondDecimals = 1);

/// A date "YYYY-MM-DD", "YYYY-MM-DDTHH:MM[:SS]" or "-0584-05-28" (UT, proleptic Gregorian)
/// as a UT1 Julian date. Throws std::invalid_argument quoting the text.
double parseUtDate(const std::string& text);

}  // namespace umbra::scene
