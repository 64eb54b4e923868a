#include "Commands.hpp"

#include <string>

namespace umbra::cli {

void addCommands(CLI::App& app, Action& action) {
  app.description("umbra: physically based visualization of eclipses, atmospheres and terrain shadows.\n"
                  "Run 'umbra COMMAND --help' for the options of a command.");
  app.require_subcommand(1);
  app.set_version_flag("--version", "umbra 0.1.0");
  app.add_flag("--verbose", "Print VTK's own messages (warnings, GL errors) as they come; without it a failure is one line");
  app.fallthrough();  // --verbose after the command's name too
  // Parse errors read like every other error: one line on stderr.
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "umbra: error: " + std::string(e.what()) + " (see --help)\n";
  });
  addRenderCommand(app, action);
  addMoonCommand(app, action);
  addPlanetsCommand(app, action);
  addEclipsesCommand(app, action);
  addEclipseCommand(app, action);
  addPrecomputeCommand(app, action);
  addProfileCommand(app, action);
  addInspectCommand(app, action);
  addAtmosphereCommand(app, action);
  addTerrainCommand(app, action);
  addSweepCommand(app, action);
  refuseEmptyAndNonFinite(app);
}

std::string unknownCommandMessage(const CLI::App& app, int argc, const char* const* argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (word.empty() || word[0] == '-') continue;
    std::string names;
    for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; })) {
      if (command->get_name() == word) return "";
      names += (names.empty() ? "" : ", ") + command->get_name();
    }
    return "umbra: error: unknown command '" + word + "'; the commands are: " + names + " (see --help)";
  }
  return "";
}

bool spreadsOverRanks(const CLI::App& app) {
  if (app.got_subcommand("render") || app.got_subcommand("sweep")) return true;  // (a single frame: rank 0)
  const CLI::App* precompute = app.get_subcommand("precompute");
  if (app.got_subcommand(precompute)) return precompute->got_subcommand("shadow") || precompute->got_subcommand("eclipse");
  const CLI::App* terrain = app.get_subcommand("terrain");
  if (app.got_subcommand(terrain) && terrain->got_subcommand("lighting")) return true;
  const CLI::App* atmosphere = app.get_subcommand("atmosphere");
  return app.got_subcommand(atmosphere) && atmosphere->got_subcommand("precompute");
}

}  // namespace umbra::cli
