// umbra: physically based eclipse shadows, from the command line.
#include "Commands.hpp"

#include <iostream>

int main(int argc, char** argv) {
  CLI::App app{"umbra: physically based visualization of eclipses, atmospheres and terrain shadows.\n"
               "Run 'umbra COMMAND --help' for the options of a command."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "umbra 0.1.0");
  // Parse errors read like every other error: one line on stderr.
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "umbra: error: " + std::string(e.what()) + " (see --help)\n";
  });
  umbra::cli::Action action;
  umbra::cli::addRenderCommand(app, action);
  umbra::cli::addMoonCommand(app, action);
  umbra::cli::addPrecomputeCommand(app, action);
  umbra::cli::addProfileCommand(app, action);
  umbra::cli::addInspectCommand(app, action);
  umbra::cli::addAtmosphereCommand(app, action);
  umbra::cli::addTerrainCommand(app, action);
  umbra::cli::requireFiniteNumbers(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    return action();
  } catch (const std::exception& e) {
    std::cerr << "umbra: error: " << e.what() << std::endl;
    return 1;
  }
}
