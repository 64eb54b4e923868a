#include "MieOpticsCache.h"

#include "MieCache.hpp"
#include "umbra/tables/TableCache.h"

#include <exception>

namespace umbra::filters {

void keepMieOpticsInCache(const std::string& directory, bool enabled) {
  if (!enabled) {
    atmosphere::setMieStore({});
    return;
  }
  const tables::TableCache cache(directory.empty() ? tables::TableCache::defaultDirectory() : directory);
  constexpr const char* kKind = "mie-optics";
  atmosphere::MieStore store;
  store.load = [cache](const atmosphere::MieKey& key) -> std::optional<nlohmann::json> {
    try {
      return cache.loadJson(kKind, key);
    } catch (const std::exception&) {
      return std::nullopt;
    }
  };
  store.store = [cache](const atmosphere::MieKey& key, const nlohmann::json& document) {
    try {
      cache.storeJson(kKind, key, document);
    } catch (const std::exception&) {
      // a read-only or full cache: computed again next time
    }
  };
  store.hold = [cache](const atmosphere::MieKey& key) -> std::shared_ptr<void> {
    try {
      return cache.lock(kKind, key);
    } catch (const std::exception&) {
      return nullptr;
    }
  };
  atmosphere::setMieStore(std::move(store));
}

}  // namespace umbra::filters
