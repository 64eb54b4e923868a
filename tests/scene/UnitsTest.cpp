#include "scene/Units.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <stdexcept>
#include <string>

using umbra::scene::kAuM;
using umbra::scene::parseLengthM;

TEST(Units, ParsesUnitsAndBareMetres) {
  EXPECT_DOUBLE_EQ(parseLengthM("384400km"), 384400e3);
  EXPECT_DOUBLE_EQ(parseLengthM("384400 km"), 384400e3);
  EXPECT_DOUBLE_EQ(parseLengthM("1.5au"), 1.5 * 149597870700.0);
  EXPECT_DOUBLE_EQ(parseLengthM("1 au"), kAuM);
  EXPECT_DOUBLE_EQ(parseLengthM("2e8m"), 2e8);
  EXPECT_DOUBLE_EQ(parseLengthM("2e8"), 2e8);
  EXPECT_DOUBLE_EQ(parseLengthM(" 12 m "), 12.0);
  EXPECT_DOUBLE_EQ(parseLengthM("-5km"), -5000.0);
  EXPECT_DOUBLE_EQ(parseLengthM(".5km"), 500.0);
}

TEST(Units, RoundTripsThroughText) {
  for (double metres : {1.0, 1737.4e3, 384400e3, 6.02e23, 1e-7}) {
    char text[64];
    std::snprintf(text, sizeof text, "%.17g km", metres / 1000.0);
    EXPECT_NEAR(parseLengthM(text), metres, metres * 1e-15);
    std::snprintf(text, sizeof text, "%.17gm", metres);
    EXPECT_EQ(parseLengthM(text), metres);
    std::snprintf(text, sizeof text, "%.17g au", metres / kAuM);
    EXPECT_NEAR(parseLengthM(text), metres, metres * 1e-15);
  }
}

TEST(Units, ErrorMessageQuotesTextAndSaysWhatIsExpected) {
  try {
    parseLengthM("12 parsec");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "invalid length '12 parsec': expected a number with unit m, km or au");
  }
}

TEST(Units, RejectsGarbage) {
  for (const char* text : {"", "   ", "km", "nan", "NaN km", "inf", "-inf m", "1e999", "12kmx",
                           "12 k m", "12 km km", "0x10", "1,5km", "abc", "12 KM", "1..2m"})
    EXPECT_THROW(parseLengthM(text), std::invalid_argument) << "'" << text << "'";
}

TEST(Units, ParsesDurations) {
  using umbra::scene::parseDurationS;
  EXPECT_DOUBLE_EQ(parseDurationS("30min"), 1800.0);
  EXPECT_DOUBLE_EQ(parseDurationS("1.5 h"), 5400.0);
  EXPECT_DOUBLE_EQ(parseDurationS("2d"), 172800.0);
  EXPECT_THROW(parseDurationS("90"), std::invalid_argument);  // seconds? minutes? a unit is required
  EXPECT_DOUBLE_EQ(parseDurationS("90 s"), 90.0);
  for (const char* text : {"", "min", "nan s", "1 week", "30 mins", "0x10"})
    EXPECT_THROW(parseDurationS(text), std::invalid_argument) << "'" << text << "'";
  try {
    parseDurationS("3 fortnights");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "invalid duration '3 fortnights': expected a number with unit s, min, h or d");
  }
}
