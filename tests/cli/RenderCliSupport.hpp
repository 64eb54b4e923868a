#pragma once
// `umbra render` to a linear EXR in the CLI tests (needs UMBRA_EXE; an X display).
#include "CliRunner.hpp"

#include "umbra/tables/Exr.h"

#include <glm/vec3.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace umbra::test {

/// Renders `scene` at `size` with small atmosphere tables (and `extra` flags) into
/// dir/frame.exr, the table cache in cacheDir/cache; checks the exit code and that every
/// value is finite.
inline tables::Table renderExr(const TempDir& dir, const std::string& scene, const std::string& size,
                               const std::vector<std::string>& extra = {}, const TempDir* cacheDir = nullptr) {
  std::vector<std::string> args = {"render", scene, "--size", size, "--atmosphere-tables", "small", "--output",
                                   dir / "frame.exr"};
  args.insert(args.end(), extra.begin(), extra.end());
  const RunResult r = run(UMBRA_EXE, args, {"UMBRA_CACHE_DIR=" + (cacheDir ? *cacheDir : dir) / "cache"});
  EXPECT_EQ(r.exitCode, 0) << r.err;
  tables::Table img = tables::readExr(dir / "frame.exr", {"R", "G", "B"});
  for (float v : img.data) EXPECT_TRUE(std::isfinite(v));
  return img;
}

inline glm::dvec3 pixel(const tables::Table& t, int x, int y) { return {t.at(x, y, 0), t.at(x, y, 1), t.at(x, y, 2)}; }

} // namespace umbra::test
