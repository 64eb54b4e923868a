#pragma once
// The star catalogue as scenes read it: once per process (sky::cachedCatalogue), and from a
// binary copy in the table cache rather than the text when the text has been read before.
//
// The copy is <cache dir>/star-catalogue-<hash>.bin, the hash (tables::parameterHash) over
// the text file's absolute path, size and modification time and the copy's format version,
// as the tables are keyed by their parameters. It holds a header (magic "UMBRASTR", version,
// star count) and each star's seven numbers as little-endian doubles, exactly as parsed;
// the names are not kept. A copy that does not match (wrong magic, version or size) is read
// past and written again; one that cannot be written (a read-only cache) is not an error.
#include "StarCatalogue.hpp"

#include <memory>
#include <string>
#include <vector>

namespace umbra::pipeline {

/// The binary copy's file for the catalogue at `path` in `cacheDirectory`.
std::string starCatalogueCopyPath(const std::string& path, const std::string& cacheDirectory);

/// Every star of the catalogue at `path` without names: from the copy in `cacheDirectory`
/// when it matches, else from the text (sky::readCatalogue, then the copy is written).
std::vector<sky::CatalogueStar> readStarCatalogue(const std::string& path, const std::string& cacheDirectory);

/// readStarCatalogue once per process, in tables::TableCache::defaultDirectory().
std::shared_ptr<const std::vector<sky::CatalogueStar>> starCatalogue(const std::string& path);

}  // namespace umbra::pipeline
