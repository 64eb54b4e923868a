// vtkAtmosphereTablesSource: the blocks asked for, their values, and the cache keyed by
// what each table depends on.
#include "FieldParameters.h"
#include "umbra/tables/Exr.h"
#include "vtkAtmosphereTablesSource.h"

#include <vtkCallbackCommand.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMultiBlockDataSet.h>

#include <fstream>
#include <vtkNew.h>
#include <vtkInformation.h>
#include <vtkPointData.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace fs = std::filesystem;

namespace {
struct CacheDir {
  fs::path path = fs::temp_directory_path() / ("umbra-atmosphere-filter-test-" + std::to_string(::getpid()));
  ~CacheDir() { fs::remove_all(path); }
};

vtkImageData* block(vtkAtmosphereTablesSource* s, const std::string& name) {
  vtkMultiBlockDataSet* out = s->GetOutput();
  for (unsigned i = 0; i < out->GetNumberOfBlocks(); ++i)
    if (out->HasMetaData(i) && name == out->GetMetaData(i)->Get(vtkCompositeDataSet::NAME()))
      return vtkImageData::SafeDownCast(out->GetBlock(i));
  return nullptr;
}

vtkImageData* refractionBlock(vtkAtmosphereTablesSource* s) { return block(s, "refraction"); }

/// Tiny tables (the suite stays fast): transmittance 16x8, scattering 2*4 x 8 x 4,
/// irradiance 8x4, 2 orders; the refraction table 32x16.
void configure(vtkAtmosphereTablesSource* s, const CacheDir& cache, const char* atmosphere,
               int tables = vtkAtmosphereTablesSource::Refraction) {
  s->SetAtmosphere(atmosphere);
  s->SetTables(tables);
  s->SetRefractionWidth(32);
  s->SetRefractionHeight(16);
  s->SetTransmittanceSize(16, 8);
  s->SetScatteringSize(4, 8, 4, 2);
  s->SetIrradianceSize(8, 4);
  s->SetOrders(2);
  s->SetCacheDirectory(cache.path.c_str());
}

std::vector<std::string> blockNames(vtkAtmosphereTablesSource* s) {
  std::vector<std::string> names;
  vtkMultiBlockDataSet* out = s->GetOutput();
  for (unsigned i = 0; i < out->GetNumberOfBlocks(); ++i)
    names.push_back(out->HasMetaData(i) ? out->GetMetaData(i)->Get(vtkCompositeDataSet::NAME()) : "");
  return names;
}

std::vector<std::string> cachedKinds(const CacheDir& cache) {
  std::vector<std::string> files;
  if (fs::exists(cache.path))
    for (const auto& e : fs::directory_iterator(cache.path)) files.push_back(e.path().filename().string());
  std::sort(files.begin(), files.end());
  return files;
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

// ---- the Bruneton tables ----------------------------------------------------------------

TEST(AtmosphereTablesSource, EveryTexelOfEveryTableIsFiniteAtEveryPreset) {
  CacheDir cache;
  for (const bool refracted : {false, true})
  for (const char* preset : {"earth", "mars", "earth-2015-calbuco"}) {
    SCOPED_TRACE(std::string(preset) + (refracted ? " (refracted paths)" : ""));
    vtkNew<vtkAtmosphereTablesSource> source;
    configure(source, cache, preset, vtkAtmosphereTablesSource::All);
    source->SetRefractedPaths(refracted);
    source->SetRefractionStepM(20e3);
    source->Update();
    ASSERT_TRUE(source->GetLastError().empty()) << source->GetLastError();
    EXPECT_EQ(source->GetLastPrecomputeCalls(), 1);
    const auto names = blockNames(source);
    for (const char* name : {"transmittance", "multiple-scattering", "direct-irradiance", "irradiance", "refraction"})
      EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << preset << " " << name;
    EXPECT_NE(std::find(names.begin(), names.end(), "single-scattering-molecules"), names.end()) << preset;
    EXPECT_EQ(source->GetLastComputed() + source->GetLastCacheHits(), static_cast<int>(names.size()));
    for (const std::string& name : names) {
      vtkImageData* image = block(source, name);
      ASSERT_NE(image, nullptr) << name;
      const auto parameters = umbra::filters::fieldParameters(image);
      EXPECT_EQ(parameters.at("kind"), "atmosphere-" + name);
      int dims[3];
      image->GetDimensions(dims);
      if (name.rfind("single-scattering", 0) == 0 || name == "multiple-scattering") {
        EXPECT_EQ(dims[0], 8) << name;
        EXPECT_EQ(dims[1], 8) << name;
        EXPECT_EQ(dims[2], 4) << name;
        EXPECT_EQ(parameters.at("depth"), "4");
      } else {
        EXPECT_EQ(dims[2], 1) << name;
      }
      const std::vector<std::string> arrays =
          name == "refraction" ? std::vector<std::string>{"deviation_rad", "contact_altitude_m"}
                               : std::vector<std::string>{"L680nm", "L550nm", "L440nm"};
      ASSERT_EQ(image->GetPointData()->GetNumberOfArrays(), static_cast<int>(arrays.size())) << name;
      for (const std::string& a : arrays) {
        auto* array = vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray(a.c_str()));
        ASSERT_NE(array, nullptr) << preset << " " << name << " " << a;
        ASSERT_EQ(array->GetNumberOfTuples(), static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2]);
        for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i) {
          const float v = array->GetValue(i);
          ASSERT_TRUE(std::isfinite(v)) << preset << " " << name << " " << a << " " << i;
          if (name != "refraction") {
            ASSERT_GE(v, 0.0f) << preset << " " << name << " " << a << " " << i;
          }
        }
      }
    }
    // Transmittance is at most 1, and larger at the top than at the ground.
    auto* t = vtkFloatArray::SafeDownCast(block(source, "transmittance")->GetPointData()->GetArray("L550nm"));
    for (vtkIdType i = 0; i < t->GetNumberOfTuples(); ++i) ASSERT_LE(t->GetValue(i), 1.0f + 1e-6f);
  }
}

TEST(AtmosphereTablesSource, SecondSourceReadsEveryTableFromTheCache) {
  CacheDir cache;
  vtkNew<vtkAtmosphereTablesSource> first, second;
  configure(first, cache, "earth", vtkAtmosphereTablesSource::All);
  first->Update();
  ASSERT_TRUE(first->GetLastError().empty()) << first->GetLastError();
  const auto names = blockNames(first);
  EXPECT_EQ(first->GetLastCacheHits(), 0);
  configure(second, cache, "earth", vtkAtmosphereTablesSource::All);
  second->Update();
  EXPECT_EQ(second->GetLastComputed(), 0);
  EXPECT_EQ(second->GetLastPrecomputeCalls(), 0);
  EXPECT_EQ(second->GetLastCacheHits(), static_cast<int>(names.size()));
  ASSERT_EQ(blockNames(second), names);
  for (const std::string& name : names) {
    vtkPointData* a = block(first, name)->GetPointData();
    vtkPointData* b = block(second, name)->GetPointData();
    ASSERT_EQ(a->GetNumberOfArrays(), b->GetNumberOfArrays());
    for (int k = 0; k < a->GetNumberOfArrays(); ++k) {
      auto* x = vtkFloatArray::SafeDownCast(a->GetArray(k));
      auto* y = vtkFloatArray::SafeDownCast(b->GetArray(a->GetArrayName(k)));
      ASSERT_NE(y, nullptr);
      for (vtkIdType i = 0; i < x->GetNumberOfTuples(); ++i) ASSERT_EQ(x->GetValue(i), y->GetValue(i)) << name;
    }
    EXPECT_EQ(umbra::filters::fieldParameters(block(first, name)), umbra::filters::fieldParameters(block(second, name)));
  }
  // A subset of the cached tables is a hit too.
  vtkNew<vtkAtmosphereTablesSource> subset;
  configure(subset, cache, "earth", vtkAtmosphereTablesSource::MultipleScattering);
  subset->Update();
  EXPECT_EQ(subset->GetLastCacheHits(), 1);
  EXPECT_EQ(subset->GetLastComputed(), 0);
  // Another order count is another table.
  vtkNew<vtkAtmosphereTablesSource> orders;
  configure(orders, cache, "earth", vtkAtmosphereTablesSource::MultipleScattering);
  orders->SetOrders(3);
  orders->Update();
  EXPECT_EQ(orders->GetLastComputed(), 1);
}

// The lowest Sun (MuSMin) and the density directions are part of the scattering tables'
// key and reach their parameters: another value is another precomputation; a minimum of
// directions below what the phase functions ask (Earth: 16) changes nothing in the values
// but is its own key; the lowest Sun changes the multiple scattering's values.
TEST(AtmosphereTablesSource, LowestSunAndDensityDirectionsKeyTheScatteringTables) {
  CacheDir cache;
  auto make = [&](double muSMin, int directions) {
    vtkSmartPointer<vtkAtmosphereTablesSource> s = vtkSmartPointer<vtkAtmosphereTablesSource>::New();
    configure(s, cache, "earth", vtkAtmosphereTablesSource::MultipleScattering);
    s->SetMuSMin(muSMin);
    s->SetMinimumDensityDirections(directions);
    s->Update();
    EXPECT_TRUE(s->GetLastError().empty()) << s->GetLastError();
    return s;
  };
  const double day = vtkNew<vtkAtmosphereTablesSource>()->GetMuSMin();  // the default
  auto dayTables = make(day, 0);
  EXPECT_NEAR(day, std::cos(102.0 * std::acos(-1.0) / 180.0), 1e-15);
  EXPECT_EQ(dayTables->GetLastComputed(), 1);
  EXPECT_EQ(make(day, 0)->GetLastCacheHits(), 1);
  auto low = make(std::cos(130.0 * std::acos(-1.0) / 180.0), 0);
  EXPECT_EQ(low->GetLastComputed(), 1);
  const auto p = umbra::filters::fieldParameters(block(low, "multiple-scattering"));
  EXPECT_NEAR(std::stod(p.at("muSMin")), std::cos(130.0 * std::acos(-1.0) / 180.0), 1e-12);
  auto* a = vtkFloatArray::SafeDownCast(block(dayTables, "multiple-scattering")->GetPointData()->GetArray(0));
  auto* b = vtkFloatArray::SafeDownCast(block(low, "multiple-scattering")->GetPointData()->GetArray(0));
  int differ = 0;
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i) differ += a->GetValue(i) != b->GetValue(i);
  EXPECT_GT(differ, a->GetNumberOfTuples() / 2);
  auto more = make(day, 24);
  EXPECT_EQ(more->GetLastComputed(), 1);
  EXPECT_NE(umbra::filters::fieldParameters(block(more, "multiple-scattering")).at("samples"),
            umbra::filters::fieldParameters(block(dayTables, "multiple-scattering")).at("samples"));
}

TEST(AtmosphereTablesSource, TransmittanceAloneComputesNoScattering) {
  CacheDir cache;
  vtkNew<vtkAtmosphereTablesSource> source;
  configure(source, cache, "earth", vtkAtmosphereTablesSource::Transmittance);
  source->Update();
  ASSERT_TRUE(source->GetLastError().empty()) << source->GetLastError();
  EXPECT_EQ(blockNames(source), std::vector<std::string>{"transmittance"});
  EXPECT_EQ(source->GetLastComputed(), 1);
  const auto files = cachedKinds(cache);
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0].rfind("atmosphere-transmittance-", 0), 0u) << files[0];
  // The same values as the transmittance of the full precomputation (which then hits it).
  vtkNew<vtkAtmosphereTablesSource> full;
  configure(full, cache, "earth", vtkAtmosphereTablesSource::Bruneton);
  full->SetUseCache(false);
  full->Update();
  auto* a = vtkFloatArray::SafeDownCast(block(source, "transmittance")->GetPointData()->GetArray("L440nm"));
  auto* b = vtkFloatArray::SafeDownCast(block(full, "transmittance")->GetPointData()->GetArray("L440nm"));
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i) ASSERT_EQ(a->GetValue(i), b->GetValue(i));
}

TEST(AtmosphereTablesSource, OtherAerosolsMissTheScatteringTablesButHitRefraction) {
  CacheDir cache;
  vtkNew<vtkAtmosphereTablesSource> earth, calbuco;
  const int tables = vtkAtmosphereTablesSource::SingleScattering | vtkAtmosphereTablesSource::Refraction;
  configure(earth, cache, "earth", tables);
  earth->Update();
  const int single = static_cast<int>(blockNames(earth).size()) - 1;
  EXPECT_GE(single, 2);  // molecules and aerosols
  configure(calbuco, cache, "earth-2015-calbuco", tables);
  calbuco->Update();
  ASSERT_TRUE(calbuco->GetLastError().empty()) << calbuco->GetLastError();
  EXPECT_EQ(calbuco->GetLastCacheHits(), 1);  // refraction
  EXPECT_EQ(calbuco->GetLastComputed(), static_cast<int>(blockNames(calbuco).size()) - 1);
  EXPECT_EQ(calbuco->GetLastPrecomputeCalls(), 1);
}

TEST(AtmosphereTablesSource, UniformWavelengthsAndRefractedPaths) {
  CacheDir cache;
  vtkNew<vtkAtmosphereTablesSource> source;
  configure(source, cache, "earth", vtkAtmosphereTablesSource::Transmittance);
  source->SetWavelengths(4);
  source->SetRefractedPaths(true);
  source->SetRefractionStepM(50e3);
  source->Update();
  ASSERT_TRUE(source->GetLastError().empty()) << source->GetLastError();
  vtkPointData* pd = block(source, "transmittance")->GetPointData();
  ASSERT_EQ(pd->GetNumberOfArrays(), 4);
  EXPECT_STREQ(pd->GetArrayName(0), "L418p75nm");  // 360 + 0.5 * 470 / 4
  EXPECT_EQ(umbra::filters::fieldParameters(block(source, "transmittance")).at("refractedPaths"), "1");
}

TEST(AtmosphereTablesSource, BadSizesAreAnError) {
  CacheDir cache;
  vtkNew<vtkAtmosphereTablesSource> source;
  configure(source, cache, "earth", vtkAtmosphereTablesSource::Bruneton);
  source->SetScatteringSize(4, 7, 4, 2);
  source->Update();
  EXPECT_NE(source->GetLastError().find("scatteringMu must be even"), std::string::npos) << source->GetLastError();
  EXPECT_FALSE(fs::exists(cache.path));
}

TEST(AtmosphereTablesSource, OneOrderGivesZeroMultipleScatteringAndIndirectIrradiance) {
  CacheDir cache;
  vtkNew<vtkAtmosphereTablesSource> source;
  configure(source, cache, "earth", vtkAtmosphereTablesSource::MultipleScattering | vtkAtmosphereTablesSource::Irradiance);
  source->SetOrders(1);
  source->Update();
  ASSERT_TRUE(source->GetLastError().empty()) << source->GetLastError();
  for (const char* name : {"multiple-scattering", "irradiance"}) {
    vtkImageData* image = block(source, name);
    ASSERT_NE(image, nullptr) << name;
    auto* a = vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("L550nm"));
    ASSERT_GT(a->GetNumberOfTuples(), 0);
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i) ASSERT_EQ(a->GetValue(i), 0.0f) << name;
  }
  auto* direct = vtkFloatArray::SafeDownCast(block(source, "direct-irradiance")->GetPointData()->GetArray("L550nm"));
  EXPECT_GT(direct->GetRange()[1], 0.5);
}

// Cancel: SetAbortExecute(1) during the precomputation (here from a progress observer; the
// GUI does it from its thread) stops it quietly with an empty output and caches nothing; the
// next update after clearing the flag computes the tables.
TEST(AtmosphereTablesSource, AbortExecuteCancelsThePrecomputation) {
  CacheDir cache;
  vtkNew<vtkAtmosphereTablesSource> source;
  configure(source, cache, "earth", vtkAtmosphereTablesSource::Bruneton);
  double lastProgress = 0.0;
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetClientData(&lastProgress);
  onProgress->SetCallback([](vtkObject* caller, unsigned long, void* client, void* data) {
    *static_cast<double*>(client) = *static_cast<double*>(data);
    if (*static_cast<double*>(data) > 0.2) static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
  });
  source->AddObserver(vtkCommand::ProgressEvent, onProgress);
  source->Update();
  EXPECT_EQ(source->GetLastError(), "precomputation cancelled");
  EXPECT_EQ(source->GetOutput()->GetNumberOfBlocks(), 0u);
  EXPECT_LT(lastProgress, 0.5);
  EXPECT_TRUE(cachedKinds(cache).empty());
  source->RemoveObserver(onProgress);
  source->SetAbortExecute(0);
  source->Modified();
  source->Update();
  EXPECT_TRUE(source->GetLastError().empty()) << source->GetLastError();
  EXPECT_EQ(blockNames(source).size(), 7u);  // transmittance, 3 single scattering, multiple, 2 irradiance
}

// A cache that cannot be written (its directory is a file) costs the tables' storage, not
// the tables: they are given, computed each time, with a warning (GetLastCacheWarning).
TEST(AtmosphereTablesSource, AnUnwritableCacheStillGivesTheTables) {
  CacheDir cache;
  fs::create_directories(cache.path);
  std::ofstream(cache.path / "file") << "x";
  CacheDir blocked;
  blocked.path = cache.path / "file" / "cache";
  vtkNew<vtkAtmosphereTablesSource> source;
  configure(source, blocked, "earth", vtkAtmosphereTablesSource::Bruneton | vtkAtmosphereTablesSource::Refraction);
  source->Update();
  EXPECT_TRUE(source->GetLastError().empty()) << source->GetLastError();
  EXPECT_FALSE(source->GetLastCacheWarning().empty());
  EXPECT_NE(block(source, "transmittance"), nullptr);
  EXPECT_NE(refractionBlock(source), nullptr);
  source->Modified();
  source->Update();
  EXPECT_EQ(source->GetLastCacheHits(), 0);
  EXPECT_GT(source->GetLastComputed(), 0);
  blocked.path = cache.path;  // removed once
}

// FileBacked: the tables written to files a batch of wavelengths at a time are the
// in-memory blocks' values to the bit, with the same parameters; a second source reads them
// from the cache (no precomputation) and copies the same files; without the cache nothing
// goes into it.
TEST(AtmosphereTablesSource, FileBackedTablesAreTheBlocksValuesWrittenBatchByBatch) {
  CacheDir cache, scratch, scratch2, untouched;
  scratch.path += "-scratch", scratch2.path += "-scratch2", untouched.path += "-untouched";
  fs::create_directories(scratch.path);
  fs::create_directories(scratch2.path);
  vtkNew<vtkAtmosphereTablesSource> memory, files, again, off;
  for (vtkAtmosphereTablesSource* s : {memory.Get(), files.Get(), again.Get(), off.Get()}) {
    configure(s, cache, "earth", vtkAtmosphereTablesSource::Bruneton);
    s->SetWavelengths(5);
  }
  memory->SetUseCache(false);
  memory->Update();
  ASSERT_TRUE(memory->GetLastError().empty()) << memory->GetLastError();
  files->SetFileBacked(true);
  files->SetScratchDirectory(scratch.path.c_str());
  files->SetWavelengthBatch(2);  // 2 + 2 + 1
  files->Update();
  ASSERT_TRUE(files->GetLastError().empty()) << files->GetLastError();
  EXPECT_EQ(files->GetLastComputed(), 7);
  const auto names = blockNames(memory);
  ASSERT_EQ(blockNames(files), names);
  for (const std::string& name : names) {
    auto parameters = umbra::filters::fieldParameters(block(files, name));
    ASSERT_EQ(parameters.count("file"), 1u) << name;
    EXPECT_EQ(block(files, name)->GetPointData()->GetNumberOfArrays(), 0) << name;
    const umbra::tables::Table t = umbra::tables::readExr(parameters.at("file"));
    vtkPointData* a = block(memory, name)->GetPointData();
    ASSERT_EQ(t.channels.size(), static_cast<std::size_t>(a->GetNumberOfArrays())) << name;
    for (std::size_t c = 0; c < t.channels.size(); ++c) {
      auto* x = vtkFloatArray::SafeDownCast(a->GetArray(t.channels[c].c_str()));
      ASSERT_NE(x, nullptr) << t.channels[c];
      ASSERT_EQ(x->GetNumberOfTuples(), static_cast<vtkIdType>(t.width) * t.height) << name;
      for (vtkIdType i = 0; i < x->GetNumberOfTuples(); ++i)
        ASSERT_EQ(x->GetValue(i), t.data[static_cast<std::size_t>(i) * t.channels.size() + c]) << name << " " << i;
    }
    int dims[3], fileDims[3];
    block(memory, name)->GetDimensions(dims);
    block(files, name)->GetDimensions(fileDims);
    EXPECT_EQ(std::vector<int>(dims, dims + 3), std::vector<int>(fileDims, fileDims + 3)) << name;
    parameters.erase("file");
    EXPECT_EQ(parameters, umbra::filters::fieldParameters(block(memory, name))) << name;
  }

  again->SetFileBacked(true);
  again->SetScratchDirectory(scratch2.path.c_str());
  again->Update();
  ASSERT_TRUE(again->GetLastError().empty()) << again->GetLastError();
  EXPECT_EQ(again->GetLastPrecomputeCalls(), 0);
  EXPECT_EQ(again->GetLastCacheHits(), 7);
  for (const std::string& name : names) {
    const std::string a = umbra::filters::fieldParameters(block(files, name)).at("file");
    const std::string b = umbra::filters::fieldParameters(block(again, name)).at("file");
    EXPECT_NE(a, b);
    std::ifstream fa(a, std::ios::binary), fb(b, std::ios::binary);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(fa), {}), std::string(std::istreambuf_iterator<char>(fb), {}))
        << name;
  }

  off->SetFileBacked(true);
  off->SetScratchDirectory(scratch.path.c_str());
  off->SetCacheDirectory(untouched.path.c_str());
  off->SetUseCache(false);
  off->Update();
  ASSERT_TRUE(off->GetLastError().empty()) << off->GetLastError();
  EXPECT_EQ(off->GetLastComputed(), 7);
  EXPECT_FALSE(fs::exists(untouched.path));

  vtkNew<vtkAtmosphereTablesSource> noScratch;
  configure(noScratch, cache, "earth", vtkAtmosphereTablesSource::Transmittance);
  noScratch->SetFileBacked(true);
  noScratch->Update();
  EXPECT_NE(noScratch->GetLastError().find("ScratchDirectory"), std::string::npos) << noScratch->GetLastError();
}
