#pragma once
// The parameters a table depends on, as canonical key/value text: what the table files
// carry in their headers and what the cache hashes. One function per kind of table, so
// that a table is keyed by what changes it and nothing else (the refraction table does
// not change with the aerosols).
#include "Atmosphere.hpp"

#include <map>
#include <string>

namespace umbra::atmosphere {

using ParameterMap = std::map<std::string, std::string>;

/// Shortest decimal text that reads back as the same double.
std::string formatNumber(double x);

/// Everything that determines n(h, lambda): radii, refractivity, dispersion and the
/// profile n - 1 follows, at `wavelengthNm`.
ParameterMap refractionParameters(const Atmosphere& atmosphere, double wavelengthNm);

/// Every parameter of the atmosphere (radii, wavelengths, ground albedo, refraction, and
/// each component's profile, coefficients and phase functions).
ParameterMap atmosphereParameters(const Atmosphere& atmosphere);

} // namespace umbra::atmosphere
