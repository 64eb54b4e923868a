#pragma once
// What the `umbra atmosphere ...` commands share: choosing the atmosphere.
#include "Commands.hpp"

#include "Atmosphere.hpp"
#include "AtmosphereModel.hpp"

#include <string>
#include <vector>

class vtkAtmosphereTablesSource;

namespace umbra::cli {

/// Adds --preset NAME and --config FILE (exactly one of them is needed).
void addAtmosphereOptions(CLI::App* command, std::string& preset, std::string& config);

/// The atmosphere named by --preset or --config, read once; throws CommandError unless
/// exactly one of them was given (and AtmosphereError for a bad file).
atmosphere::AtmosphereModelPtr atmosphereOption(const std::string& preset, const std::string& config);

/// Updates `source` through the cache that `cache` names, with a progress line saying
/// `what`: its error thrown as a CommandError (VTK's own messages kept quiet), a cache hit
/// and a cache that could not be written said on stderr.
void updateTablesSource(vtkAtmosphereTablesSource* source, const CacheOptions& cache, const std::string& what);

// The subcommands of `umbra atmosphere`, one file each.
void addAtmosphereRefractionCommand(CLI::App& atmosphereCmd, Action& action);
void addAtmospherePrecomputeCommand(CLI::App& atmosphereCmd, Action& action);
void addAtmosphereSkyCommand(CLI::App& atmosphereCmd, Action& action);
void addAtmosphereEclipseSkyCommand(CLI::App& atmosphereCmd, Action& action);

} // namespace umbra::cli
