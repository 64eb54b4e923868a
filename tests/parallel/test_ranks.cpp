// The ranks' shares of the work, and a process run directly: one rank, MPI not started.
#include "Ranks.hpp"

#include <gtest/gtest.h>

#include <cstdlib>

using umbra::parallel::Ranks;
using umbra::parallel::share;

TEST(Share, ConsecutiveSharesCoverEveryItemOnceAndDifferByOneAtMost) {
  for (std::size_t count : {0u, 1u, 2u, 5u, 7u, 64u, 1000u})
    for (int size : {1, 2, 3, 8, 64}) {
      std::size_t next = 0, least = count, most = 0;
      for (int r = 0; r < size; ++r) {
        const auto [begin, end] = share(count, r, size);
        EXPECT_EQ(begin, next) << count << " over " << size;
        ASSERT_LE(begin, end);
        least = std::min(least, end - begin);
        most = std::max(most, end - begin);
        next = end;
      }
      EXPECT_EQ(next, count);
      EXPECT_LE(most - least, 1u);
      EXPECT_EQ(most, (count + size - 1) / size);
    }
  EXPECT_THROW(share(4, 2, 2), std::invalid_argument);
  EXPECT_THROW(share(4, 0, 0), std::invalid_argument);
}

TEST(Ranks, RunDirectlyOneRankWithoutMpi) {
  // Unless this test itself runs under mpirun.
  if (umbra::parallel::launchedByMpi()) GTEST_SKIP() << "under an MPI launcher";
  Ranks& world = Ranks::world();
  EXPECT_EQ(world.rank(), 0);
  EXPECT_EQ(world.size(), 1);
  EXPECT_TRUE(world.root());
  EXPECT_FALSE(world.mpi());
  EXPECT_EQ(world.gather(std::vector<float>{1.5f, 2.5f}), (std::vector<float>{1.5f, 2.5f}));
  EXPECT_EQ(world.gather(std::string("x")), std::vector<std::string>{"x"});
  EXPECT_EQ(world.broadcast("y"), "y");
  EXPECT_EQ(world.finish(""), "");
  EXPECT_EQ(world.finish("bad case"), "bad case");  // one rank: no "rank 0:" in front
}

TEST(Ranks, LaunchedByMpiFollowsTheLaunchersVariables) {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"}) {
    const char* was = std::getenv(name);
    const std::string saved = was ? was : "";
    ::setenv(name, "2", 1);
    EXPECT_TRUE(umbra::parallel::launchedByMpi()) << name;
    ::setenv(name, "", 1);
    if (was) ::setenv(name, saved.c_str(), 1); else ::unsetenv(name);
  }
}
