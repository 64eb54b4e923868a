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
  EXPECT_LT(maxDiff, 0.01);  // a 256^2 LuT at the Moon's distance (see docs/accuracy-vs-speed/eclipse-luts.md)
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

// A LuT over the ranges of Phobos' distances behind Mars: the ranges travel in field data,
// the EXR header and the cache key; the profile filter reads them back and agrees with the
// exact profile at 64^2 (the whole-range 64^2 LuT does not: docs/eclipse-shadows.md).
TEST(ShadowProfileFilter, RangedLutCarriesItsRangesAndResolvesPhobos) {
  CacheDir cache;
  const eclipse::SunOccluderSystem mars{eclipse::kSunRadiusM, 3389.5e3, 2.2794e11};
  const double d = 9376e3, maxOffset = 1.1 * eclipse::shadowConeRadii(mars, d).penumbraRadiusM;
  const eclipse::LutRange r = eclipse::lutRangeForDistances(mars, d, std::hypot(d, maxOffset), true, 64);
  double err[2] = {0.0, 0.0};
  for (int ranged = 0; ranged < 2; ++ranged) {
    auto source = makeSource(cache, 64);
    source->SetOccluderRadiusM(mars.occluderRadiusM);
    source->SetSunOccluderDistanceM(mars.sunOccluderDistanceM);
    if (ranged) source->SetLutRange(r);
    vtkNew<vtkShadowProfileFilter> lut, exact;
    for (vtkShadowProfileFilter* f : {lut.Get(), exact.Get()}) {
      f->SetInputConnection(source->GetOutputPort());
      f->SetReceiverDistanceM(d);
      f->SetMaxOffsetM(maxOffset);
      f->SetSamples(400);
    }
    exact->ExactOn();
    lut->Update();
    exact->Update();
    const auto* la = vtkDoubleArray::SafeDownCast(lut->GetOutput()->GetColumnByName("luminance"));
    const auto* lb = vtkDoubleArray::SafeDownCast(exact->GetOutput()->GetColumnByName("luminance"));
    for (vtkIdType i = 0; i < 400; ++i) err[ranged] = std::max(err[ranged], std::abs(la->GetValue(i) - lb->GetValue(i)));
    if (!ranged) continue;
    const eclipse::ShadowLut back = filters::fromImageData(source->GetOutput());
    EXPECT_EQ(back.uMin, r.uMin);
    EXPECT_EQ(back.uMax, r.uMax);
    EXPECT_EQ(back.vMin, r.vMin);
    double origin[3];
    source->GetOutput()->GetOrigin(origin);
    EXPECT_DOUBLE_EQ(origin[0], back.texelU(0));
    EXPECT_DOUBLE_EQ(origin[1], back.texelV(0));
    // The cache keeps the ranges: a second source reads the same ranged LuT back.
    auto again = makeSource(cache, 64);
    again->SetLutRange(r);
    again->Update();
    EXPECT_TRUE(again->GetLastUpdateWasCacheHit());
    EXPECT_NE(again->GetCachePath(), makeSource(cache, 64)->GetCachePath());
    const eclipse::ShadowLut cached = filters::fromImageData(again->GetOutput());
    EXPECT_EQ(cached.rgb, back.rgb);
    EXPECT_EQ(cached.uMin, r.uMin);
    EXPECT_EQ(cached.vMax, r.vMax);
  }
  std::printf("  Phobos, 64^2 profile: max |LuT - exact| %.3g whole, %.3g ranged\n", err[0], err[1]);
  EXPECT_LT(err[1], 1e-3);
  EXPECT_GT(err[0], 10 * err[1]);
}
