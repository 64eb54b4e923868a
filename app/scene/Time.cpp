#include "scene/Time.hpp"

#include <erfa.h>

#include <cstdio>
#include <regex>
#include <stdexcept>

namespace umbra::scene {

namespace {

constexpr double kSecondsPerDay = 86400.0;

[[noreturn]] void throwBadTime(const std::string& text, const std::string& why) {
  throw std::invalid_argument("invalid UTC time '" + text + "': " + why);
}

void toTai(UtcTime time, double& tai1, double& tai2) {
  if (eraUtctai(time.jd1, time.jd2, &tai1, &tai2) < 0)
    throw std::invalid_argument("UTC time out of range (JD " +
                                std::to_string(time.jd1 + time.jd2) + ")");
}

UtcTime fromTai(double tai1, double tai2) {
  UtcTime time;
  if (eraTaiutc(tai1, tai2, &time.jd1, &time.jd2) < 0)
    throw std::invalid_argument("TAI time out of range (JD " +
                                std::to_string(tai1 + tai2) + ")");
  return time;
}

} // namespace

UtcTime parseUtc(const std::string& text) {
  static const std::regex kIso(
      R"(\s*(\d{4})-(\d{2})-(\d{2})[T ](\d{2}):(\d{2})(?::(\d{2}(?:\.\d*)?))?Z?\s*)");
  std::smatch m;
  if (!std::regex_match(text, m, kIso))
    throwBadTime(text, "expected ISO 8601 like 2015-09-28T01:45:00Z");
  const int year = std::stoi(m[1]);
  const int month = std::stoi(m[2]);
  const int day = std::stoi(m[3]);
  const int hour = std::stoi(m[4]);
  const int minute = std::stoi(m[5]);
  const double second = m[6].matched ? std::stod(m[6]) : 0.0;

  UtcTime time;
  const int status =
      eraDtf2d("UTC", year, month, day, hour, minute, second, &time.jd1, &time.jd2);
  switch (status) {
  case -1: throwBadTime(text, "year out of range");
  case -2: throwBadTime(text, "month out of range");
  case -3: throwBadTime(text, "day out of range");
  case -4: throwBadTime(text, "hour out of range");
  case -5: throwBadTime(text, "minute out of range");
  case -6: throwBadTime(text, "second out of range");
  default: break;
  }
  // Warnings: +1 dubious year (accepted: leap seconds unknown there), +2 time after the
  // end of the day (a second of 60 or more on a day without a leap second).
  if (status >= 2) throwBadTime(text, "second out of range");
  return time;
}

std::string formatUtc(UtcTime time) {
  int year = 0, month = 0, day = 0, hms[4] = {0, 0, 0, 0};
  if (eraD2dtf("UTC", 0, time.jd1, time.jd2, &year, &month, &day, hms) < 0)
    throw std::invalid_argument("UTC time out of range (JD " +
                                std::to_string(time.jd1 + time.jd2) + ")");
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%04d-%02d-%02dT%02d:%02d:%02dZ", year, month, day,
                hms[0], hms[1], hms[2]);
  return buffer;
}

UtcTime addSeconds(UtcTime time, double seconds) {
  double tai1 = 0.0, tai2 = 0.0;
  toTai(time, tai1, tai2);
  return fromTai(tai1, tai2 + seconds / kSecondsPerDay);
}

double secondsBetween(UtcTime a, UtcTime b) {
  double a1 = 0.0, a2 = 0.0, b1 = 0.0, b2 = 0.0;
  toTai(a, a1, a2);
  toTai(b, b1, b2);
  return ((b1 - a1) + (b2 - a2)) * kSecondsPerDay;
}

void toTt(UtcTime time, double& tt1, double& tt2) {
  double tai1 = 0.0, tai2 = 0.0;
  toTai(time, tai1, tai2);
  eraTaitt(tai1, tai2, &tt1, &tt2);
}

UtcTime fromTt(double tt1, double tt2) {
  double tai1 = 0.0, tai2 = 0.0;
  eraTttai(tt1, tt2, &tai1, &tai2);
  return fromTai(tai1, tai2);
}

} // namespace umbra::scene
