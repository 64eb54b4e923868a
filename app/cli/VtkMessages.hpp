#pragma once
// VTK's messages (warnings, errors, GL errors; many lines each) kept off the terminal: a
// failure reads as umbra's one error line. With --verbose each message is printed as it
// comes, folded to one line and prefixed "umbra: vtk:".
#include <cstddef>
#include <string>

namespace umbra::cli {

/// Installs the collector as VTK's output window for the life of the process (first call;
/// later calls change only `verbose`).
void routeVtkMessages(bool verbose);

/// Messages VTK gave since routeVtkMessages, and the first of them folded to one line.
std::size_t vtkMessageCount();
std::string firstVtkMessage();

/// " (VTK gave N messages; --verbose shows them)" after a failure's line, or "" when there
/// were none or they were shown.
std::string vtkMessagesHint();

}  // namespace umbra::cli
