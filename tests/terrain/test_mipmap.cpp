#include "CraterField.hpp"
#include "MaximumMipmap.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace umbra::terrain;

TEST(MaximumMipmap, EachTexelIsTheMaximumOfTheCellsItCovers) {
  CraterFieldOptions o;
  o.size = 45;  // not a power of two: partial blocks at the edges
  o.seed = 7;
  HeightField f = makeCraterField(o);
  for (int j = 10; j < 14; ++j)
    for (int i = 3; i < 9; ++i) f.heightsM[j * f.width + i] = std::numeric_limits<double>::quiet_NaN();
  const MaximumMipmap mip(f);
  ASSERT_EQ(mip.levels(), 7);  // 44 cells -> 22, 11, 6, 3, 2, 1
  for (int m = 0; m < mip.levels(); ++m) {
    const int block = 1 << m;
    for (int bj = 0; bj < mip.height(m); ++bj)
      for (int bi = 0; bi < mip.width(m); ++bi) {
        double expected = -std::numeric_limits<double>::infinity();
        for (int j = bj * block; j <= std::min((bj + 1) * block, f.height - 1); ++j)
          for (int i = bi * block; i <= std::min((bi + 1) * block, f.width - 1); ++i)
            if (f.valid(i, j)) expected = std::max(expected, f.at(i, j));
        ASSERT_EQ(mip.max(m, bi, bj), expected) << m << " " << bi << " " << bj;
      }
  }
  EXPECT_EQ(mip.width(mip.levels() - 1), 1);
}

TEST(CraterField, IsDeterministicAndHasCratersOfTheRequestedDepth) {
  CraterFieldOptions o;
  o.size = 128;
  o.seed = 42;
  const HeightField a = makeCraterField(o), b = makeCraterField(o);
  EXPECT_EQ(a.heightsM, b.heightsM);
  o.seed = 43;
  EXPECT_NE(makeCraterField(o).heightsM, a.heightsM);
  double lo = 1e300, hi = -1e300;
  for (double h : a.heightsM) lo = std::min(lo, h), hi = std::max(hi, h);
  // The largest craters (0.35 x 128 x 30 m = 1.3 km) are ~0.2 D = 270 m deep: relief of hundreds of metres.
  EXPECT_GT(hi - lo, 150.0);
  EXPECT_LT(hi - lo, 2000.0);
  a.validate();
}
