// vtkAtmosphereTablesSource: the blocks asked for, their values, and the cache keyed by
// what each table depends on.
#include "FieldParameters.h"
#include "vtkAtmosphereTablesSource.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace fs = std::filesystem;

namespace {
struct CacheDir {
  fs::path path = fs::temp_directory_path() / ("umbra-atmosphere-filter-test-" + std::to_string(::getpid()));
  ~CacheDir() { fs::remove_all(path); }
};

vtkImageData* refractionBlock(vtkAtmosphereTablesSource* s) {
  return vtkImageData::SafeDownCast(s->GetOutput()->GetBlock(0));
}

void configure(vtkAtmosphereTablesSource* s, const CacheDir& cache, const char* atmosphere) {
  s->SetAtmosphere(atmosphere);
  s->SetRefractionWidth(32);
  s->SetRefractionHeight(16);
  s->SetCacheDirectory(cache.path.c_str());
}
} // namespace

TEST(AtmosphereTablesSource, RefractionTableHasTheHorizontalRayInItsCorner) {
  CacheDir cache;
  vtkNew<vtkAtmosphereTablesSource> source;
  configure(source, cache, "earth");
  source->Update();
  ASSERT_TRUE(source->GetLastError().empty()) << source->GetLastError();
  vtkImageData* image = refractionBlock(source);
  ASSERT_NE(image, nullptr);
  int dims[3];
  image->GetDimensions(dims);
  EXPECT_EQ(dims[0], 32);
  EXPECT_EQ(dims[1], 16);
  auto* deviation = vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("deviation_rad"));
  auto* contact = vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("contact_altitude_m"));
  ASSERT_NE(deviation, nullptr);
  ASSERT_NE(contact, nullptr);
  for (vtkIdType i = 0; i < deviation->GetNumberOfTuples(); ++i) {
    ASSERT_TRUE(std::isfinite(deviation->GetValue(i)));
    ASSERT_TRUE(std::isfinite(contact->GetValue(i)));
  }
  // x_mu = 1, x_r = 0: the horizontal ray at the ground, ~0.6 degrees; x_mu = 0: zenith, 0.
  const double horizontalDeg = deviation->GetValue(31) * 180.0 / M_PI;
  EXPECT_GT(horizontalDeg, 0.55);
  EXPECT_LT(horizontalDeg, 0.65);
  EXPECT_NEAR(deviation->GetValue(0), 0.0, 1e-9);
  EXPECT_EQ(umbra::filters::fieldParameters(image).at("kind"), "atmosphere-refraction");
}

TEST(AtmosphereTablesSource, CacheIsKeyedByWhatTheTableDependsOn) {
  CacheDir cache;
  vtkNew<vtkAtmosphereTablesSource> first, aerosols, mars;
  configure(first, cache, "earth");
  first->Update();
  EXPECT_EQ(first->GetLastComputed(), 1);
  EXPECT_EQ(first->GetLastCacheHits(), 0);
  // The 2015 Calbuco atmosphere differs only in its aerosols: same refraction table.
  configure(aerosols, cache, "earth-2015-calbuco");
  aerosols->Update();
  EXPECT_EQ(aerosols->GetLastCacheHits(), 1);
  EXPECT_EQ(aerosols->GetLastComputed(), 0);
  auto* a = vtkFloatArray::SafeDownCast(refractionBlock(first)->GetPointData()->GetArray("deviation_rad"));
  auto* b = vtkFloatArray::SafeDownCast(refractionBlock(aerosols)->GetPointData()->GetArray("deviation_rad"));
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i) ASSERT_EQ(a->GetValue(i), b->GetValue(i));
  configure(mars, cache, "mars");
  mars->Update();
  EXPECT_EQ(mars->GetLastComputed(), 1);
}

TEST(AtmosphereTablesSource, NoTableAskedNoneMade) {
  CacheDir cache;
  vtkNew<vtkAtmosphereTablesSource> source;
  configure(source, cache, "earth");
  source->SetTables(0);
  source->Update();
  EXPECT_EQ(source->GetOutput()->GetNumberOfBlocks(), 0u);
  EXPECT_EQ(source->GetLastComputed(), 0);
  EXPECT_FALSE(fs::exists(cache.path));
}

TEST(AtmosphereTablesSource, UnknownAtmosphereIsAnError) {
  CacheDir cache;
  vtkNew<vtkAtmosphereTablesSource> source;
  configure(source, cache, "pluto");
  source->Update();
  EXPECT_NE(source->GetLastError().find("unknown atmosphere preset 'pluto'"), std::string::npos);
}
