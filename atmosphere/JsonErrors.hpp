#pragma once
// One-line messages for malformed JSON files (atmospheres here, scenes in app/scene):
// "<file>: invalid JSON at line L, column C: <reason>", and keys that are not known.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <initializer_list>
#include <optional>
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

/// The first key of a JSON object that is not among `keys`, with the message for it:
/// "unknown key (expected one of: a, b, c)"; nothing when every key is known.
struct UnknownKey {
  std::string key;
  std::string message;
};
inline std::optional<UnknownKey> firstUnknownKey(const nlohmann::json& object,
                                                 std::initializer_list<const char*> keys) {
  std::string list;
  for (const char* key : keys) list += (list.empty() ? "" : ", ") + std::string(key);
  for (const auto& item : object.items()) {
    if (std::none_of(keys.begin(), keys.end(), [&](const char* key) { return item.key() == key; }))
      return UnknownKey{item.key(), "unknown key (expected one of: " + list + ")"};
  }
  return std::nullopt;
}

} // namespace umbra::atmosphere
