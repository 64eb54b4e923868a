// vtkTerrainHorizonShadowFilter and vtkMaximumMipmap: they hand the physics library's
// results through the pipeline unchanged, report progress and reject bad DEMs.
#include "CraterField.hpp"
#include "MaximumMipmap.hpp"
#include "SoftShadow.hpp"
#include "TerrainImageData.h"
#include "vtkMaximumMipmap.h"
#include "vtkTerrainHorizonShadowFilter.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace umbra;

namespace {
terrain::HeightField craters() {
  terrain::CraterFieldOptions o;
  o.size = 64;
  o.seed = 9;
  terrain::HeightField f = terrain::makeCraterField(o);
  f.heightsM[5 * 64 + 7] = std::numeric_limits<double>::quiet_NaN();
  return f;
}
} // namespace

TEST(TerrainHorizonShadowFilter, OutputsTheLibrarysFractionForEachMethod) {
  const terrain::HeightField field = craters();
  const terrain::MaximumMipmap mip(field);
  auto image = filters::imageFromHeightField(field);
  for (int method : {0, 1, 2}) {
    vtkNew<vtkTerrainHorizonShadowFilter> filter;
    filter->SetInputData(image);
    filter->SetSunElevationAzimuthDeg(2.0, 200.0);
    filter->SetMethod(method);
    int progressEvents = 0;
    vtkNew<vtkCallbackCommand> progress;
    progress->SetClientData(&progressEvents);
    progress->SetCallback([](vtkObject*, unsigned long, void* count, void*) { ++*static_cast<int*>(count); });
    filter->AddObserver(vtkCommand::ProgressEvent, progress);
    filter->Update();
    vtkDataArray* out = filter->GetOutput()->GetPointData()->GetArray("visible_solar_fraction");
    ASSERT_NE(out, nullptr);
    ASSERT_EQ(out->GetNumberOfTuples(), 64 * 64);
    EXPECT_NE(filter->GetOutput()->GetPointData()->GetArray("height_m"), nullptr);  // the input passes through
    EXPECT_GE(progressEvents, 2);
    EXPECT_GT(filter->GetSamplesLookedAt(), 0);
    terrain::SunDisc sun;
    sun.direction = terrain::sunDirectionFromElevationAzimuth(2.0 * M_PI / 180.0, 200.0 * M_PI / 180.0);
    terrain::ShadowOptions o;
    o.method = static_cast<terrain::ShadowMethod>(method);
    double lit = 0.0;
    for (int j = 0; j < 64; j += 9)
      for (int i = 0; i < 64; i += 7) {
        const double expected = terrain::visibleFraction(field, mip, i, j, sun, o);
        EXPECT_NEAR(out->GetTuple1(j * 64 + i), expected, 1e-12 * std::max(1.0, std::abs(expected))) << method;
        lit += expected;
      }
    EXPECT_GT(lit, 0.0);  // not all dark: the comparison means something
  }
}

TEST(TerrainHorizonShadowFilter, NoDataValueAndBadDemsAreHandled) {
  terrain::HeightField field = craters();
  field.heightsM[10 * 64 + 10] = -32768.0;  // a no-data marker, as in many DEMs
  field.heightsM[5 * 64 + 7] = 0.0;
  auto image = filters::imageFromHeightField(field);
  vtkNew<vtkTerrainHorizonShadowFilter> filter;
  filter->SetInputData(image);
  filter->SetSunElevationAzimuthDeg(1.0, 30.0);
  filter->SetNoDataValue(-32768.0);
  filter->Update();
  vtkDataArray* out = filter->GetOutput()->GetPointData()->GetArray("visible_solar_fraction");
  ASSERT_NE(out, nullptr);
  for (vtkIdType k = 0; k < out->GetNumberOfTuples(); ++k) ASSERT_TRUE(std::isfinite(out->GetTuple1(k)));

  // Unequal spacing: an error, no output array.
  image->SetSpacing(30.0, 40.0, 1.0);
  vtkNew<vtkTerrainHorizonShadowFilter> bad;
  bad->SetInputData(image);
  bad->GlobalWarningDisplayOff();
  bad->Update();
  EXPECT_EQ(bad->GetOutput()->GetPointData()->GetArray("visible_solar_fraction"), nullptr);
  bad->GlobalWarningDisplayOn();
}

TEST(MaximumMipmapFilter, EachLevelIsTheLibrarysMipmap) {
  const terrain::HeightField field = craters();
  const terrain::MaximumMipmap mip(field);
  auto image = filters::imageFromHeightField(field);
  for (int level : {0, 2, 5, 20}) {
    vtkNew<vtkMaximumMipmap> filter;
    filter->SetInputData(image);
    filter->SetLevel(level);
    filter->Update();
    vtkImageData* out = filter->GetOutput();
    const int m = std::min(level, mip.levels() - 1);
    int dims[3];
    out->GetDimensions(dims);
    ASSERT_EQ(dims[0], mip.width(m));
    ASSERT_EQ(dims[1], mip.height(m));
    EXPECT_DOUBLE_EQ(out->GetSpacing()[0], field.spacingM * std::ldexp(1.0, m));
    vtkDataArray* maxima = out->GetPointData()->GetArray("max_height_m");
    ASSERT_NE(maxima, nullptr);
    for (int k = 0; k < dims[0] * dims[1]; ++k) ASSERT_EQ(maxima->GetTuple1(k), mip.level(m)[k]);
    EXPECT_EQ(out->GetFieldData()->GetArray("levels")->GetTuple1(0), mip.levels());
  }
}
