#pragma once
// Everything an atmospheric eclipse table needs, made in one place: the atmosphere at the
// wavelengths, its Bruneton tables along refracted paths, the deviation / contact table,
// the limb ray profile and the shadow model that reads them.
#include "AtmosphericShadow.hpp"

#include "Atmosphere.hpp"
#include "Precompute.hpp"
#include "Refraction.hpp"

#include <functional>
#include <map>
#include <memory>
#include <string>

namespace umbra::eclipse {

struct EclipseAtmosphereOptions {
  atmosphere::PrecomputeOptions tables;  ///< refraction on by default (see the constructor)
  bool refraction = true;                ///< bend rays (the deviation table, refracted paths)
  int refractionWidth = atmosphere::kDefaultTableSizes.refraction[0];
  int refractionHeight = atmosphere::kDefaultTableSizes.refraction[1];
  double refractionStepM = 10e3;
  int profileSamples = 4096;             ///< impact parameters of the limb ray profile
  double terrainMeanElevationM = -1.0;   ///< < 0: defaultTerrain(occluder)
  EclipseAtmosphereOptions() { tables.refraction = true; }
};

/// The prepared atmosphere; `model` points into this object (not copyable).
struct EclipseAtmosphere {
  atmosphere::Atmosphere atmosphere;
  atmosphere::AtmosphereTables tables;
  atmosphere::RefractionTable refraction;  ///< the rows the limb ray profile reads (all when given)
  AtmosphericShadowModel model;
  EclipseAtmosphere() = default;
  EclipseAtmosphere(const EclipseAtmosphere&) = delete;
  EclipseAtmosphere& operator=(const EclipseAtmosphere&) = delete;
};

/// Progress of the preparation: fraction in [0, 1] and the stage; false cancels
/// (atmosphere::PrecomputeCancelled is thrown).
using EclipseProgress = std::function<bool(double, const std::string&)>;

/// Precomputes the tables of `atm` (already at its wavelengths) for the occluder `occluderName`
/// ("earth", "mars", ...: picks the terrain) seen from a Sun `sunOccluderDistanceM` away.
/// The occluder's radius is the atmosphere's bottom radius. Throws std::invalid_argument
/// for bad options.
std::unique_ptr<EclipseAtmosphere> prepareEclipseAtmosphere(const atmosphere::Atmosphere& atm,
                                                            const std::string& occluderName,
                                                            double sunOccluderDistanceM,
                                                            const EclipseAtmosphereOptions& options,
                                                            const EclipseProgress& progress = {});

/// The same from tables computed elsewhere (e.g. vtkAtmosphereTablesSource's cache):
/// `tables` must be those of `atm` with options.tables (refracted paths when
/// options.refraction), and `refraction` its deviation table (ignored without
/// options.refraction; empty: the rows the limb ray profile reads are traced here, at
/// options' size and step). Throws std::invalid_argument when they do not match `atm`.
std::unique_ptr<EclipseAtmosphere> prepareEclipseAtmosphere(const atmosphere::Atmosphere& atm,
                                                            atmosphere::AtmosphereTables tables,
                                                            atmosphere::RefractionTable refraction,
                                                            const std::string& occluderName,
                                                            double sunOccluderDistanceM,
                                                            const EclipseAtmosphereOptions& options);

/// Every parameter that changes the prepared model's values, known before preparing it
/// (for headers and cache keys): the atmosphere's, the options', the bodies'.
std::map<std::string, std::string> eclipseAtmosphereParameters(const atmosphere::Atmosphere& atm,
                                                               const std::string& occluderName,
                                                               double sunOccluderDistanceM,
                                                               const EclipseAtmosphereOptions& options);

} // namespace umbra::eclipse
