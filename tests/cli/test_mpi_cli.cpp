// umbra across MPI ranks (mpirun -n 2, oversubscribed on a 2-core machine): the frames of
// an animation split over the ranks are the frames of one process; a failing or killed
// rank leaves no frames.
#include "CliRunner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

using namespace umbra::test;

namespace {

const std::string kScene = UMBRA_SOURCE_DIR "/examples/scenes/lunar-eclipse-2015-09-28.json";

/// `mpirun -n ranks umbra args...` (as root too, more ranks than cores allowed).
std::vector<std::string> mpirunArgs(int ranks, const std::vector<std::string>& args) {
  std::vector<std::string> a = {"-n", std::to_string(ranks), "--oversubscribe", "--allow-run-as-root", UMBRA_EXE};
  a.insert(a.end(), args.begin(), args.end());
  return a;
}

std::vector<std::string> animation(const std::string& output) {
  return {"render", kScene, "--size", "64x48", "--from", "2015-09-28T01:00:00Z", "--to", "2015-09-28T03:00:00Z",
          "--step", "30min", "--output", output};
}

/// The names in `dir`, sorted (hidden ones too).
std::vector<std::string> namesIn(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

const std::vector<std::string> kFrames = {"f-00.png", "f-01.png", "f-02.png", "f-03.png", "f-04.png"};

}  // namespace

TEST(RenderMpi, FramesOverTwoRanksAreTheFramesOfOneProcess) {
  TempDir dir;
  const std::vector<std::string> env{"UMBRA_CACHE_DIR=" + dir / "cache"};
  std::filesystem::create_directory(dir / "one");
  std::filesystem::create_directory(dir / "two");
  const RunResult one = run(UMBRA_EXE, animation(dir / "one/f-%02d.png"), env);
  ASSERT_EQ(one.exitCode, 0) << one.err;
  // An empty cache for the ranks: one of them makes the shadow LuT, the other reads it.
  const RunResult two = run(UMBRA_MPIEXEC, mpirunArgs(2, animation(dir / "two/f-%02d.png")),
                            {"UMBRA_CACHE_DIR=" + dir / "cache-two"});
  ASSERT_EQ(two.exitCode, 0) << two.err;
  EXPECT_EQ(namesIn(dir / "two"), kFrames);  // no part file left
  for (const std::string& f : kFrames) EXPECT_EQ(readAll(dir / ("one/" + f)), readAll(dir / ("two/" + f))) << f;
  // One report, rank 0's, naming the ranks.
  EXPECT_EQ(std::count(two.out.begin(), two.out.end(), '\n'), 1) << two.out;
  EXPECT_NE(two.out.find("wrote 5 frames"), std::string::npos) << two.out;
  EXPECT_NE(two.out.find("on 2 ranks"), std::string::npos) << two.out;
  // The LuT made once (its lock gone), and the same as one process makes.
  std::vector<std::string> luts;
  for (const std::string& name : namesIn(dir / "cache-two")) {
    EXPECT_EQ(name.find(".lock"), std::string::npos) << name;
    if (name.rfind("eclipse-shadow-airless-", 0) == 0) luts.push_back(name);
  }
  ASSERT_EQ(luts.size(), 1u);
  EXPECT_EQ(readAll(dir / ("cache/" + luts[0])), readAll(dir / ("cache-two/" + luts[0])));
}

TEST(RenderMpi, ARankThatFailsLeavesNoFrames) {
  TempDir dir;
  std::filesystem::create_directory(dir / "frames");
  // The last frame (rank 1's) cannot be written: its part file's name is taken by a directory.
  std::filesystem::create_directory(dir / "frames/.f-04.part.png");
  const RunResult r = run(UMBRA_MPIEXEC, mpirunArgs(2, animation(dir / "frames/f-%02d.png")),
                          {"UMBRA_CACHE_DIR=" + dir / "cache"});
  EXPECT_NE(r.exitCode, 0);
  // One error, from rank 0, naming the rank, the frame and why (mpirun adds its own lines).
  EXPECT_NE(r.err.find("umbra: error: rank 1: frame 4 (2015-09-28T03:00:00Z, " + dir / "frames/f-04.png" + "): "),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("Is a directory"), std::string::npos) << r.err;
  std::size_t errors = 0;
  for (std::size_t at = r.err.find("umbra: error"); at != std::string::npos; at = r.err.find("umbra: error", at + 1))
    ++errors;
  EXPECT_EQ(errors, 1u) << r.err;
  EXPECT_EQ(namesIn(dir / "frames"), std::vector<std::string>{".f-04.part.png"});  // rank 0's frames gone too
}

TEST(RenderMpi, AKilledRankLeavesNoFramesAndAValidCache) {
  TempDir dir;
  std::filesystem::create_directory(dir / "frames");
  // 25 frames; once the first part file is there, the newest rank is killed.
  std::string command = quote(UMBRA_MPIEXEC);
  for (const std::string& a :
       mpirunArgs(2, {"render", kScene, "--size", "64x48", "--from", "2015-09-28T00:00:00Z", "--to",
                      "2015-09-28T04:00:00Z", "--step", "10min", "--output", dir / "frames/f-%02d.png"}))
    command += " " + quote(a);
  const std::string script = "UMBRA_CACHE_DIR=" + quote(dir / "cache") + " " + command + " >" + quote(dir / "out") +
                             " 2>" + quote(dir / "err") + " & m=$!; for i in $(seq 300); do ls " +
                             quote(dir / "frames") + "/.f-*.part.png >/dev/null 2>&1 && break; sleep 0.1; done; " +
                             "pkill -9 -n -P $m; wait $m; echo $? >" + quote(dir / "rc");
  ASSERT_EQ(std::system(("sh -c " + quote(script)).c_str()), 0);
  EXPECT_NE(std::stoi(readAll(dir / "rc")), 0);
  EXPECT_NE(readAll(dir / "err").find("signal 9"), std::string::npos) << readAll(dir / "err");
  for (const std::string& name : namesIn(dir / "frames")) EXPECT_EQ(name.rfind(".f-", 0), 0u) << name;  // parts only
  // The cache: complete tables only (no temporary, no lock), which a new run reads.
  for (const std::string& name : namesIn(dir / "cache")) {
    EXPECT_EQ(name.find(".lock"), std::string::npos) << name;
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << name;
  }
  const RunResult again = run(UMBRA_EXE, animation(dir / "frames/g-%02d.png"), {"UMBRA_CACHE_DIR=" + dir / "cache"});
  EXPECT_EQ(again.exitCode, 0) << again.err;
}
