// umbra atmosphere SUBCOMMAND: refraction, precompute, ...
#include "AtmosphereCommon.hpp"

#include "vtkAtmosphereTablesSource.h"
#include "umbra/tables/TableCache.h"

#include <iostream>

namespace umbra::cli {

void addAtmosphereOptions(CLI::App* command, std::string& preset, std::string& config) {
  std::string list;
  for (const auto& p : atmosphere::presetNames()) list += (list.empty() ? "" : ", ") + p;
  command->add_option("--preset", preset, "Atmosphere preset: " + list);
  command->add_option("--config", config, "Atmosphere file (JSON, see docs/atmosphere-format.md)");
}

atmosphere::AtmosphereModelPtr atmosphereOption(const std::string& preset, const std::string& config) {
  if (preset.empty() == config.empty()) throw CommandError("give one of --preset or --config");
  return atmosphere::AtmosphereModel::load(preset.empty() ? config : preset);
}

void addAtmosphereCommand(CLI::App& app, Action& action) {
  CLI::App* atmosphereCmd = app.add_subcommand("atmosphere", "Atmosphere models: refraction, tables, sky, the sky of a solar eclipse");
  atmosphereCmd->require_subcommand(1);
  addAtmosphereRefractionCommand(*atmosphereCmd, action);
  addAtmospherePrecomputeCommand(*atmosphereCmd, action);
  addAtmosphereSkyCommand(*atmosphereCmd, action);
  addAtmosphereEclipseSkyCommand(*atmosphereCmd, action);
}

void updateTablesSource(vtkAtmosphereTablesSource* source, const CacheOptions& cache, const std::string& what) {
  source->SetCacheDirectory(cache.directory.c_str());
  source->SetUseCache(!cache.disabled);
  {
    ProgressLine progress(what, source);
    const bool warnings = vtkObject::GetGlobalWarningDisplay() != 0;
    vtkObject::GlobalWarningDisplayOff();  // the error comes back as one line below
    source->Update();
    vtkObject::SetGlobalWarningDisplay(warnings ? 1 : 0);
  }
  if (!source->GetLastError().empty()) throw CommandError(source->GetLastError());
  if (source->GetLastCacheHits() > 0)
    std::cerr << "cache hit: " << source->GetLastCacheHits() << " table(s) read from "
              << (cache.directory.empty() ? tables::TableCache::defaultDirectory() : cache.directory) << "\n";
  if (!source->GetLastCacheWarning().empty())
    std::cerr << "umbra: warning: could not cache the tables: " << source->GetLastCacheWarning() << "\n";
}

} // namespace umbra::cli
