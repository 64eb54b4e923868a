// The atmosphere is read once per run, where the user names it (the scene file), and passed
// down as a value (atmosphere::AtmosphereModel) to the tables, the eclipse LuTs and the
// renderer: a render of the 2015 lunar eclipse scene and a 10-frame animation of it each
// read their preset's document once. The commands run in this process, as `umbra` runs them.
#include "AtmosphereModel.hpp"
#include "Commands.hpp"
#include "MieOpticsCache.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace {

// `umbra ARGS` in this process (main.cpp's steps); its exit code.
int runUmbra(std::vector<std::string> args) {
  CLI::App app;
  umbra::cli::Action action;
  umbra::cli::addCommands(app, action);
  umbra::filters::keepMieOpticsInCache("");
  std::reverse(args.begin(), args.end());  // CLI11 takes them last first
  app.parse(args);
  return action();
}

} // namespace

TEST(AtmosphereReads, ARenderAndAnAnimationReadTheirPresetOnce) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "umbra-atmosphere-reads";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string scene = UMBRA_SOURCE_DIR "/examples/scenes/lunar-eclipse-2015-09-28-moon.json";
  const std::vector<std::vector<std::string>> runs = {
      {"render", scene, "--size", "64x36", "--atmosphere-tables", "small", "--output", (dir / "one.exr").string()},
      {"render", scene, "--size", "64x36", "--atmosphere-tables", "small", "--from", "2015-09-28T01:00:00Z", "--to",
       "2015-09-28T03:15:00Z", "--step", "15min", "--output", (dir / "frame-%02d.exr").string()}};
  for (const auto& args : runs) {
    const long before = umbra::atmosphere::AtmosphereModel::documentsRead();
    EXPECT_EQ(runUmbra(args), 0);
    EXPECT_EQ(umbra::atmosphere::AtmosphereModel::documentsRead() - before, 1) << args.size() << " arguments";
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "one.exr"));
  EXPECT_TRUE(std::filesystem::exists(dir / "frame-09.exr"));
  EXPECT_FALSE(std::filesystem::exists(dir / "frame-10.exr"));
  std::filesystem::remove_all(dir);
}
