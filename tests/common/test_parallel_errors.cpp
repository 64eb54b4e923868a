// ParallelErrors: an exception thrown in an OpenMP parallel loop reaches the caller (it
// used to end the program in std::terminate), the first one, and the loop stops early.
#include "ParallelErrors.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>

using umbra::ParallelErrors;

TEST(ParallelErrors, TheFirstExceptionReachesTheCaller) {
  ParallelErrors errors;
  std::atomic<int> ran{0};
  const int n = 100000;
#pragma omp parallel for schedule(dynamic, 1)
  for (int k = 0; k < n; ++k) errors.run([&] {
    ++ran;
    if (k % 10 == 7) throw std::invalid_argument("bad iteration");
  });
  EXPECT_TRUE(errors.failed());
  EXPECT_THROW(errors.rethrow(), std::invalid_argument);
  EXPECT_LT(ran.load(), n);  // the iterations after a failure are skipped
}

TEST(ParallelErrors, NoExceptionNoThrow) {
  ParallelErrors errors;
  std::atomic<long> sum{0};
#pragma omp parallel for
  for (int k = 0; k < 1000; ++k) errors.run([&] { sum += k; });
  EXPECT_FALSE(errors.failed());
  EXPECT_NO_THROW(errors.rethrow());
  EXPECT_EQ(sum.load(), 499500);
}
