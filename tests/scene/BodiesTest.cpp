#include "scene/Bodies.hpp"
#include "scene/Units.hpp"

#include <gtest/gtest.h>

using namespace umbra::scene;

namespace {
const BodyPreset& preset(const char* name) {
  const BodyPreset* p = findPreset(name);
  if (p == nullptr) throw std::runtime_error(std::string("no preset ") + name);
  return *p;
}
} // namespace

TEST(Bodies, PresetNamesInOrder) {
  EXPECT_EQ(presetNames(),
            (std::vector<std::string>{"Sun", "Earth", "Moon", "Mars", "Phobos", "Deimos"}));
  EXPECT_EQ(presetNameList(), "Sun, Earth, Moon, Mars, Phobos, Deimos");
}

TEST(Bodies, LookupIsCaseInsensitive) {
  ASSERT_NE(findPreset("moon"), nullptr);
  EXPECT_EQ(findPreset("MOON")->name, "Moon");
  EXPECT_EQ(findPreset("Pluto"), nullptr);
  EXPECT_EQ(findPreset(""), nullptr);
}

TEST(Bodies, IauRadii) {
  EXPECT_EQ(preset("Sun").equatorialRadiusM, 696342e3);
  EXPECT_EQ(preset("Sun").polarRadiusM, 696342e3);
  EXPECT_EQ(preset("Sun").meanRadiusM, 696342e3);
  EXPECT_DOUBLE_EQ(preset("Earth").equatorialRadiusM, 6378136.6);
  EXPECT_DOUBLE_EQ(preset("Earth").polarRadiusM, 6356751.9);
  EXPECT_DOUBLE_EQ(preset("Earth").meanRadiusM, 6371008.4);
  EXPECT_DOUBLE_EQ(preset("Moon").meanRadiusM, 1737400.0);
  EXPECT_DOUBLE_EQ(preset("Moon").polarRadiusM, 1737400.0);
  EXPECT_DOUBLE_EQ(preset("Mars").equatorialRadiusM, 3396190.0);
  EXPECT_DOUBLE_EQ(preset("Mars").polarRadiusM, 3376200.0);
  EXPECT_DOUBLE_EQ(preset("Mars").meanRadiusM, 3389500.0);
  EXPECT_DOUBLE_EQ(preset("Phobos").meanRadiusM, 11080.0);
  EXPECT_DOUBLE_EQ(preset("Phobos").equatorialRadiusM, 11080.0);
  EXPECT_DOUBLE_EQ(preset("Deimos").meanRadiusM, 6200.0);
}

TEST(Bodies, OrbitsAndSurfaces) {
  EXPECT_EQ(preset("Sun").parent, "");
  EXPECT_EQ(preset("Earth").parent, "Sun");
  EXPECT_EQ(preset("Earth").meanDistanceFromParentM, 149597870700.0);
  EXPECT_EQ(preset("Moon").parent, "Earth");
  EXPECT_DOUBLE_EQ(preset("Moon").meanDistanceFromParentM, 384400e3);
  EXPECT_NEAR(preset("Mars").meanDistanceFromParentM / kAuM, 1.523679, 1e-6);
  EXPECT_DOUBLE_EQ(preset("Phobos").meanDistanceFromParentM, 9376e3);
  EXPECT_DOUBLE_EQ(preset("Deimos").meanDistanceFromParentM, 23463.2e3);
  EXPECT_TRUE(preset("Earth").hasAtmosphere);
  EXPECT_TRUE(preset("Mars").hasAtmosphere);
  EXPECT_FALSE(preset("Moon").hasAtmosphere);
  EXPECT_DOUBLE_EQ(preset("Earth").geometricAlbedo, 0.367);
  EXPECT_DOUBLE_EQ(preset("Moon").geometricAlbedo, 0.12);
  EXPECT_DOUBLE_EQ(preset("Mars").geometricAlbedo, 0.170);
  EXPECT_DOUBLE_EQ(preset("Phobos").geometricAlbedo, 0.071);
  EXPECT_DOUBLE_EQ(preset("Deimos").geometricAlbedo, 0.068);
}

TEST(Bodies, MeanDistanceFromSun) {
  EXPECT_EQ(meanDistanceFromSunM(preset("Sun")), 0.0);
  EXPECT_EQ(meanDistanceFromSunM(preset("Earth")), kAuM);
  EXPECT_EQ(meanDistanceFromSunM(preset("Moon")), kAuM);
  EXPECT_DOUBLE_EQ(meanDistanceFromSunM(preset("Phobos")), 227939200e3);
  EXPECT_DOUBLE_EQ(meanDistanceFromSunM(preset("Deimos")), 227939200e3);
}
