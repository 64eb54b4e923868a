#pragma once
// The Lorenz-Mie optics of the aerosol components, kept between uses: in this process's
// memory (an atmosphere loaded again, or by another part of the program, runs no Lorenz-Mie),
// and in a store the program plugs in (the table cache's JSON entries: the next run reads
// them). Keyed by every input of mieLogNormal written exactly (hexadecimal floats).
#include "Mie.hpp"

#include <nlohmann/json.hpp>

#include <complex>
#include <cstddef>
#include <functional>
#include <memory>
#include <map>
#include <optional>
#include <string>

namespace umbra::atmosphere {

/// The inputs of one mieLogNormal call as exact text: the key its result is kept under.
using MieKey = std::map<std::string, std::string>;

/// Where results persist between processes: `load` gives the document stored under a key
/// (nullopt: none), `store` keeps one; while what `hold` gives for a key lives, no other
/// process computes that key (the table cache's lock), and `load` is asked again under it.
/// Any may be empty; none may throw.
struct MieStore {
  std::function<std::optional<nlohmann::json>(const MieKey&)> load;
  std::function<void(const MieKey&, const nlohmann::json&)> store;
  std::function<std::shared_ptr<void>(const MieKey&)> hold;
};

/// Replaces the store (by default there is none: results live in memory for the process).
void setMieStore(MieStore store);

/// mieLogNormal (same arguments) through the caches: this process's memory, then the store,
/// else computed and kept in both. The result is mieLogNormal's to the bit.
MieAerosol cachedMieLogNormal(double wavelengthM, std::complex<double> m, const LogNormalSizes& sizes, int phaseSamples,
                              int extraLevels, double bulkTolerance, double phaseTolerance);

/// How the calls went since the process started (or forgetMieResults).
struct MieCacheCounts {
  std::size_t fromMemory = 0, fromStore = 0, computed = 0;
};
MieCacheCounts mieCacheCounts();
/// Empties the process's memory of results and zeroes the counts (the store is left alone).
void forgetMieResults();

/// A result as a JSON document (doubles written so that they read back to the bit), and
/// back: nullopt unless the document is a complete result with finite values and
/// `phaseSamples` phase-table entries.
nlohmann::json mieToJson(const MieAerosol& optics);
std::optional<MieAerosol> mieFromJson(const nlohmann::json& document, int phaseSamples);

}  // namespace umbra::atmosphere
