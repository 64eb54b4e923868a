// The "optics" object of an atmosphere file's component: each model's coefficients (and the
// phase function it implies) at the load's wavelengths (docs/atmosphere-format.md, "Optics").
#include "reader/Reader.hpp"

#include "Humidity.hpp"
#include "Mie.hpp"
#include "MieCache.hpp"

#include <algorithm>
#include <complex>
#include <exception>
#include <utility>

namespace umbra::atmosphere::reader {
namespace {

/// The "mie" model's phase table: every 0.5 degrees (the forward peak of micron-sized
/// dust is ~3 degrees wide at 440 nm), and the size quadrature's tolerances (relative
/// change of one halving; Mie.hpp): bulk coefficients to ~1e-4, phase samples to ~1e-2.
/// Martian dust (r_eff 1.5 um, v_eff 0.3) then takes 1000-2000 radius nodes a wavelength
/// instead of 5000-14000 (docs/accuracy-vs-speed/atmosphere-tables.md, "Mars' dust by Lorenz-Mie").
constexpr int kMiePhaseSamples = 361;
constexpr double kMieBulkTolerance = 1e-4, kMiePhaseTolerance = 1e-2;

/// The refractive-index part of a "rayleigh" model: n - 1 per wavelength and the number
/// density it holds at.
std::pair<std::vector<double>, double> parseRefractiveIndex(const Reader& in, const json& value,
                                                            const std::string& field) {
  const auto positiveN = [](double x) { return x > 0.0; };
  if (!value.is_object()) in.fail(field, "expected an object, " + got(value));
  std::vector<double> refractivity;
  double atN = kStandardNumberDensityPerM3;
  in.object(value, field, "components.*.optics.refractiveIndex");
  if (value.contains("formula") && value.contains("refractivity"))
    in.fail(field, "expected one of 'formula' and 'refractivity', not both");
  if (value.contains("formula")) {
    const std::string formula = in.string(value["formula"], field + ".formula");
    double lo = 0.0, hi = 0.0;
    std::function<double(double)> f;
    if (formula == "peck-reeder-1972") {
      lo = 230.0, hi = 1690.0, f = airRefractivityPeckReeder;
    } else if (formula == "bideau-mehu-1973-co2") {
      lo = 180.0, hi = 1700.0, f = co2RefractivityBideauMehu;
    } else {
      in.fail(field + ".formula", "expected one of: peck-reeder-1972, bideau-mehu-1973-co2, " +
                                      got(value["formula"]));
    }
    for (double lambda : in.wavelengths()) {
      if (lambda < lo || lambda > hi)
        in.fail(field + ".formula", "wavelength " + number(lambda) + " nm is outside the formula's range (" +
                                        number(lo) + "-" + number(hi) + " nm)");
      refractivity.push_back(f(lambda));
    }
    if (value.contains("atNumberDensityPerM3"))
      atN = in.positive(value["atNumberDensityPerM3"], field + ".atNumberDensityPerM3", "number density in 1/m^3");
  } else {
    refractivity = in.spectrum(in.require(value, "refractivity", field), field + ".refractivity",
                               "n - 1, a positive number below 1", [](double r) { return r > 0.0 && r < 1.0; });
    atN = in.number(in.require(value, "atNumberDensityPerM3", field), field + ".atNumberDensityPerM3",
                    "a positive number density in 1/m^3", positiveN);
  }
  return {refractivity, atN};
}

/// The size distribution of a "mie" model: one radius (effectiveRadiusM: <r^3>/<r^2>, or
/// medianRadiusM: the number distribution's median, OPAC's mode radius) and at most one
/// width (effectiveVariance, or geometricStdDev sigma_g; none: one radius), cut to
/// radiusRangeM [min, max] when given, N from numberDensityPerM3.
LogNormalSizes parseMieSizes(const Reader& in, const json& value, const std::string& field) {
  auto key = [&](const char* k) { return Reader::join(field, k); };
  const bool byMedian = value.contains("medianRadiusM");
  if (byMedian == value.contains("effectiveRadiusM"))
    in.fail(field, "expected exactly one of 'effectiveRadiusM' and 'medianRadiusM'");
  if (value.contains("effectiveVariance") && value.contains("geometricStdDev"))
    in.fail(field, "expected at most one of 'effectiveVariance' and 'geometricStdDev'");
  const char* radiusKey = byMedian ? "medianRadiusM" : "effectiveRadiusM";
  const double r = in.number(value[radiusKey], key(radiusKey),
                             byMedian ? "a median radius in (0, 2e-5] m" : "an effective radius in (0, 2e-5] m",
                             [](double x) { return x > 0.0 && x <= 2e-5; });
  // The width as given: v_eff, or sigma_g (v_eff = exp(ln^2 sigma_g) - 1; Mie.hpp).
  double vEff = 0.0, sigma = 1.0;
  if (value.contains("effectiveVariance")) {
    vEff = in.number(value["effectiveVariance"], key("effectiveVariance"), "an effective variance in [0, 2]",
                     [](double x) { return x >= 0.0 && x <= 2.0; });
    sigma = std::exp(std::sqrt(std::log1p(vEff)));
  }
  if (value.contains("geometricStdDev")) {
    sigma = in.number(value["geometricStdDev"], key("geometricStdDev"), "a geometric standard deviation in [1, 5]",
                      [](double x) { return x >= 1.0 && x <= 5.0; });
    vEff = std::expm1(std::log(sigma) * std::log(sigma));
  }
  const double N = in.number(in.require(value, "numberDensityPerM3", field), key("numberDensityPerM3"),
                             "a number density above 0, at most 1e35 in 1/m^3",
                             [](double x) { return x > 0.0 && x <= 1e35; });
  LogNormalSizes sizes = byMedian ? LogNormalSizes{r, sigma, N} : logNormalFromEffective(r, vEff, N);
  if (value.contains("radiusRangeM")) {
    const std::vector<double> range = in.numbers(value["radiusRangeM"], key("radiusRangeM"));
    if (range.size() != 2 || !(range[0] >= 0.0) || !(range[1] > range[0]) || !(range[1] <= 1e-3))
      in.fail(key("radiusRangeM"), "expected [min, max] radii in m, 0 <= min < max <= 1e-3");
    sizes.minRadiusM = range[0], sizes.maxRadiusM = range[1];
  }
  return sizes;
}

/// r_wet / r_dry of a "mie" model's "hygroscopicGrowth" rows at the air's relative humidity.
double parseGrowth(const Reader& in, const json& value, const std::string& field) {
  in.object(value, field, "components.*.optics.hygroscopicGrowth");
  const std::vector<double> humidity = in.numbers(in.require(value, "relativeHumidity", field),
                                                  Reader::join(field, "relativeHumidity"));
  const std::vector<double> factor = in.numbers(in.require(value, "radiusFactor", field),
                                                Reader::join(field, "radiusFactor"));
  try {
    return growthFactor(humidity, factor, in.relativeHumidity());
  } catch (const std::invalid_argument& e) {
    in.failWithKey(field, e.what());
  }
}

// Coefficients at most 1 per metre and number densities at most 1e35 per cubic metre (air at
// sea level: 1e-5 /m, 2.5e25 /m^3): beyond them the tables overflow.
const char* const kCoefficient = "a coefficient from 0 to 1 in 1/m";
bool coefficientRange(double x) { return x >= 0.0 && x <= 1.0; }
bool nonNegative(double x) { return x >= 0.0; }
bool positive(double x) { return x > 0.0; }

/// An optics object being read: the reader, the object, its field path and the load's
/// wavelengths, with what several models read alike.
struct OpticsInput {
  const Reader& in;
  const json& value;
  const std::string& field;
  const std::vector<double>& lambdas;

  std::size_t n() const { return lambdas.size(); }
  std::string key(const char* k) const { return Reader::join(field, k); }
  const json& require(const char* k) const { return in.require(value, k, field); }
  /// A required spectrum of the object.
  std::vector<double> spectrum(const char* k, const std::string& expected, const std::function<bool(double)>& ok) const {
    return in.spectrum(require(k), key(k), expected, ok);
  }
  double density(const char* k) const {
    return in.number(require(k), key(k), "a number density above 0, at most 1e35 in 1/m^3",
                     [](double x) { return x > 0.0 && x <= 1e35; });
  }
  /// A coefficient spectrum, 0 when the key is absent.
  std::vector<double> optionalCoefficients(const char* k) const {
    return value.contains(k) ? in.spectrum(value[k], key(k), kCoefficient, coefficientRange) : std::vector<double>(n(), 0.0);
  }
  /// Costa Eq. 17's scattering from the van de Hulst parameters of `v` (at `f`).
  std::vector<double> vanDeHulst(const json& v, const std::string& f) const {
    const double turbidity = in.number(in.require(v, "turbidity", f), Reader::join(f, "turbidity"),
                                       "a turbidity >= 1", [](double t) { return t >= 1.0; });
    const double nu = in.number(in.require(v, "jungeExponent", f), Reader::join(f, "jungeExponent"),
                                "a Junge exponent in [2, 6]", [](double x) { return x >= 2.0 && x <= 6.0; });
    const std::vector<double> K = in.spectrum(in.require(v, "K", f), Reader::join(f, "K"), "a number >= 0", nonNegative);
    std::vector<double> beta(n());
    for (std::size_t i = 0; i < n(); ++i) beta[i] = vanDeHulstScatteringPerM(turbidity, nu, K[i], lambdas[i]);
    return beta;
  }
};

Optics rayleighOptics(const OpticsInput& x) {
  const auto [refractivity, atN] = parseRefractiveIndex(x.in, x.require("refractiveIndex"), x.key("refractiveIndex"));
  const double N = x.density("numberDensityPerM3");
  const double delta = x.in.number(x.require("depolarisation"), x.key("depolarisation"),
                                   "a depolarisation factor in [0, 0.5]", [](double d) { return d >= 0.0 && d <= 0.5; });
  Optics o;
  for (std::size_t i = 0; i < x.n(); ++i)
    o.scattering.push_back(rayleighCrossSectionM2(refractivity[i], atN, x.lambdas[i], delta) * N);
  o.absorption.assign(x.n(), 0.0);
  o.defaultPhase.assign(x.n(), PhaseFunction::rayleigh());
  return o;
}

Optics absorberOptics(const OpticsInput& x) {
  const double N = x.density("numberDensityPerM3");
  const std::vector<double> sigma = x.spectrum("crossSectionM2", "a cross-section >= 0 in m^2", nonNegative);
  Optics o;
  o.scattering.assign(x.n(), 0.0);
  for (double s : sigma) o.absorption.push_back(N * s);
  return o;
}

Optics coefficientsOptics(const OpticsInput& x) {
  return {x.spectrum("scatteringPerM", kCoefficient, coefficientRange), x.optionalCoefficients("absorptionPerM"), {}};
}

Optics vanDeHulstOptics(const OpticsInput& x) {
  return {x.vanDeHulst(x.value, x.field), x.optionalCoefficients("absorptionPerM"), {}};
}

Optics anomalousDiffractionOptics(const OpticsInput& x) {
  const double r = x.in.number(x.require("radiusM"), x.key("radiusM"), "a particle radius in (0, 0.01] m",
                               [](double v) { return v > 0.0 && v <= 0.01; });
  const double N = x.density("numberDensityPerM3");
  const std::vector<double> m =
      x.spectrum("refractiveIndexReal", "a real refractive index > 1", [](double v) { return v > 1.0; });
  const std::vector<double> k = x.spectrum("refractiveIndexImag", "an imaginary refractive index >= 0", nonNegative);
  std::vector<double> extinction(x.n());
  for (std::size_t i = 0; i < x.n(); ++i)
    extinction[i] = anomalousDiffractionExtinctionPerM(r, m[i], k[i], N, x.lambdas[i]);
  Optics o;
  if (x.value.contains("vanDeHulst")) {
    // Costa's combination: scattering from Eq. 17, extinction from Eq. 20.
    const std::string f = x.key("vanDeHulst");
    x.in.object(x.value["vanDeHulst"], f, "components.*.optics.vanDeHulst");
    o.scattering = x.vanDeHulst(x.value["vanDeHulst"], f);
    for (std::size_t i = 0; i < x.n(); ++i) {
      if (o.scattering[i] > extinction[i] * (1.0 + 1e-12))
        x.in.fail(f, "at " + number(x.lambdas[i]) + " nm the Eq. 17 scattering " + number(o.scattering[i]) +
                         " 1/m exceeds the Eq. 20 extinction " + number(extinction[i]) + " 1/m");
      o.absorption.push_back(std::max(0.0, extinction[i] - o.scattering[i]));
    }
    return o;
  }
  constexpr double kPi = 3.14159265358979323846;
  for (std::size_t i = 0; i < x.n(); ++i) {
    const double absorption = kPi * r * r * anomalousDiffractionAbsorptionEfficiency(r, k[i], x.lambdas[i]) * N;
    o.absorption.push_back(std::min(absorption, extinction[i]));
    o.scattering.push_back(extinction[i] - o.absorption.back());
  }
  return o;
}

Optics mieOptics(const OpticsInput& x) {
  LogNormalSizes sizes = parseMieSizes(x.in, x.value, x.field);
  const std::vector<double> m = x.spectrum("refractiveIndexReal", "a real refractive index > 0", positive);
  const std::vector<double> k = x.spectrum("refractiveIndexImag", "an imaginary refractive index >= 0", nonNegative);
  // In humid air a hygroscopic particle grows and its index moves towards water's.
  const double growth =
      x.value.contains("hygroscopicGrowth") ? parseGrowth(x.in, x.value["hygroscopicGrowth"], x.key("hygroscopicGrowth")) : 1.0;
  sizes.medianRadiusM *= growth, sizes.minRadiusM *= growth, sizes.maxRadiusM *= growth;
  // The wavelengths in parallel, each through the Lorenz-Mie cache (MieCache.hpp).
  // The first wavelength's error, as a loop in order would give it.
  const std::size_t n = x.n();
  std::vector<MieAerosol> optics(n);
  std::vector<std::exception_ptr> failures(n);
#pragma omp parallel for schedule(dynamic)
  for (std::size_t i = 0; i < n; ++i) {
    try {
      const std::complex<double> index =
          humidRefractiveIndex({m[i], k[i]}, waterRefractiveIndexReal(x.lambdas[i]), growth);
      optics[i] = cachedMieLogNormal(x.lambdas[i] * 1e-9, index, sizes, kMiePhaseSamples, 0, kMieBulkTolerance,
                                     kMiePhaseTolerance);
    } catch (...) {
      failures[i] = std::current_exception();
    }
  }
  for (const std::exception_ptr& failure : failures)
    if (failure) std::rethrow_exception(failure);
  Optics o;
  for (const MieAerosol& a : optics) {
    o.scattering.push_back(a.scatteringPerM);
    o.absorption.push_back(a.absorptionPerM);
    o.defaultPhase.push_back(PhaseFunction::tabulated(a.cosTheta, a.phase));
  }
  return o;
}

// Populations sharing one density profile (an OPAC aerosol type): their coefficients add,
// their phase functions mix weighted by their scattering.
Optics mixtureOptics(const OpticsInput& x) {
  const json& of = x.require("of");
  if (!of.is_object() || of.empty()) x.in.fail(x.key("of"), "expected a non-empty object of named optics, " + got(of));
  std::vector<Optics> parts;
  for (const auto& item : of.items()) {
    const std::string f = x.key("of") + "." + item.key();
    parts.push_back(parseOptics(x.in, item.value(), f));
    const Optics& part = parts.back();
    if (part.defaultPhase.empty() && std::any_of(part.scattering.begin(), part.scattering.end(), positive))
      x.in.fail(f, "expected a model with its own phase function in a mixture (rayleigh, mie), got '" +
                       x.in.string(item.value()["model"], f + ".model") + "'");
  }
  Optics o;
  o.scattering.assign(x.n(), 0.0), o.absorption.assign(x.n(), 0.0);
  for (std::size_t i = 0; i < x.n(); ++i) {
    std::vector<PhaseFunction> phases;
    std::vector<double> weights;
    for (const Optics& part : parts) {
      o.scattering[i] += part.scattering[i], o.absorption[i] += part.absorption[i];
      if (part.defaultPhase.empty()) continue;
      phases.push_back(part.defaultPhase[i]);
      weights.push_back(part.scattering[i]);
    }
    o.defaultPhase.push_back(o.scattering[i] > 0.0 ? PhaseFunction::mixture(phases, weights) : PhaseFunction::isotropic());
  }
  return o;
}

/// The models, in the order messages list them.
const std::vector<std::pair<const char*, Optics (*)(const OpticsInput&)>>& opticsModels() {
  static const std::vector<std::pair<const char*, Optics (*)(const OpticsInput&)>> models{
      {"rayleigh", rayleighOptics},
      {"absorber", absorberOptics},
      {"coefficients", coefficientsOptics},
      {"van-de-hulst", vanDeHulstOptics},
      {"anomalous-diffraction", anomalousDiffractionOptics},
      {"mie", mieOptics},
      {"mixture", mixtureOptics}};
  return models;
}

}  // namespace

Optics parseOptics(const Reader& in, const json& value, const std::string& field) {
  if (!value.is_object()) in.fail(field, "expected an object, " + got(value));
  if (value.contains("description")) {  // free text, as a component's
    in.string(value["description"], field + ".description");
    json rest = value;
    rest.erase("description");
    return parseOptics(in, rest, field);
  }
  const std::string model = in.string(in.require(value, "model", field), field + ".model");
  const auto& models = opticsModels();
  const auto known = std::find_if(models.begin(), models.end(), [&](const auto& m) { return model == m.first; });
  if (known == models.end()) {
    std::vector<std::string> names;
    for (const auto& m : models) names.emplace_back(m.first);
    in.fail(Reader::join(field, "model"), "expected one of: " + join(names) + ", " + got(value["model"]));
  }
  in.object(value, field, "components.*.optics", model);
  return known->second({in, value, field, in.wavelengths()});
}

}  // namespace umbra::atmosphere::reader
