// umbra render SCENE [--time ISO8601] [--size WxH] --output FILE.png|FILE.exr
// (filled in when the render pass lands)
#include "Commands.hpp"

namespace umbra::cli {
void addRenderCommand(CLI::App&, Action&) {}
} // namespace umbra::cli
