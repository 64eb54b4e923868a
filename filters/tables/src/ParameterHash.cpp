#include <cstdint>
#include <cstdio>

#include "umbra/tables/Table.h"

namespace umbra::tables {

std::string parameterHash(const std::map<std::string, std::string>& parameters) {
  // FNV-1a, 64 bit. std::map orders keys by std::char_traits<char>, i.e. as unsigned
  // bytes, so the order (and the hash) is the same on every platform.
  std::uint64_t h = 0xcbf29ce484222325ULL;
  auto feed = [&h](const std::string& s) {
    for (unsigned char byte : s) {
      h ^= byte;
      h *= 0x100000001b3ULL;
    }
  };
  for (const auto& [key, value] : parameters) {
    feed(key);
    feed("=");
    feed(value);
    feed("\n");
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

}  // namespace umbra::tables
