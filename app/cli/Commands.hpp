#pragma once
// The `umbra` command line: one function per subcommand registers its options on the
// CLI11 app and returns the action to run once the command line has been parsed.
#include <CLI/CLI.hpp>

#include "scene/Time.hpp"

class vtkImageData;
class vtkObject;

#include <chrono>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

namespace umbra::cli {

/// What a subcommand runs; returns the process exit code.
using Action = std::function<int()>;

/// Bad input found while running a command (the message is printed as one line).
struct CommandError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Options shared by the commands that build tables.
struct CacheOptions {
  std::string directory;  ///< empty: $UMBRA_CACHE_DIR, $XDG_CACHE_HOME/umbra or ~/.cache/umbra
  bool disabled = false;
  /// Not an option: the LuTs' texels shared by the MPI ranks (precompute shadow, eclipse).
  bool overRanks = false;
  void addTo(CLI::App* command);
};

/// --time's instant (ISO 8601 UTC), or now (to the second) when it is empty. Throws
/// CommandError naming --time.
scene::UtcTime timeOption(const std::string& text);

/// The instants from --from to --to (inclusive) every --step (a duration such as 30min:
/// units s, min, h, d), at most 100 000 of them. Throws CommandError naming the option.
std::vector<scene::UtcTime> timeSteps(const std::string& from, const std::string& to, const std::string& step);

/// Writes `image` as a PNG under a temporary name and renames it to `path` (VTK's first row
/// is the picture's bottom). Throws CommandError naming the path.
void writePng(vtkImageData* image, const std::string& path);

/// One "umbra: note:" line on stderr when the first or the last of `times` lies beyond
/// the years the ephemerides are fitted to (scene::ephemerisRangeNote).
void noteTimesBeyondEphemeris(const std::vector<scene::UtcTime>& times);

/// The whole command line on `app`: its description, version flag, one-line parse
/// errors, every command and the number checks; `action` is set by the command parsed.
void addCommands(CLI::App& app, Action& action);

/// "" when the command line's first word that is not an option names one of `app`'s
/// commands (or there is none), else a one-line error naming the word and listing them.
std::string unknownCommandMessage(const CLI::App& app, int argc, const char* const* argv);

/// Whether the command parsed on `app` spreads its work over MPI ranks (the others run on
/// rank 0 alone): render (an animation's frames), precompute shadow and eclipse (the LuTs'
/// texels, and the atmosphere tables' wavelengths), atmosphere precompute (the wavelengths),
/// sweep (its cases), terrain lighting (its time steps).
bool spreadsOverRanks(const CLI::App& app);

/// Under mpirun, how a command's run went over the ranks, for its last line: " on N ranks in
/// T s (in collectives: rank 0 C s, at most M s)", C the time rank 0 spent communicating and
/// waiting for the others, M the most any rank spent so (parallel::Ranks), T counted from
/// `start`; run directly, empty.
std::string ranksNote(std::chrono::steady_clock::time_point start);

/// Every option of `app` and its subcommands that takes a value refuses an empty one, and
/// every number option NaN and infinities, naming the option (CLI11 would read "" as 0 and
/// let NaN through its ranges).
void refuseEmptyAndNonFinite(CLI::App& app);

void addRenderCommand(CLI::App& app, Action& action);
void addMoonCommand(CLI::App& app, Action& action);
void addPlanetsCommand(CLI::App& app, Action& action);
void addEclipsesCommand(CLI::App& app, Action& action);
void addEclipseCommand(CLI::App& app, Action& action);
void addPrecomputeCommand(CLI::App& app, Action& action);
void addProfileCommand(CLI::App& app, Action& action);
void addInspectCommand(CLI::App& app, Action& action);
void addAtmosphereCommand(CLI::App& app, Action& action);
void addTerrainCommand(CLI::App& app, Action& action);
/// `terrain lighting`, under the `terrain` command (TerrainLightingCommand.cpp).
void addTerrainLightingCommand(CLI::App* terrainCmd, Action& action);
void addSweepCommand(CLI::App& app, Action& action);

/// Progress for long work on stderr: a live percentage on a terminal, quiet otherwise,
/// never going back while shown; the line is cleared when the work is done (fraction 1)
/// or the ProgressLine ends. With a
/// `source` it follows that VTK object's vtkCommand::ProgressEvent while it lives.
class ProgressLine {
public:
  explicit ProgressLine(std::string what, vtkObject* source = nullptr);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;
  void update(double fraction);

private:
  void onProgress(vtkObject*, unsigned long, void* fraction);
  void clear();
  std::string what;
  int lastPercent = -1;
  bool terminal;
  bool done = false;  ///< the last run reached 1: later reports are dropped until one at 0
  std::mutex mutex;
  vtkObject* source = nullptr;
  unsigned long observer = 0;
};

} // namespace umbra::cli
