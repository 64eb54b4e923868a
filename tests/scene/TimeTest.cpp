#include "scene/Time.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

using namespace umbra::scene;

namespace {
double jd(UtcTime t) { return t.jd1 + t.jd2; }
constexpr double kSecondDays = 1.0 / 86400.0;
} // namespace

TEST(Time, ParsesIso8601Forms) {
  const double expected = 2457293.5 + (1.0 + 45.0 / 60.0) / 24.0; // 2015-09-28 01:45 UTC
  EXPECT_NEAR(jd(parseUtc("2015-09-28T01:45:00Z")), expected, 1e-3 * kSecondDays);
  EXPECT_NEAR(jd(parseUtc("2015-09-28T01:45Z")), expected, 1e-3 * kSecondDays);
  EXPECT_NEAR(jd(parseUtc("2015-09-28 01:45:00")), expected, 1e-3 * kSecondDays);
  EXPECT_NEAR(jd(parseUtc("2015-09-28T01:45:00")), expected, 1e-3 * kSecondDays);
  EXPECT_NEAR(jd(parseUtc("2015-09-28T01:45:00.5Z")), expected + 0.5 * kSecondDays,
              1e-3 * kSecondDays);
}

TEST(Time, FormatsRoundedSeconds) {
  EXPECT_EQ(formatUtc(parseUtc("2015-09-28T01:45:00Z")), "2015-09-28T01:45:00Z");
  EXPECT_EQ(formatUtc(parseUtc("2015-09-28T01:45Z")), "2015-09-28T01:45:00Z");
  EXPECT_EQ(formatUtc(parseUtc("2015-09-28T01:45:00.4Z")), "2015-09-28T01:45:00Z");
  EXPECT_EQ(formatUtc(parseUtc("2015-09-28T01:45:00.6Z")), "2015-09-28T01:45:01Z");
  EXPECT_EQ(formatUtc(parseUtc("1999-12-31T23:59:59.7Z")), "2000-01-01T00:00:00Z");
}

TEST(Time, AddSecondsCountsTheLeapSecondOf2015June30) {
  const UtcTime before = parseUtc("2015-06-30T23:59:59Z");
  EXPECT_EQ(formatUtc(addSeconds(before, 1.0)), "2015-06-30T23:59:60Z");
  EXPECT_EQ(formatUtc(addSeconds(before, 2.0)), "2015-07-01T00:00:00Z");
  EXPECT_NEAR(secondsBetween(before, parseUtc("2015-07-01T00:00:00Z")), 2.0, 1e-6);
  EXPECT_EQ(formatUtc(addSeconds(parseUtc("2015-09-28T01:45:00Z"), 3720.0)),
            "2015-09-28T02:47:00Z");
  EXPECT_EQ(formatUtc(addSeconds(parseUtc("2015-09-28T01:45:00Z"), -86400.0)),
            "2015-09-27T01:45:00Z");
}

TEST(Time, TerrestrialTimeIs68Point184SecondsAheadIn2015) {
  // TT - UTC = 32.184 s + (TAI - UTC = 36 s from 2015-07-01).
  const UtcTime utc = parseUtc("2015-09-28T02:47:00Z");
  double tt1 = 0.0, tt2 = 0.0;
  toTt(utc, tt1, tt2);
  EXPECT_NEAR(((tt1 - utc.jd1) + (tt2 - utc.jd2)) * 86400.0, 68.184, 1e-5);
}

TEST(Time, RejectsBadText) {
  for (const char* text : {"", "yesterday", "2015-09-28", "2015-9-28T01:45Z", "2015-13-01T00:00Z",
                           "2015-02-30T00:00Z", "2015-09-28T25:00Z", "2015-09-28T01:61Z",
                           "2015-09-28T01:45:61Z", "2015-09-28T01:45:00+02:00",
                           "2015-09-28T01:45:00Zjunk"})
    EXPECT_THROW(parseUtc(text), std::invalid_argument) << "'" << text << "'";
  try {
    parseUtc("2015-13-01T00:00Z");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "invalid UTC time '2015-13-01T00:00Z': month out of range");
  }
}
