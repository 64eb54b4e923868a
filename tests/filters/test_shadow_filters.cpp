// vtkEclipseShadowLutSource and vtkShadowProfileFilter: outputs, field data, progress,
// the disk cache, and agreement with the physics library they wrap.
#include "ShadowLut.hpp"
#include "ShadowLutData.h"
#include "vtkEclipseShadowLutSource.h"
#include "vtkShadowProfileFilter.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkTable.h>

#include <gtest/gtest.h>

#include <filesystem>

namespace fs = std::filesystem;
using namespace umbra;

namespace {
struct CacheDir {
  fs::path path = fs::temp_directory_path() / ("umbra-filter-test-" + std::to_string(::getpid()));
  ~CacheDir() { fs::remove_all(path); }
};

vtkSmartPointer<vtkEclipseShadowLutSource> makeSource(const CacheDir& cache, int size) {
  auto s = vtkSmartPointer<vtkEclipseShadowLutSource>::New();
  s->SetWidth(size);
  s->SetHeight(size);
  s->SetOccluderName("Earth");
  s->SetCacheDirectory(cache.path.c_str());
  return s;
}
} // namespace

TEST(EclipseShadowLutSource, ImageHoldsTheLutAtTexelCentres) {
  CacheDir cache;
  auto source = makeSource(cache, 32);
  source->Update();
  vtkImageData* image = source->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  EXPECT_EQ(dims[0], 32);
  EXPECT_EQ(dims[1], 32);
  EXPECT_EQ(dims[2], 1);
  double p[3];
  int ijk[3] = {3, 7, 0};
  image->GetPoint(image->ComputePointId(ijk), p);
  EXPECT_DOUBLE_EQ(p[0], 3.5 / 32);
  EXPECT_DOUBLE_EQ(p[1], 7.5 / 32);
  auto* values = vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray(filters::kShadowLutArrayName));
  ASSERT_NE(values, nullptr);
  ASSERT_EQ(values->GetNumberOfComponents(), 3);
  const eclipse::ShadowLut reference = eclipse::buildAirlessShadowLut({32, 32});
  for (vtkIdType k = 0; k < values->GetNumberOfTuples(); ++k) EXPECT_EQ(values->GetComponent(k, 0), reference.rgb[3 * k]);
  const auto fields = filters::fieldParameters(image);
  EXPECT_EQ(fields.at("kind"), filters::kAirlessShadowLutKind);
  EXPECT_EQ(fields.at("occluder"), "Earth");
  EXPECT_EQ(fields.at("width"), "32");
  EXPECT_EQ(fields.at("limbDarkening"), "0.6");
}

TEST(EclipseShadowLutSource, SecondSourceHitsTheCacheWithTheSameValues) {
  CacheDir cache;
  auto first = makeSource(cache, 16);
  first->Update();
  EXPECT_FALSE(first->GetLastUpdateWasCacheHit());
  EXPECT_TRUE(fs::exists(first->GetCachePath()));
  auto second = makeSource(cache, 16);
  second->SetOccluderName("Mars");  // bodies do not change an airless LuT
  second->Update();
  EXPECT_TRUE(second->GetLastUpdateWasCacheHit());
  EXPECT_EQ(filters::fromImageData(first->GetOutput()).rgb, filters::fromImageData(second->GetOutput()).rgb);
  EXPECT_EQ(filters::fieldParameters(second->GetOutput()).at("occluder"), "Mars");
  // any parameter that changes the values changes the key
  auto darker = makeSource(cache, 16);
  darker->SetLimbDarkening(0.5);
  darker->Update();
  EXPECT_FALSE(darker->GetLastUpdateWasCacheHit());
  EXPECT_NE(darker->GetCachePath(), first->GetCachePath());
}

TEST(EclipseShadowLutSource, UseCacheOffWritesNothing) {
  CacheDir cache;
  auto source = makeSource(cache, 16);
  source->UseCacheOff();
  source->Update();
  EXPECT_FALSE(fs::exists(cache.path));
}

TEST(EclipseShadowLutSource, ReportsProgressUpToOne) {
  CacheDir cache;
  auto source = makeSource(cache, 16);
  source->UseCacheOff();
  std::vector<double> seen;
  vtkNew<vtkCallbackCommand> cb;
  cb->SetClientData(&seen);
  cb->SetCallback([](vtkObject*, unsigned long, void* client, void* data) {
    static_cast<std::vector<double>*>(client)->push_back(*static_cast<double*>(data));
  });
  source->AddObserver(vtkCommand::ProgressEvent, cb);
  source->Update();
  ASSERT_GE(seen.size(), 3u);
  EXPECT_EQ(seen.back(), 1.0);
}

TEST(ShadowProfileFilter, LutAndExactProfilesAgreeAndUseTheBodiesOfTheLut) {
  CacheDir cache;
  auto source = makeSource(cache, 256);
  source->SetOccluderRadiusM(6371e3);
  source->SetSunOccluderDistanceM(149597870700.0);
  vtkNew<vtkShadowProfileFilter> lut, exact;
  for (vtkShadowProfileFilter* f : {lut.Get(), exact.Get()}) {
    f->SetInputConnection(source->GetOutputPort());
    f->SetReceiverDistanceM(384400e3);
    f->SetSamples(300);
  }
  exact->ExactOn();
  lut->Update();
  exact->Update();
  vtkTable* a = lut->GetOutput();
  vtkTable* b = exact->GetOutput();
  ASSERT_EQ(a->GetNumberOfRows(), 300);
  ASSERT_EQ(a->GetNumberOfColumns(), 5);
  EXPECT_STREQ(a->GetColumnName(0), "offset_km");
  EXPECT_STREQ(a->GetColumnName(4), "luminance");
  const auto* la = vtkDoubleArray::SafeDownCast(a->GetColumnByName("luminance"));
  const auto* lb = vtkDoubleArray::SafeDownCast(b->GetColumnByName("luminance"));
  double maxDiff = 0.0;
  for (vtkIdType i = 0; i < 300; ++i) maxDiff = std::max(maxDiff, std::abs(la->GetValue(i) - lb->GetValue(i)));
  EXPECT_LT(maxDiff, 0.01);  // a 256^2 LuT at the Moon's distance (see docs/accuracy-vs-speed.md)
  // default extent: 1.25 x the penumbra radius, which is ~8177 km here
  const double last = vtkDoubleArray::SafeDownCast(a->GetColumnByName("offset_km"))->GetValue(299);
  EXPECT_NEAR(last, 1.25 * 8176.8, 2.0);
}

TEST(ShadowProfileFilter, ExactModeNeedsNoInput) {
  vtkNew<vtkShadowProfileFilter> f;
  f->SetSunRadiusM(eclipse::kSunRadiusM);
  f->SetOccluderRadiusM(6371e3);
  f->SetSunOccluderDistanceM(149597870700.0);
  f->SetReceiverDistanceM(384400e3);
  f->SetSamples(10);
  f->ExactOn();
  f->Update();
  ASSERT_EQ(f->GetOutput()->GetNumberOfRows(), 10);
  EXPECT_EQ(vtkDoubleArray::SafeDownCast(f->GetOutput()->GetColumnByName("luminance"))->GetValue(0), 0.0);
}
