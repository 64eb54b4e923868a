// umbra: physically based eclipse shadows, from the command line.
#include "Commands.hpp"
#include "MieOpticsCache.h"
#include "VtkMessages.hpp"

#include <iostream>

int main(int argc, char** argv) {
  CLI::App app;
  umbra::cli::Action action;
  umbra::cli::addCommands(app, action);
  umbra::filters::keepMieOpticsInCache("");  // a command's --cache-dir / --no-cache changes it
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  umbra::cli::routeVtkMessages(app.get_option("--verbose")->count() > 0);
  int code = 1;
  try {
    code = action();
  } catch (const std::exception& e) {
    std::cerr << "umbra: error: " << e.what() << umbra::cli::vtkMessagesHint() << std::endl;
    return 1;
  }
  if (const std::string hint = umbra::cli::vtkMessagesHint(); !hint.empty()) {
    std::string first = umbra::cli::firstVtkMessage();
    if (first.size() > 200) first = first.substr(0, 197) + "...";
    std::cerr << "umbra: note: " << first << hint << std::endl;
  }
  return code;
}
