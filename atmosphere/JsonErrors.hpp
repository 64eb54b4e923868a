#pragma once
// One-line messages for malformed JSON files (atmospheres here, scenes in app/scene):
// "<file>: invalid JSON at line L, column C: <reason>".
#include <nlohmann/json.hpp>

#include <algorithm>
#include <string>

namespace umbra::atmosphere {

inline std::string jsonErrorMessage(const std::string& text, const nlohmann::json::parse_error& e,
                                    const std::string& file) {
  // byte is the 1-based index of the last character read.
  const std::size_t end = std::min<std::size_t>(e.byte, text.size());
  std::size_t line = 1, column = 0;
  for (std::size_t i = 0; i + 1 < end; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 0;
    } else {
      ++column;
    }
  }
  ++column;
  std::string reason = e.what();
  const std::size_t at = reason.find("parse error");
  const std::size_t colon = at == std::string::npos ? at : reason.find(": ", at);
  if (colon != std::string::npos) reason = reason.substr(colon + 2);
  return file + ": invalid JSON at line " + std::to_string(line) + ", column " + std::to_string(column) + ": " + reason;
}

} // namespace umbra::atmosphere
