#pragma once
// One-line messages for malformed JSON files (atmospheres here, scenes in app/scene):
// "<file>: invalid JSON at line L, column C: <reason>", and keys that are not known.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

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

/// The largest scene or atmosphere file read (theirs are a few KB; /dev/zero is endless).
inline constexpr std::size_t kMaxJsonFileBytes = 16u << 20;

/// The text of a scene or atmosphere file, or the one-line reason it cannot be had:
/// "<path>: cannot open file: <why>", "<path>: is a directory, not a file", "<path>: larger
/// than 16 MiB: not a scene or atmosphere file".
struct FileText {
  std::string text;
  std::string error;  ///< empty when text holds the file
};
inline FileText readJsonFileText(const std::string& path) {
  FileText out;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    out.error = path + ": is a directory, not a file";
    return out;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    out.error = path + ": cannot open file: " + std::strerror(errno);
    return out;
  }
  char buffer[65536];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    out.text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (out.text.size() > kMaxJsonFileBytes) {
      out.text.clear();
      out.error = path + ": larger than 16 MiB: not a scene or atmosphere file";
      return out;
    }
  }
  if (in.bad()) out.error = path + ": cannot read file";
  return out;
}

/// The deepest nesting a scene or atmosphere file may have (theirs is at most 6): deeper
/// documents are refused while they are read, before they could exhaust the stack.
inline constexpr int kMaxJsonDepth = 64;

/// Parses a scene or atmosphere file (comments allowed) and returns it, or the one-line
/// message of what is wrong: malformed JSON (jsonErrorMessage), nesting deeper than
/// kMaxJsonDepth, or a key given twice in one object ("<file>: bodies[1].albedo: duplicate
/// key"; JSON would keep the last silently).
template <class Json>
struct ParsedJson {
  Json value;
  std::string error;  ///< empty when value holds the document
};
/// Json: nlohmann::json or nlohmann::ordered_json (keys in the file's order).
template <class Json = nlohmann::json>
ParsedJson<Json> parseJsonFile(const std::string& text, const std::string& file) {
  using json = Json;
  struct Frame {
    bool array = false;
    std::size_t count = 0;  // elements seen (arrays)
    std::string name;       // its place in the document, "" for the root
    std::vector<std::string> keys;
  };
  std::vector<Frame> frames;
  std::string problem;
  auto placeOfNext = [&]() -> std::string {  // the path of the value about to start
    if (frames.empty()) return "";
    Frame& f = frames.back();
    if (f.array) return f.name + "[" + std::to_string(f.count++) + "]";
    return f.keys.empty() ? f.name : (f.name.empty() ? "" : f.name + ".") + f.keys.back();
  };
  const typename json::parser_callback_t check = [&](int depth, typename json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start: {
        if (depth >= kMaxJsonDepth) {
          std::string at = frames.empty() ? std::string("the top") : placeOfNext();
          if (at.size() > 48) at = at.substr(0, 45) + "...";
          problem = file + ": nested more than " + std::to_string(kMaxJsonDepth) + " levels deep (at " + at + ")";
          throw std::length_error(problem);
        }
        Frame f;
        f.array = event == json::parse_event_t::array_start;
        f.name = placeOfNext();
        frames.push_back(std::move(f));
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        if (!frames.empty()) frames.pop_back();
        break;
      case json::parse_event_t::key: {
        Frame& f = frames.back();
        const std::string key = parsed.template get<std::string>();
        if (std::find(f.keys.begin(), f.keys.end(), key) != f.keys.end()) {
          problem = file + ": " + (f.name.empty() ? "" : f.name + ".") + key + ": duplicate key";
          throw std::invalid_argument(problem);
        }
        f.keys.push_back(key);
        break;
      }
      case json::parse_event_t::value:
        if (!frames.empty() && frames.back().array) ++frames.back().count;
        break;
    }
    return true;
  };
  ParsedJson<Json> out;
  try {
    out.value = json::parse(text, check, true, /*ignore_comments=*/true);
  } catch (const nlohmann::json::parse_error& e) {
    out.error = jsonErrorMessage(text, e, file);
  } catch (const nlohmann::json::exception& e) {  // a number too large ("1e999"), ...
    std::string what = e.what();
    if (what.rfind("[json.exception.", 0) == 0 && what.find("] ") != std::string::npos)
      what = what.substr(what.find("] ") + 2);
    out.error = file + ": " + what;
  } catch (const std::exception& e) {
    out.error = problem.empty() ? file + ": " + e.what() : problem;
  }
  return out;
}

/// The first key of a JSON object that is not among `keys`, with the message for it:
/// "unknown key (expected one of: a, b, c)"; nothing when every key is known.
struct UnknownKey {
  std::string key;
  std::string message;
};
template <class Keys>
std::optional<UnknownKey> firstUnknownKeyOf(const nlohmann::json& object, const Keys& keys) {
  std::string list;
  for (const auto& key : keys) list += (list.empty() ? "" : ", ") + std::string(key);
  for (const auto& item : object.items()) {
    if (std::none_of(keys.begin(), keys.end(), [&](const auto& key) { return item.key() == key; }))
      return UnknownKey{item.key(), "unknown key (expected one of: " + list + ")"};
  }
  return std::nullopt;
}
inline std::optional<UnknownKey> firstUnknownKey(const nlohmann::json& object,
                                                 std::initializer_list<const char*> keys) {
  return firstUnknownKeyOf(object, keys);
}
inline std::optional<UnknownKey> firstUnknownKey(const nlohmann::json& object, const std::vector<std::string>& keys) {
  return firstUnknownKeyOf(object, keys);
}

} // namespace umbra::atmosphere
