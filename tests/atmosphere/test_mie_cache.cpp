// The Lorenz-Mie cache (atmosphere/MieCache.hpp): a result comes back to the bit from
// memory and from the store, one entry serves every number density, a damaged stored
// result is computed again, and an atmosphere loaded twice runs Lorenz-Mie once.
#include "Atmosphere.hpp"
#include "MieCache.hpp"
#include "Spectrum.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

using namespace umbra::atmosphere;

namespace {

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expectSameBits(const MieAerosol& a, const MieAerosol& b) {
  EXPECT_TRUE(sameBits(a.scatteringPerM, b.scatteringPerM)) << a.scatteringPerM << " " << b.scatteringPerM;
  EXPECT_TRUE(sameBits(a.extinctionPerM, b.extinctionPerM)) << a.extinctionPerM << " " << b.extinctionPerM;
  EXPECT_TRUE(sameBits(a.absorptionPerM, b.absorptionPerM)) << a.absorptionPerM << " " << b.absorptionPerM;
  EXPECT_TRUE(sameBits(a.asymmetry, b.asymmetry));
  EXPECT_EQ(a.sizeNodes, b.sizeNodes);
  EXPECT_EQ(a.converged, b.converged);
  ASSERT_EQ(a.phase.size(), b.phase.size());
  for (std::size_t j = 0; j < a.phase.size(); ++j) {
    EXPECT_TRUE(sameBits(a.cosTheta[j], b.cosTheta[j])) << j;
    EXPECT_TRUE(sameBits(a.phase[j], b.phase[j])) << j;
  }
}

// OPAC's water-soluble particles at 550 nm (an absorbing index, a few hundred size nodes).
constexpr double kWavelengthM = 550e-9;
const std::complex<double> kIndex{1.53, 0.006};
constexpr int kSamples = 91;
constexpr double kBulk = 1e-4, kPhase = 1e-2;
LogNormalSizes sizes(double numberDensityPerM3) { return {0.0212e-6, 2.24, numberDensityPerM3, 0.005e-6, 20e-6}; }

MieAerosol direct(double n) { return mieLogNormal(kWavelengthM, kIndex, sizes(n), kSamples, 0, kBulk, kPhase); }
MieAerosol cached(double n) { return cachedMieLogNormal(kWavelengthM, kIndex, sizes(n), kSamples, 0, kBulk, kPhase); }

/// A store in a map, as the table cache is one on disk.
struct MapStore {
  std::map<MieKey, nlohmann::json> entries;
  int loads = 0, stores = 0, holds = 0;
  std::function<void(MapStore&)> whileWaiting;  // what another process does before the lock is had
  MieStore store() {
    return {[this](const MieKey& k) -> std::optional<nlohmann::json> {
              ++loads;
              auto it = entries.find(k);
              if (it == entries.end()) return std::nullopt;
              return it->second;
            },
            [this](const MieKey& k, const nlohmann::json& d) {
              ++stores;
              entries[k] = d;
            },
            [this](const MieKey&) -> std::shared_ptr<void> {
              ++holds;
              if (whileWaiting) whileWaiting(*this);
              return std::make_shared<int>(0);
            }};
  }
};

class MieCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    setMieStore({});
    forgetMieResults();
  }
  void TearDown() override {
    setMieStore({});
    forgetMieResults();
  }
};

}  // namespace

TEST_F(MieCacheTest, OneEntryServesEveryNumberDensityToTheBit) {
  expectSameBits(cached(7.0e9), direct(7.0e9));
  expectSameBits(cached(3.0e6), direct(3.0e6));  // the same particles, fewer of them
  expectSameBits(cached(0.0), direct(0.0));
  const MieCacheCounts counts = mieCacheCounts();
  EXPECT_EQ(counts.computed, 1u);
  EXPECT_EQ(counts.fromMemory, 2u);
  EXPECT_EQ(counts.fromStore, 0u);
}

TEST_F(MieCacheTest, WhatAnotherProcessStoredWhileThisOneWaitedIsRead) {
  // The first process computes and stores; a second, finding nothing, waits for the lock
  // (meanwhile the first stores): it reads, it does not compute.
  MapStore first;
  setMieStore(first.store());
  const MieAerosol made = cached(7.0e9);
  EXPECT_EQ(first.holds, 1);  // a miss: computed under the lock
  MapStore second;
  second.whileWaiting = [&first](MapStore& self) { self.entries = first.entries; };
  setMieStore(second.store());
  forgetMieResults();
  expectSameBits(cached(7.0e9), made);
  EXPECT_EQ(second.holds, 1);
  EXPECT_EQ(second.loads, 2);  // before the lock and under it
  EXPECT_EQ(second.stores, 0);
  EXPECT_EQ(mieCacheCounts().fromStore, 1u);
  EXPECT_EQ(mieCacheCounts().computed, 0u);
}

TEST_F(MieCacheTest, TheStoreGivesTheResultBackToTheBitInTheNextProcess) {
  MapStore map;
  setMieStore(map.store());
  const MieAerosol first = cached(7.0e9);
  EXPECT_EQ(map.stores, 1);
  ASSERT_EQ(map.entries.size(), 1u);
  forgetMieResults();  // as a new process would start
  expectSameBits(cached(7.0e9), first);
  EXPECT_EQ(mieCacheCounts().fromStore, 1u);
  EXPECT_EQ(mieCacheCounts().computed, 0u);
  EXPECT_EQ(map.stores, 1);

  // A stored result that is not one (cut short, a NaN) is computed again and replaced.
  nlohmann::json& stored = map.entries.begin()->second;
  stored["phase"].erase(stored["phase"].begin());
  forgetMieResults();
  expectSameBits(cached(7.0e9), first);
  EXPECT_EQ(mieCacheCounts().computed, 1u);
  EXPECT_EQ(map.stores, 2);
  map.entries.begin()->second["asymmetry"] = std::numeric_limits<double>::quiet_NaN();
  forgetMieResults();
  expectSameBits(cached(7.0e9), first);
  EXPECT_EQ(mieCacheCounts().computed, 1u);
}

TEST_F(MieCacheTest, EveryInputIsInTheKey) {
  MapStore map;
  setMieStore(map.store());
  cached(1.0);
  cachedMieLogNormal(kWavelengthM * (1 + 1e-15), kIndex, sizes(1.0), kSamples, 0, kBulk, kPhase);
  cachedMieLogNormal(kWavelengthM, {1.53, 0.0061}, sizes(1.0), kSamples, 0, kBulk, kPhase);
  LogNormalSizes wider = sizes(1.0);
  wider.geometricStdDev = 2.25;
  cachedMieLogNormal(kWavelengthM, kIndex, wider, kSamples, 0, kBulk, kPhase);
  LogNormalSizes uncut = sizes(1.0);
  uncut.maxRadiusM = 0.0;
  cachedMieLogNormal(kWavelengthM, kIndex, uncut, kSamples, 0, kBulk, kPhase);
  cachedMieLogNormal(kWavelengthM, kIndex, sizes(1.0), kSamples + 2, 0, kBulk, kPhase);
  cachedMieLogNormal(kWavelengthM, kIndex, sizes(1.0), kSamples, 0, kBulk / 2, kPhase);
  EXPECT_EQ(map.entries.size(), 7u);
  EXPECT_EQ(mieCacheCounts().computed, 7u);
}

TEST_F(MieCacheTest, AnAtmosphereLoadedTwiceRunsLorenzMieOnce) {
  const std::vector<double> nm = WavelengthSet::rgb().nm;
  const Atmosphere first = loadAtmosphere("earth", nm);
  const MieCacheCounts once = mieCacheCounts();
  EXPECT_GT(once.computed, 0u);
  const Atmosphere second = loadAtmosphere("earth", nm);
  EXPECT_EQ(mieCacheCounts().computed, once.computed);
  EXPECT_EQ(mieCacheCounts().fromMemory, once.fromMemory + once.computed);
  for (const Component& c : first.components) {
    const Component& d = second.component(c.name);
    for (std::size_t l = 0; l < nm.size(); ++l) {
      EXPECT_TRUE(sameBits(c.scatteringPerM[l], d.scatteringPerM[l])) << c.name;
      EXPECT_TRUE(sameBits(c.absorptionPerM[l], d.absorptionPerM[l])) << c.name;
      for (double mu : {-1.0, -0.3, 0.5, 0.99, 1.0}) EXPECT_TRUE(sameBits(c.phase(l)(mu), d.phase(l)(mu))) << c.name;
    }
  }
}

TEST(MieJson, RefusesWhatIsNotACompleteFiniteResult) {
  const MieAerosol a = mieLogNormal(kWavelengthM, kIndex, sizes(1.0), kSamples, 0, kBulk, kPhase);
  const nlohmann::json d = mieToJson(a);
  ASSERT_TRUE(mieFromJson(d, kSamples).has_value());
  expectSameBits(*mieFromJson(nlohmann::json::parse(d.dump()), kSamples), a);
  EXPECT_FALSE(mieFromJson(d, kSamples + 1).has_value());
  for (const char* field : {"scatteringPerM", "phase", "converged", "sizeNodes"}) {
    nlohmann::json missing = d;
    missing.erase(field);
    EXPECT_FALSE(mieFromJson(missing, kSamples).has_value()) << field;
  }
  nlohmann::json text = d;
  text["extinctionPerM"] = "1e-3";
  EXPECT_FALSE(mieFromJson(text, kSamples).has_value());
  EXPECT_FALSE(mieFromJson(nlohmann::json::array(), kSamples).has_value());
}
