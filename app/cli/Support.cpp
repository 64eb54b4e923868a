#include "Commands.hpp"

#include <unistd.h>

#include <cstdio>
#include <iostream>

namespace umbra::cli {

void CacheOptions::addTo(CLI::App* command) {
  command->add_option("--cache-dir", this->directory,
                      "Table cache directory (default: $UMBRA_CACHE_DIR, else $XDG_CACHE_HOME/umbra, "
                      "else ~/.cache/umbra)");
  command->add_flag("--no-cache", this->disabled, "Neither read nor write the table cache");
}

ProgressLine::ProgressLine(std::string w) : what(std::move(w)), terminal(::isatty(STDERR_FILENO) != 0) {}

ProgressLine::~ProgressLine() {
  if (this->terminal && this->lastPercent >= 0) std::cerr << "\r\033[K" << std::flush;
}

void ProgressLine::update(double fraction) {
  const int percent = static_cast<int>(fraction * 100.0);
  if (!this->terminal || percent == this->lastPercent) return;
  this->lastPercent = percent;
  std::cerr << "\r" << this->what << ": " << percent << "%" << std::flush;
}

} // namespace umbra::cli
