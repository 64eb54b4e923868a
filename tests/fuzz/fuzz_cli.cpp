// The command line's options (app/cli): the input's lines are the arguments; any of them
// give a parsed command or a CLI11 parse error (no action runs: they compute), and the
// value parsers behind the options (times, lengths, durations) their own errors.
#include "Commands.hpp"
#include "scene/Time.hpp"
#include "scene/Units.hpp"

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> args;
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  for (std::string line; std::getline(in, line) && args.size() < 32;) args.push_back(line);
  for (const std::string& a : args) {
    try {
      umbra::scene::parseUtc(a);
    } catch (const std::invalid_argument&) {
    }
    try {
      umbra::scene::parseLengthM(a);
    } catch (const std::invalid_argument&) {
    }
    try {
      umbra::scene::parseDurationS(a);
    } catch (const std::invalid_argument&) {
    }
  }
  // One command line for every input (building it costs more than a parse); clear() forgets
  // the last parse.
  static umbra::cli::Action action;
  static CLI::App& app = [] () -> CLI::App& {
    static CLI::App a;
    umbra::cli::addCommands(a, action);
    return a;
  }();
  app.clear();
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError&) {
  }
  return 0;
}
