#include "StarCatalogueCache.h"

#include "OutputFile.hpp"
#include "umbra/tables/Table.h"
#include "umbra/tables/TableCache.h"

#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <system_error>

namespace umbra::pipeline {
namespace {

namespace fs = std::filesystem;

constexpr char kMagic[8] = {'U', 'M', 'B', 'R', 'A', 'S', 'T', 'R'};
constexpr std::uint64_t kVersion = 1;
constexpr std::size_t kValuesPerStar = 7;
constexpr std::size_t kHeaderBytes = sizeof kMagic + 2 * sizeof(std::uint64_t);

std::vector<sky::CatalogueStar> readCopy(const std::string& copy) {
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(copy, ec);
  if (ec || size < kHeaderBytes) return {};
  std::ifstream in(copy, std::ios::binary);
  char magic[sizeof kMagic];
  std::uint64_t version = 0, count = 0;
  in.read(magic, sizeof magic);
  in.read(reinterpret_cast<char*>(&version), sizeof version);
  in.read(reinterpret_cast<char*>(&count), sizeof count);
  if (!in || std::memcmp(magic, kMagic, sizeof kMagic) != 0 || version != kVersion || count == 0 ||
      count > (size - kHeaderBytes) / (kValuesPerStar * sizeof(double)) ||
      size != kHeaderBytes + count * kValuesPerStar * sizeof(double))
    return {};
  std::vector<double> values(count * kValuesPerStar);
  in.read(reinterpret_cast<char*>(values.data()), static_cast<std::streamsize>(values.size() * sizeof(double)));
  if (!in) return {};
  std::vector<sky::CatalogueStar> stars(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double* v = &values[i * kValuesPerStar];
    sky::CatalogueStar& s = stars[i];
    s.raRad = v[0], s.decRad = v[1], s.pmRaCosDecMasPerYear = v[2], s.pmDecMasPerYear = v[3];
    s.parallaxMas = v[4], s.vMag = v[5], s.bMinusV = v[6];
  }
  return stars;
}

void writeCopy(const std::string& copy, const std::vector<sky::CatalogueStar>& stars) {
  std::error_code ec;
  fs::create_directories(fs::path(copy).parent_path(), ec);
  try {
    output::OutputFile file(copy);  // written aside, then renamed: never half a copy
    {
      std::ofstream out(file.tempPath(), std::ios::binary | std::ios::trunc);
      const std::uint64_t version = kVersion, count = stars.size();
      out.write(kMagic, sizeof kMagic);
      out.write(reinterpret_cast<const char*>(&version), sizeof version);
      out.write(reinterpret_cast<const char*>(&count), sizeof count);
      for (const sky::CatalogueStar& s : stars) {
        const double v[kValuesPerStar] = {s.raRad, s.decRad, s.pmRaCosDecMasPerYear, s.pmDecMasPerYear,
                                          s.parallaxMas, s.vMag, s.bMinusV};
        out.write(reinterpret_cast<const char*>(v), sizeof v);
      }
      if (!out) return;  // the OutputFile removes its temporary
    }
    file.commit();
  } catch (const std::runtime_error&) {
    // A cache that cannot be written (read-only, full) only costs the next read its speed.
  }
}

}  // namespace

namespace {

/// What names the copy of catalogue `path`: the file as it is now.
std::map<std::string, std::string> copyKey(const std::string& path) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  const std::uintmax_t size = fs::file_size(path, ec);
  const auto time = fs::last_write_time(path, ec).time_since_epoch();
  return {{"kind", "star-catalogue"},
          {"path", absolute.string()},
          {"size", std::to_string(size)},
          {"mtime", std::to_string(std::chrono::duration_cast<std::chrono::nanoseconds>(time).count())},
          {"version", std::to_string(kVersion)}};
}

}  // namespace

std::string starCatalogueCopyPath(const std::string& path, const std::string& cacheDirectory) {
  return (fs::path(cacheDirectory) / ("star-catalogue-" + tables::parameterHash(copyKey(path)) + ".bin")).string();
}

std::vector<sky::CatalogueStar> readStarCatalogue(const std::string& path, const std::string& cacheDirectory) {
  if (!fs::is_regular_file(path)) return sky::readCatalogue(path);  // its error
  const std::string copy = starCatalogueCopyPath(path, cacheDirectory);
  std::vector<sky::CatalogueStar> stars = readCopy(copy);
  if (!stars.empty()) return stars;
  // Several processes at once (the ranks of an MPI run): one writes the copy, the others
  // wait and read it.
  const auto lock = tables::TableCache(cacheDirectory).lock("star-catalogue", copyKey(path));
  if (lock && !(stars = readCopy(copy)).empty()) return stars;
  stars = sky::readCatalogue(path);
  for (sky::CatalogueStar& s : stars) s.name.clear();
  writeCopy(copy, stars);
  return stars;
}

std::shared_ptr<const std::vector<sky::CatalogueStar>> starCatalogue(const std::string& path) {
  return sky::cachedCatalogue(path, [](const std::string& p) {
    return readStarCatalogue(p, tables::TableCache::defaultDirectory());
  });
}

}  // namespace umbra::pipeline
