#pragma once
// The output of vtkAtmosphereTablesSource back as the plain tables of atmosphere/ (the
// render pass and the eclipse sources read them from one place).
#include "Atmosphere.hpp"
#include "Precompute.hpp"
#include "Refraction.hpp"

#include <map>
#include <string>

class vtkMultiBlockDataSet;

namespace umbra::filters {

/// The Bruneton blocks (transmittance, single scattering per component, multiple
/// scattering, direct and indirect irradiance) back as AtmosphereTables (float values
/// widened to double), for `atmosphere` (the model they were computed for, at the same
/// wavelengths). Throws std::invalid_argument naming the missing or inconsistent block.
atmosphere::AtmosphereTables tablesFromBlocks(vtkMultiBlockDataSet* blocks, const atmosphere::Atmosphere& atmosphere);

/// The "refraction" block back as a RefractionTable (radii from `atmosphere`). Throws
/// std::invalid_argument when the block or its arrays are missing.
atmosphere::RefractionTable refractionFromBlocks(vtkMultiBlockDataSet* blocks, const atmosphere::Atmosphere& atmosphere);

/// The field parameters of the block named `name` (empty when there is none).
std::map<std::string, std::string> blockParameters(vtkMultiBlockDataSet* blocks, const std::string& name);

} // namespace umbra::filters
