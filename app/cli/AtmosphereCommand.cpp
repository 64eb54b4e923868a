// umbra atmosphere SUBCOMMAND: refraction, precompute, ...
#include "AtmosphereCommon.hpp"

namespace umbra::cli {

void addAtmosphereOptions(CLI::App* command, std::string& preset, std::string& config) {
  std::string list;
  for (const auto& p : atmosphere::presetNames()) list += (list.empty() ? "" : ", ") + p;
  command->add_option("--preset", preset, "Atmosphere preset: " + list);
  command->add_option("--config", config, "Atmosphere file (JSON, see docs/atmosphere-format.md)");
}

atmosphere::Atmosphere loadAtmosphereOption(const std::string& preset, const std::string& config,
                                            const std::vector<double>& wavelengthsNm) {
  if (preset.empty() == config.empty()) throw CommandError("give one of --preset or --config");
  return atmosphere::loadAtmosphere(preset.empty() ? config : preset, wavelengthsNm);
}

void addAtmosphereCommand(CLI::App& app, Action& action) {
  CLI::App* atmosphereCmd = app.add_subcommand("atmosphere", "Atmosphere models: refraction, tables, sky");
  atmosphereCmd->require_subcommand(1);
  addAtmosphereRefractionCommand(*atmosphereCmd, action);
  addAtmospherePrecomputeCommand(*atmosphereCmd, action);
  addAtmosphereSkyCommand(*atmosphereCmd, action);
}

} // namespace umbra::cli
