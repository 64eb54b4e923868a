// umbra: physically based eclipse shadows, from the command line.
// Under mpirun the commands that spread their work over ranks (parallel/Ranks.hpp) run on
// every rank; any other runs on rank 0 alone. Messages come from rank 0.
#include "Commands.hpp"
#include "MieOpticsCache.h"
#include "Ranks.hpp"
#include "VtkMessages.hpp"

#include <iostream>

int main(int argc, char** argv) {
  umbra::parallel::Ranks ranks(&argc, &argv);
  CLI::App app;
  umbra::cli::Action action;
  umbra::cli::addCommands(app, action);
  umbra::filters::keepMieOpticsInCache("");  // a command's --cache-dir / --no-cache changes it
  if (const std::string unknown = umbra::cli::unknownCommandMessage(app, argc, argv); !unknown.empty()) {
    if (ranks.root()) std::cerr << unknown << std::endl;
    return static_cast<int>(CLI::ExitCodes::ExtrasError);
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (!ranks.root()) return e.get_exit_code();
    return app.exit(e);
  }
  umbra::cli::routeVtkMessages(app.get_option("--verbose")->count() > 0);
  const bool everyRank = umbra::cli::spreadsOverRanks(app);
  if (!everyRank && !ranks.root()) return 0;
  // The other ranks' messages would repeat rank 0's: their errors reach rank 0 (Ranks::finish).
  std::ostream quiet(nullptr);
  if (!ranks.root()) {
    std::cout.rdbuf(quiet.rdbuf());
    std::cerr.rdbuf(quiet.rdbuf());
  }
  if (!everyRank && ranks.size() > 1)
    std::cerr << "umbra: note: this command runs on one rank: rank 0 does it, the other " << ranks.size() - 1
              << " wait\n";
  int code = 1;
  try {
    code = action();
  } catch (const std::exception& e) {
    if (ranks.root()) std::cerr << "umbra: error: " << e.what() << umbra::cli::vtkMessagesHint() << std::endl;
    return 1;
  }
  if (const std::string hint = umbra::cli::vtkMessagesHint(); !hint.empty() && ranks.root()) {
    std::string first = umbra::cli::firstVtkMessage();
    if (first.size() > 200) first = first.substr(0, 197) + "...";
    std::cerr << "umbra: note: " << first << hint << std::endl;
  }
  return code;
}
