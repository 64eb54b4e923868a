// The eclipse tables of an occluder with an atmosphere through the filters: the shadow-LuT
// source with an atmosphere (same values as the library, cache, update extents), the
// limb-luminance source, and the profile filter on an atmospheric LuT (R, G, B).
#include "AtmosphereTablesBlocks.h"
#include "EclipseAtmosphere.hpp"
#include "ShadowLutData.h"
#include "Spectrum.hpp"
#include "vtkAtmosphereTablesSource.h"
#include "vtkEclipseShadowLutSource.h"
#include "vtkLimbLuminanceSource.h"
#include "vtkShadowProfileFilter.h"

#include <vtkCallbackCommand.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkTable.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace fs = std::filesystem;
using namespace umbra;

namespace {
struct CacheDir {
  fs::path path = fs::temp_directory_path() / ("umbra-eclipse-atmo-test-" + std::to_string(::getpid()));
  ~CacheDir() { fs::remove_all(path); }
};

/// Small tables: a second or two.
template <class Source>
void configure(Source* s, const CacheDir& cache) {
  s->SetOccluderName("earth");
  s->SetOccluderRadiusM(6371008.4);
  s->SetSunOccluderDistanceM(1.496e11);
  s->SetAtmosphere("earth");
  s->SetOrders(2);
  s->SetTransmittanceSize(64, 16);
  s->SetScatteringSize(8, 32, 8, 4);
  s->SetIrradianceSize(16, 4);
  s->SetRefractionSize(128, 64);
  s->SetCacheDirectory(cache.path.c_str());
}

/// A 4 x 3 limb-luminance LuT of 8 columns, 2 layers, views of 16 rows.
vtkSmartPointer<vtkLimbLuminanceSource> limbSource(const CacheDir& cache) {
  auto s = vtkSmartPointer<vtkLimbLuminanceSource>::New();
  configure(s.Get(), cache);
  s->SetWidth(4);
  s->SetHeight(3);
  s->SetColumns(8);
  s->SetLayers(2);
  s->SetLimbRows(16);
  s->SetScatteringCells(4);
  return s;
}

vtkSmartPointer<vtkEclipseShadowLutSource> shadowSource(const CacheDir& cache) {
  auto s = vtkSmartPointer<vtkEclipseShadowLutSource>::New();
  configure(s.Get(), cache);
  s->SetWidth(8);
  s->SetHeight(6);
  s->SetLimbSize(32);
  s->SetScatteringCells(4);
  return s;
}

/// The library's options of configure().
eclipse::EclipseAtmosphereOptions smallOptions() {
  eclipse::EclipseAtmosphereOptions o;
  o.tables.orders = 2;
  o.tables.transmittanceWidth = 64, o.tables.transmittanceHeight = 16;
  o.tables.scatteringR = 8, o.tables.scatteringMu = 32, o.tables.scatteringMuS = 8, o.tables.scatteringNu = 4;
  o.tables.irradianceWidth = 16, o.tables.irradianceHeight = 4;
  o.refractionWidth = 128, o.refractionHeight = 64;
  return o;
}

/// vtkAtmosphereTablesSource with the options of configure() and what the eclipse tables need.
vtkSmartPointer<vtkAtmosphereTablesSource> tablesSource(const CacheDir& cache) {
  auto source = vtkSmartPointer<vtkAtmosphereTablesSource>::New();
  source->SetAtmosphere("earth");
  source->SetTables(vtkAtmosphereTablesSource::All);
  source->SetOrders(2);
  source->SetTransmittanceSize(64, 16);
  source->SetScatteringSize(8, 32, 8, 4);
  source->SetIrradianceSize(16, 4);
  source->SetRefractedPaths(true);
  source->SetRefractionWidth(128);
  source->SetRefractionHeight(64);
  source->SetCacheDirectory(cache.path.c_str());
  return source;
}

/// The messages of ErrorEvents sent by an object.
struct ErrorCatcher {
  std::string message;
  vtkNew<vtkCallbackCommand> command;
  explicit ErrorCatcher(vtkObject* o) {
    command->SetClientData(this);
    command->SetCallback([](vtkObject*, unsigned long, void* self, void* text) {
      static_cast<ErrorCatcher*>(self)->message += static_cast<const char*>(text);
    });
    o->AddObserver(vtkCommand::ErrorEvent, command);
  }
};

vtkFloatArray* scalars(vtkImageData* image) { return vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars()); }

/// The largest difference between two RGB LuTs of the same size; infinity when they differ
/// in size or one is missing.
double maxRgbDifference(vtkImageData* x, vtkImageData* y) {
  vtkFloatArray* a = scalars(x);
  vtkFloatArray* b = scalars(y);
  if (!a || !b || a->GetNumberOfTuples() != b->GetNumberOfTuples()) return HUGE_VAL;
  double maxDiff = 0.0;
  for (vtkIdType k = 0; k < a->GetNumberOfTuples(); ++k)
    for (int c = 0; c < 3; ++c) maxDiff = std::max(maxDiff, std::abs(double(a->GetComponent(k, c)) - b->GetComponent(k, c)));
  return maxDiff;
}
} // namespace

TEST(EclipseAtmosphereFilters, ShadowLutSourceWithAnAtmosphereIsTheLibrarysLut) {
  CacheDir cache;
  auto source = shadowSource(cache);
  source->Update();
  vtkImageData* image = source->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  ASSERT_EQ(dims[0], 8);
  ASSERT_EQ(dims[1], 6);
  EXPECT_FALSE(source->GetLastUpdateWasCacheHit());

  const eclipse::EclipseAtmosphereOptions o = smallOptions();
  const auto prepared = eclipse::prepareEclipseAtmosphere(
      atmosphere::loadAtmosphere("earth", atmosphere::WavelengthSet::rgb().nm), "earth", 1.496e11, o);
  eclipse::AtmosphericShadowLutParams p;
  p.width = 8, p.height = 6;
  p.limb = {32, 32, 4, 4};
  const eclipse::ShadowLut reference = eclipse::buildAtmosphericShadowLut(prepared->model, p);
  vtkFloatArray* values = scalars(image);
  ASSERT_NE(values, nullptr);
  ASSERT_EQ(values->GetNumberOfTuples(), 48);
  for (vtkIdType k = 0; k < 48; ++k)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(values->GetComponent(k, c), reference.rgb[3 * k + c]);
  // Umbra texel (small v, u past the Moon's distance): red through the atmosphere.
  const auto fields = filters::fieldParameters(image);
  EXPECT_EQ(fields.at("kind"), filters::kAtmosphereShadowLutKind);
  EXPECT_EQ(fields.at("atmosphere"), "earth");

  auto again = shadowSource(cache);
  again->Update();
  EXPECT_TRUE(again->GetLastUpdateWasCacheHit());
  for (vtkIdType k = 0; k < 48; ++k) EXPECT_EQ(scalars(again->GetOutput())->GetComponent(k, 0), values->GetComponent(k, 0));
  EXPECT_TRUE(fs::exists(again->GetCachePath()));
}

TEST(EclipseAtmosphereFilters, UpdateExtentComputesOnlyThatPart) {
  CacheDir cache;
  auto full = shadowSource(cache);
  full->SetUseCache(false);
  full->Update();
  auto part = shadowSource(cache);
  const int extent[6] = {2, 5, 1, 4, 0, 0};  // u texels 2..5, v texels 1..4
  part->UpdateExtent(extent);
  vtkImageData* image = part->GetOutput();
  int ext[6];
  image->GetExtent(ext);
  EXPECT_EQ(ext[0], 2);
  EXPECT_EQ(ext[1], 5);
  EXPECT_EQ(ext[2], 1);
  EXPECT_EQ(ext[3], 4);
  double point[3];
  int ijk[3] = {3, 2, 0};
  image->GetPoint(image->ComputePointId(ijk), point);
  EXPECT_DOUBLE_EQ(point[0], 3.5 / 8);
  EXPECT_DOUBLE_EQ(point[1], 2.5 / 6);
  for (int j = 1; j <= 4; ++j)
    for (int i = 2; i <= 5; ++i) {
      int at[3] = {i, j, 0};
      EXPECT_EQ(scalars(image)->GetComponent(image->ComputePointId(at), 1),
                scalars(full->GetOutput())->GetComponent(j * 8 + i, 1));
    }
  // As a LuT: the part's ranges, the same texel centres and values, so that a lookup
  // between its texel centres (e.g. a profile through it) equals the whole table's.
  const eclipse::ShadowLut p = filters::fromImageData(image), f = filters::fromImageData(full->GetOutput());
  EXPECT_EQ(p.width, 4);
  EXPECT_EQ(p.height, 4);
  EXPECT_DOUBLE_EQ(p.uMin, 2.0 / 8);
  EXPECT_DOUBLE_EQ(p.uMax, 6.0 / 8);
  EXPECT_DOUBLE_EQ(p.vMin, 1.0 / 6);
  EXPECT_DOUBLE_EQ(p.vMax, 5.0 / 6);
  EXPECT_DOUBLE_EQ(p.texelU(1), f.texelU(3));
  EXPECT_DOUBLE_EQ(p.texelV(2), f.texelV(3));
  for (const eclipse::LutCoords c : {eclipse::LutCoords{0.40, 0.45}, eclipse::LutCoords{0.33, 0.62}})
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(p.sample(c)[k], f.sample(c)[k], 1e-6 * (1.0 + std::abs(f.sample(c)[k])));
}

TEST(EclipseAtmosphereFilters, LimbLuminanceSourceIsA3dRgbTexture) {
  CacheDir cache;
  auto source = limbSource(cache);
  source->Update();
  int dims[3];
  source->GetOutput()->GetDimensions(dims);
  EXPECT_EQ(dims[0], 4);
  EXPECT_EQ(dims[1], 3);
  EXPECT_EQ(dims[2], 16);
  vtkFloatArray* values = scalars(source->GetOutput());
  ASSERT_NE(values, nullptr);
  double brightest = 0.0;
  for (vtkIdType k = 0; k < values->GetNumberOfTuples(); ++k)
    for (int c = 0; c < 3; ++c) {
      ASSERT_TRUE(std::isfinite(values->GetComponent(k, c)));
      ASSERT_GE(values->GetComponent(k, c), 0.0);
      brightest = std::max(brightest, values->GetComponent(k, c));
    }
  EXPECT_GT(brightest, 0.0);
  EXPECT_FALSE(source->GetLastUpdateWasCacheHit());
  auto again = limbSource(cache);
  again->Update();
  EXPECT_TRUE(again->GetLastUpdateWasCacheHit());
  EXPECT_EQ(scalars(again->GetOutput())->GetComponent(7, 0), values->GetComponent(7, 0));

  auto airless = vtkSmartPointer<vtkLimbLuminanceSource>::New();
  airless->SetAtmosphere("");
  airless->Update();  // an error, no crash
  EXPECT_EQ(scalars(airless->GetOutput()), nullptr);
}

// Cancel (SetAbortExecute(1) from a progress observer, as the GUI's worker does): both
// eclipse sources stop with an empty output, GetLastUpdateAborted, and no error event (a
// cancel is not an error: VTK printed the source's error and the executive's failure);
// cleared, the next update computes the table.
TEST(EclipseAtmosphereFilters, AbortIsQuietAndTheNextUpdateComputes) {
  CacheDir cache;
  const auto limb = limbSource(cache);
  const auto shadow = shadowSource(cache);
  for (vtkEclipseAtmosphereSource* source :
       {static_cast<vtkEclipseAtmosphereSource*>(shadow), static_cast<vtkEclipseAtmosphereSource*>(limb)}) {
    int errors = 0;
    vtkNew<vtkCallbackCommand> onError;
    onError->SetClientData(&errors);
    onError->SetCallback([](vtkObject*, unsigned long, void* client, void*) { ++*static_cast<int*>(client); });
    vtkNew<vtkCallbackCommand> onProgress;
    onProgress->SetCallback([](vtkObject* caller, unsigned long, void*, void* data) {
      if (*static_cast<double*>(data) > 0.6) static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
    });
    source->AddObserver(vtkCommand::ErrorEvent, onError);
    source->AddObserver(vtkCommand::ProgressEvent, onProgress);
    source->Update();
    EXPECT_TRUE(source->GetLastUpdateAborted()) << source->GetClassName();
    EXPECT_EQ(source->GetOutput()->GetNumberOfPoints(), 0) << source->GetClassName();
    EXPECT_EQ(errors, 0) << source->GetClassName();
    source->RemoveObserver(onProgress);
    source->SetAbortExecute(0);
    source->Update();
    EXPECT_FALSE(source->GetLastUpdateAborted()) << source->GetClassName();
    EXPECT_GT(source->GetOutput()->GetNumberOfPoints(), 0) << source->GetClassName();
    EXPECT_EQ(errors, 0) << source->GetClassName();
  }
}

// Ranged (u, v in [0.5, 1], 2 x 2 texels): its texels are the whole 4 x 4 LuT's texels
// (2 + i, 2 + j) (the same centres), bit for bit; the ranges in field data, the point
// coordinates and the cache key (a different table, not a cache hit).
TEST(EclipseAtmosphereFilters, RangedLimbLuminanceLutIsPartOfTheWholeOne) {
  CacheDir cache;
  const auto make = [&](int size, const eclipse::LutRange* range) {
    auto s = vtkSmartPointer<vtkLimbLuminanceSource>::New();
    configure(s.Get(), cache);
    s->SetWidth(size);
    s->SetHeight(size);
    s->SetColumns(4);
    s->SetLimbRows(16);
    s->SetScatteringCells(4);
    if (range) s->SetLutRange(*range);
    s->Update();
    return s;
  };
  const eclipse::LutRange range{0.5, 1.0, 0.5, 1.0, 0.0};
  auto whole = make(4, nullptr);
  auto ranged = make(2, &range);
  EXPECT_FALSE(ranged->GetLastUpdateWasCacheHit());
  vtkImageData* r = ranged->GetOutput();
  vtkImageData* w = whole->GetOutput();
  int dims[3];
  r->GetDimensions(dims);
  ASSERT_EQ(dims[0], 2);
  ASSERT_EQ(dims[2], 4);
  EXPECT_EQ(filters::lutRangeOf(filters::fieldParameters(r), "ranged"), range);
  double p[3];
  r->GetPoint(0, p);
  EXPECT_DOUBLE_EQ(p[0], 0.625);
  EXPECT_DOUBLE_EQ(p[1], 0.625);
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        int a[3] = {i, j, k}, b[3] = {i + 2, j + 2, k};
        for (int c = 0; c < 3; ++c)
          EXPECT_EQ(scalars(r)->GetComponent(r->ComputePointId(a), c), scalars(w)->GetComponent(w->ComputePointId(b), c))
              << i << " " << j << " " << k;
      }
}

TEST(EclipseAtmosphereFilters, ProfileOfTheAtmosphericLutIsRedInTheUmbra) {
  CacheDir cache;
  auto source = shadowSource(cache);
  source->SetWidth(48);
  source->SetHeight(32);
  auto profile = vtkSmartPointer<vtkShadowProfileFilter>::New();
  profile->SetInputConnection(source->GetOutputPort());
  profile->SetReceiverDistanceM(384400e3);
  profile->SetSamples(11);
  profile->Update();
  vtkTable* t = profile->GetOutput();
  ASSERT_EQ(t->GetNumberOfRows(), 11);
  const double r = t->GetValueByName(0, "r").ToDouble(), g = t->GetValueByName(0, "g").ToDouble(),
               b = t->GetValueByName(0, "b").ToDouble(), lum = t->GetValueByName(0, "luminance").ToDouble();
  EXPECT_GT(r, g);
  EXPECT_GT(g, b);
  EXPECT_GT(r, 1e-6);
  EXPECT_LT(r, 1e-2);
  EXPECT_NEAR(lum, 0.2126 * r + 0.7152 * g + 0.0722 * b, 1e-12);
}

// The tables of vtkAtmosphereTablesSource (same options, refraction on), read back with
// tablesFromBlocks / refractionFromBlocks, prepare the same shadow model as the library's
// own precomputation: the LuTs agree within float rounding (the blocks store floats).
TEST(EclipseAtmosphereFilters, TablesFromTheTablesSourcePrepareTheSameLut) {
  CacheDir cache;
  const atmosphere::Atmosphere atm = atmosphere::loadAtmosphere("earth", atmosphere::WavelengthSet::rgb().nm);
  const eclipse::EclipseAtmosphereOptions o = smallOptions();
  auto source = tablesSource(cache);
  source->Update();
  ASSERT_EQ(source->GetLastError(), "");
  const auto fromBlocks = eclipse::prepareEclipseAtmosphere(atm, filters::tablesFromBlocks(source->GetOutput(), atm),
                                                            filters::refractionFromBlocks(source->GetOutput(), atm),
                                                            "earth", 1.496e11, o);
  const auto direct = eclipse::prepareEclipseAtmosphere(atm, "earth", 1.496e11, o);
  eclipse::AtmosphericShadowLutParams p;
  p.width = 8, p.height = 6;
  p.limb = {32, 32, 4, 4};
  const eclipse::ShadowLut a = eclipse::buildAtmosphericShadowLut(fromBlocks->model, p);
  const eclipse::ShadowLut b = eclipse::buildAtmosphericShadowLut(direct->model, p);
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  double maxDiff = 0.0;
  for (std::size_t k = 0; k < a.rgb.size(); ++k) maxDiff = std::max(maxDiff, std::abs(double(a.rgb[k]) - double(b.rgb[k])));
  EXPECT_LT(maxDiff, 1e-5);  // float tables: relative rounding ~6e-8, carried through the integrals
  // A multiblock without the refraction table: a clear error.
  source->SetTables(vtkAtmosphereTablesSource::Bruneton);
  source->Update();
  try {
    filters::refractionFromBlocks(source->GetOutput(), atm);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("refraction"), std::string::npos) << e.what();
  }
  // The tables of another atmosphere: refused.
  const atmosphere::Atmosphere mars = atmosphere::loadAtmosphere("mars", atmosphere::WavelengthSet::rgb().nm);
  EXPECT_THROW(eclipse::prepareEclipseAtmosphere(mars, filters::tablesFromBlocks(source->GetOutput(), atm),
                                                 atmosphere::RefractionTable{}, "mars", 2.28e11, o),
               std::invalid_argument);
}

// The shadow-LuT source fed by vtkAtmosphereTablesSource (the pipeline) makes the LuT of
// the Atmosphere property (same options) within float rounding; a second pipeline reads
// the atmosphere tables from their cache (no precomputation); an input without the
// refraction table gives the same LuT (the rows it reads traced by the source); an input
// of straight paths with refraction on is a clear error.
TEST(EclipseAtmosphereFilters, ShadowLutSourceTakesTheTablesThroughItsInput) {
  CacheDir cache;
  auto byProperty = shadowSource(cache);
  byProperty->SetUseCache(false);
  byProperty->Update();
  for (int run = 0; run < 2; ++run) {
    auto tables = tablesSource(cache);
    auto lut = shadowSource(cache);
    lut->SetAtmosphere(nullptr);  // from the input
    lut->SetUseCache(false);
    lut->SetInputConnection(tables->GetOutputPort());
    lut->Update();
    EXPECT_EQ(tables->GetLastPrecomputeCalls(), run == 0 ? 1 : 0) << "run " << run;
    if (run == 1) { EXPECT_EQ(tables->GetLastComputed(), 0); }
    EXPECT_LT(maxRgbDifference(lut->GetOutput(), byProperty->GetOutput()), 1e-5) << "run " << run;
    EXPECT_NE(filters::fieldParameters(lut->GetOutput()).at("atmosphereTables").find("input:"), std::string::npos);
  }
  // Bruneton tables only, refraction on: the rows of the refraction table that the LuT
  // reads are traced by the source, and the LuT is the same.
  auto bruneton = tablesSource(cache);
  bruneton->SetTables(vtkAtmosphereTablesSource::Bruneton);
  auto lut = shadowSource(cache);
  lut->SetAtmosphere(nullptr);
  lut->SetUseCache(false);
  lut->SetInputConnection(bruneton->GetOutputPort());
  ErrorCatcher errors(lut);
  lut->Update();
  EXPECT_EQ(errors.message, "");
  EXPECT_LT(maxRgbDifference(lut->GetOutput(), byProperty->GetOutput()), 1e-5);
  // Tables of straight paths with refraction on: refused too.
  auto straight = tablesSource(cache);
  straight->SetRefractedPaths(false);
  lut->SetInputConnection(straight->GetOutputPort());
  errors.message.clear();
  lut->Update();
  EXPECT_NE(errors.message.find("refracted paths off"), std::string::npos) << errors.message;
}
