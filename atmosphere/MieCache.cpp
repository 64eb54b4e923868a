#include "MieCache.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <utility>

namespace umbra::atmosphere {
namespace {

/// Changes whenever mieLogNormal's results would (a kept result of an older one is not read).
constexpr const char* kFormat = "1";
/// The most results kept in memory (a few kB each); beyond, the memory starts again empty.
constexpr std::size_t kMemoryEntries = 4096;

struct State {
  std::mutex mutex;
  MieStore store;
  std::map<MieKey, MieAerosol> memory;
  MieCacheCounts counts;
};
State& state() {
  static State s;
  return s;
}

std::string exact(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%a", v);
  return text;
}

/// The key of a population of one particle per cubic metre: the results of any other number
/// density are these times it (mieLogNormal scales by it last), so they share one entry.
MieKey keyOf(double wavelengthM, std::complex<double> m, const LogNormalSizes& sizes, int phaseSamples, int extraLevels,
             double bulkTolerance, double phaseTolerance) {
  return {{"format", kFormat},
          {"wavelengthM", exact(wavelengthM)},
          {"refractiveIndexReal", exact(m.real())},
          {"refractiveIndexImag", exact(m.imag())},
          {"medianRadiusM", exact(sizes.medianRadiusM)},
          {"geometricStdDev", exact(sizes.geometricStdDev)},
          {"minRadiusM", exact(sizes.minRadiusM)},
          {"maxRadiusM", exact(sizes.maxRadiusM)},
          {"phaseSamples", std::to_string(phaseSamples)},
          {"extraLevels", std::to_string(extraLevels)},
          {"bulkTolerance", exact(bulkTolerance)},
          {"phaseTolerance", exact(phaseTolerance)}};
}

/// A result for one particle per cubic metre at another number density, as mieLogNormal
/// gives it (the same products, in the same order).
MieAerosol scaled(MieAerosol a, double numberDensityPerM3) {
  a.extinctionPerM *= numberDensityPerM3;
  a.scatteringPerM *= numberDensityPerM3;
  a.absorptionPerM = std::max(0.0, a.extinctionPerM - a.scatteringPerM);
  return a;
}

}  // namespace

void setMieStore(MieStore store) {
  State& s = state();
  const std::lock_guard<std::mutex> lock(s.mutex);
  s.store = std::move(store);
}

MieCacheCounts mieCacheCounts() {
  State& s = state();
  const std::lock_guard<std::mutex> lock(s.mutex);
  return s.counts;
}

void forgetMieResults() {
  State& s = state();
  const std::lock_guard<std::mutex> lock(s.mutex);
  s.memory.clear();
  s.counts = {};
}

MieAerosol cachedMieLogNormal(double wavelengthM, std::complex<double> m, const LogNormalSizes& sizes, int phaseSamples,
                              int extraLevels, double bulkTolerance, double phaseTolerance) {
  const MieKey key = keyOf(wavelengthM, m, sizes, phaseSamples, extraLevels, bulkTolerance, phaseTolerance);
  State& s = state();
  MieStore store;
  {
    const std::lock_guard<std::mutex> lock(s.mutex);
    if (auto it = s.memory.find(key); it != s.memory.end()) {
      ++s.counts.fromMemory;
      return scaled(it->second, sizes.numberDensityPerM3);
    }
    store = s.store;
  }
  // Loaded or computed outside the lock: wavelengths run in parallel (two threads asking
  // for the same key both compute it, and keep the same result).
  std::optional<MieAerosol> one;
  auto fromStore = [&] {
    if (store.load)
      if (const std::optional<nlohmann::json> document = store.load(key)) one = mieFromJson(*document, phaseSamples);
  };
  fromStore();
  std::shared_ptr<void> held;  // another process computing the key: wait, then read its result
  if (!one && store.hold && (held = store.hold(key))) fromStore();
  const bool loaded = one.has_value();
  if (!loaded) {
    LogNormalSizes unit = sizes;
    unit.numberDensityPerM3 = 1.0;
    one = mieLogNormal(wavelengthM, m, unit, phaseSamples, extraLevels, bulkTolerance, phaseTolerance);
    if (store.store) store.store(key, mieToJson(*one));
  }
  {
    const std::lock_guard<std::mutex> lock(s.mutex);
    ++(loaded ? s.counts.fromStore : s.counts.computed);
    if (s.memory.size() >= kMemoryEntries) s.memory.clear();
    s.memory.emplace(key, *one);
  }
  return scaled(std::move(*one), sizes.numberDensityPerM3);
}

nlohmann::json mieToJson(const MieAerosol& a) {
  return {{"scatteringPerM", a.scatteringPerM},
          {"extinctionPerM", a.extinctionPerM},
          {"absorptionPerM", a.absorptionPerM},
          {"asymmetry", a.asymmetry},
          {"cosTheta", a.cosTheta},
          {"phase", a.phase},
          {"sizeNodes", a.sizeNodes},
          {"minSizeParameter", a.minSizeParameter},
          {"maxSizeParameter", a.maxSizeParameter},
          {"converged", a.converged},
          {"quadratureChange", a.quadratureChange}};
}

std::optional<MieAerosol> mieFromJson(const nlohmann::json& d, int phaseSamples) {
  try {
    MieAerosol a;
    auto finite = [&](const char* name) {
      const double v = d.at(name).get<double>();
      if (!std::isfinite(v)) throw std::domain_error(name);
      return v;
    };
    a.scatteringPerM = finite("scatteringPerM");
    a.extinctionPerM = finite("extinctionPerM");
    a.absorptionPerM = finite("absorptionPerM");
    a.asymmetry = finite("asymmetry");
    a.minSizeParameter = finite("minSizeParameter");
    a.maxSizeParameter = finite("maxSizeParameter");
    a.quadratureChange = finite("quadratureChange");
    a.sizeNodes = d.at("sizeNodes").get<int>();
    a.converged = d.at("converged").get<bool>();
    a.cosTheta = d.at("cosTheta").get<std::vector<double>>();
    a.phase = d.at("phase").get<std::vector<double>>();
    const auto size = static_cast<std::size_t>(phaseSamples);
    if (a.cosTheta.size() != size || a.phase.size() != size) return std::nullopt;
    for (std::size_t j = 0; j < size; ++j)
      if (!std::isfinite(a.cosTheta[j]) || !std::isfinite(a.phase[j])) return std::nullopt;
    return a;
  } catch (const std::exception&) {
    return std::nullopt;  // not a result: computed again
  }
}

}  // namespace umbra::atmosphere
