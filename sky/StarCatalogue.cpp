#include "StarCatalogue.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

namespace umbra::sky {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// The number in columns [begin, end) of `line`, all of it.
double field(const std::string& line, std::size_t begin, std::size_t end, const char* what) {
  if (line.size() < end) throw std::invalid_argument(std::string(what) + ": the line ends before column " + std::to_string(end));
  const std::string text = line.substr(begin, end - begin);
  const char* start = text.c_str();
  while (*start == ' ') ++start;
  char* stop = nullptr;
  errno = 0;
  const double value = std::strtod(start, &stop);
  if (stop == start || *stop != '\0' || errno == ERANGE || !std::isfinite(value))
    throw std::invalid_argument(std::string(what) + ": expected a number in columns " + std::to_string(begin + 1) + "-" +
                                std::to_string(end) + ", got '" + text + "'");
  return value;
}

std::string trimmed(const std::string& s) {
  const std::size_t a = s.find_first_not_of(' '), b = s.find_last_not_of(' ');
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

}  // namespace

std::optional<CatalogueStar> parseKStarsLine(const std::string& line) {
  if (line.empty() || line[0] == '#' || trimmed(line).empty()) return std::nullopt;
  CatalogueStar s;
  const double h = field(line, 0, 2, "RA hours"), m = field(line, 2, 4, "RA minutes"), sec = field(line, 4, 9, "RA seconds");
  // Seconds of 60.00 occur (rounded up): they are taken as they are.
  if (h >= 24.0 || m >= 60.0 || sec > 60.0) throw std::invalid_argument("RA: '" + line.substr(0, 9) + "' is not hhmmss.ss");
  s.raRad = (h + m / 60.0 + sec / 3600.0) * kPi / 12.0;
  if (line.size() < 19 || (line[10] != '+' && line[10] != '-'))
    throw std::invalid_argument("Dec: expected a sign in column 11");
  const double d = field(line, 11, 13, "Dec degrees"), dm = field(line, 13, 15, "Dec minutes"),
               ds = field(line, 15, 19, "Dec seconds");
  if (d > 90.0 || dm >= 60.0 || ds > 60.0) throw std::invalid_argument("Dec: '" + line.substr(10, 9) + "' is not sddmmss.s");
  s.decRad = (line[10] == '-' ? -1.0 : 1.0) * (d + dm / 60.0 + ds / 3600.0) * kPi / 180.0;
  if (std::abs(s.decRad) > kPi / 2.0) throw std::invalid_argument("Dec: beyond a pole");
  s.pmRaCosDecMasPerYear = field(line, 20, 29, "proper motion in RA");
  s.pmDecMasPerYear = field(line, 29, 38, "proper motion in Dec");
  s.parallaxMas = field(line, 38, 45, "parallax");
  s.vMag = field(line, 46, 51, "magnitude");
  s.bMinusV = field(line, 51, 56, "B-V");
  if (const std::size_t comma = line.find(','); comma != std::string::npos) {
    const std::string rest = line.substr(comma + 1);
    const std::size_t second = rest.find(',');
    const std::string bayer = trimmed(rest.substr(0, second));
    const std::string common = second == std::string::npos ? "" : trimmed(rest.substr(second + 1));
    s.name = common.empty() ? bayer : common;
  }
  return s;
}

std::optional<CatalogueStar> parseXplanetLine(const std::string& line) {
  if (line.empty() || line[0] == '#' || trimmed(line).empty()) return std::nullopt;
  const std::size_t quote = line.find('"');
  std::istringstream numbers(line.substr(0, quote));
  std::string dec, ra, mag;
  numbers >> dec >> ra >> mag;
  const auto number = [](const std::string& text, const char* what) {
    char* stop = nullptr;
    errno = 0;
    const double value = std::strtod(text.c_str(), &stop);
    if (text.empty() || *stop != '\0' || errno == ERANGE || !std::isfinite(value))
      throw std::invalid_argument(std::string(what) + ": expected a number, got '" + text + "'");
    return value;
  };
  CatalogueStar s;
  const double decDeg = number(dec, "Dec (deg)"), raHours = number(ra, "RA (h)");
  if (std::abs(decDeg) > 90.0) throw std::invalid_argument("Dec (deg): beyond a pole");
  if (raHours < 0.0 || raHours > 24.0) throw std::invalid_argument("RA (h): outside [0, 24]");
  s.decRad = decDeg * kPi / 180.0;
  s.raRad = raHours * kPi / 12.0;
  s.vMag = number(mag, "magnitude");
  s.bMinusV = kColourlessBMinusV;
  if (quote != std::string::npos) {
    const std::size_t close = line.find('"', quote + 1);
    s.name = trimmed(line.substr(quote + 1, close == std::string::npos ? std::string::npos : close - quote - 1));
  }
  return s;
}

namespace {

using LineParser = std::optional<CatalogueStar> (*)(const std::string&);

// Every star of `in` through `parse`, down to faintestVMag; errors name path and line.
std::vector<CatalogueStar> readWith(std::istream& in, const std::string& path, double faintestVMag, LineParser parse) {
  std::vector<CatalogueStar> stars;
  std::string line;
  for (long number = 1; std::getline(in, line); ++number) {
    try {
      const std::optional<CatalogueStar> star = parse(line);
      if (!star) continue;
      if (star->vMag > faintestVMag) break;
      stars.push_back(*star);
    } catch (const std::invalid_argument& e) {
      throw StarCatalogueError(path + ":" + std::to_string(number) + ": " + e.what());
    }
  }
  if (in.bad()) throw StarCatalogueError(path + ": read error");
  if (stars.empty() && faintestVMag >= 99.0) throw StarCatalogueError(path + ": no stars");
  return stars;
}

std::ifstream openCatalogue(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw StarCatalogueError(path + ": cannot open: " + std::strerror(errno) +
                                    " (the star catalogue comes with Debian's kstars-data)");
  return in;
}

}  // namespace

std::vector<CatalogueStar> readKStarsCatalogue(const std::string& path, double faintestVMag) {
  std::ifstream in = openCatalogue(path);
  return readWith(in, path, faintestVMag, parseKStarsLine);
}

std::vector<CatalogueStar> readCatalogue(const std::string& path, double faintestVMag) {
  std::ifstream in = openCatalogue(path);
  std::string line;
  bool xplanet = false;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || trimmed(line).empty()) continue;
    xplanet = line.find('"') != std::string::npos;
    break;
  }
  in.clear();
  in.seekg(0);
  return readWith(in, path, faintestVMag, xplanet ? parseXplanetLine : parseKStarsLine);
}

std::shared_ptr<const std::vector<CatalogueStar>> cachedCatalogue(const std::string& path, const CatalogueReader& read) {
  struct Entry {
    std::uintmax_t size = 0;
    std::filesystem::file_time_type time;
    std::shared_ptr<const std::vector<CatalogueStar>> stars;
  };
  static std::mutex mutex;
  static std::map<std::string, Entry> entries;
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  const std::filesystem::file_time_type time = ec ? std::filesystem::file_time_type() : std::filesystem::last_write_time(path, ec);
  const std::lock_guard<std::mutex> lock(mutex);
  auto it = entries.find(path);
  if (!ec && it != entries.end() && it->second.size == size && it->second.time == time) return it->second.stars;
  auto stars = std::make_shared<const std::vector<CatalogueStar>>(read ? read(path) : readCatalogue(path));
  if (!ec) entries[path] = {size, time, stars};
  return stars;
}

}  // namespace umbra::sky
