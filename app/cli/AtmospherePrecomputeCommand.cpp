// umbra atmosphere precompute --preset NAME|--config FILE [--refraction] [--orders N]
//   [--wavelengths N] [--transmittance-size WxH] [--scattering-size R,MU,MU_S,NU]
//   [--irradiance-size WxH] [--refraction-size WxH] [--wavelength-batch N] [--memory MiB]
//   [--spill auto|always|never] --output DIR [--cache-dir D] [--no-cache]
//
// Writes the Bruneton tables of vtkAtmosphereTablesSource (and, with --refraction, the
// refraction table; the scattering then follows refracted paths) into DIR, one EXR file per
// table named <kind>.exr (kind = "atmosphere-<block name>", e.g.
// atmosphere-transmittance.exr, atmosphere-single-scattering-molecules.exr), the layout of
// the filter's header comment: channels "L<nm>nm", 3D tables with their R slices stacked.
// DIR is created when its parent exists. Each file is written atomically; when one cannot
// be written, those already written by this run are removed (and DIR if this run made it).
// The source writes the Bruneton tables itself, each batch of wavelengths as it is finished
// (vtkAtmosphereTablesSource::SetFileBacked), into DIR's staging directory: no table is held
// for every wavelength, and --memory (or --wavelength-batch) bounds the batch; beyond what
// fits in memory the tables but J_k go through a temporary file (--spill,
// PrecomputeOptions::spillTables).
// The size options exist mostly for tests and quick looks (e.g. --transmittance-size 16x8
// --scattering-size 4,8,4,2 --irradiance-size 8x4 --orders 2 runs in well under a second).
#include "AtmosphereCommon.hpp"
#include "Commands.hpp"
#include "Ranks.hpp"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>


#include "Describe.hpp"
#include "FieldParameters.h"
#include "Precompute.hpp"
#include "vtkAtmosphereTablesSource.h"
#include "umbra/tables/Exr.h"
#include "umbra/tables/TableCache.h"

#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <regex>

namespace fs = std::filesystem;

namespace umbra::cli {
namespace {

std::vector<int> parseSize(const std::string& option, const std::string& text, int count, const char* separator,
                           const char* example) {
  std::vector<int> values;
  std::string pattern = R"((\d{1,5}))";
  for (int i = 1; i < count; ++i) pattern += std::string(separator) + R"((\d{1,5}))";
  std::smatch m;
  if (!std::regex_match(text, m, std::regex(pattern)))
    throw CommandError(option + ": expected " + example + ", got '" + text + "'");
  for (int i = 1; i <= count; ++i) values.push_back(std::stoi(m[i]));
  return values;
}

/// A block back as a table: its arrays as channels, (NU * MU_S) x (MU * R) for 3D blocks.
tables::Table tableOf(vtkImageData* image) {
  tables::Table t;
  int dims[3];
  image->GetDimensions(dims);
  t.width = dims[0];
  t.height = dims[1] * dims[2];
  vtkPointData* pd = image->GetPointData();
  const int nc = pd->GetNumberOfArrays();
  const std::size_t n = static_cast<std::size_t>(t.width) * t.height;
  t.data.resize(n * static_cast<std::size_t>(nc));
  for (int c = 0; c < nc; ++c) {
    vtkDataArray* a = pd->GetArray(c);
    t.channels.push_back(a->GetName());
    for (std::size_t i = 0; i < n; ++i)
      t.data[i * static_cast<std::size_t>(nc) + static_cast<std::size_t>(c)] =
          static_cast<float>(a->GetComponent(static_cast<vtkIdType>(i), 0));
  }
  t.parameters = filters::fieldParameters(image);
  return t;
}

} // namespace

void addAtmospherePrecomputeCommand(CLI::App& atmosphereCmd, Action& action) {
  CLI::App* precompute = atmosphereCmd.add_subcommand(
      "precompute", "Precompute the Bruneton 2017 tables of an atmosphere (transmittance, single scattering per "
                    "component, multiple scattering, direct and indirect irradiance; per unit solar irradiance) "
                    "into a directory, one EXR file per table");
  struct Options {
    std::string preset, config, output;
    bool refraction = false;
    int orders = atmosphere::kDefaultTableSizes.orders, wavelengths = 3, wavelengthBatch = 0;
    double memoryMiB = 128;
    std::string spill = "auto";
    std::string refractionSize = atmosphere::sizeText(atmosphere::kDefaultTableSizes.refraction),
                transmittanceSize = atmosphere::sizeText(atmosphere::kDefaultTableSizes.transmittance),
                scatteringSize = atmosphere::sizeText(atmosphere::kDefaultTableSizes.scattering),
                irradianceSize = atmosphere::sizeText(atmosphere::kDefaultTableSizes.irradiance);
    std::string step = "10km";
    CacheOptions cache;
  };
  auto o = std::make_shared<Options>();
  addAtmosphereOptions(precompute, o->preset, o->config);
  precompute->add_flag("--refraction", o->refraction,
                       "Integrate along refracted rays, and also write the refraction (deviation) table");
  precompute->add_option("--orders", o->orders, "Scattering orders (1: single scattering only)")->capture_default_str();
  precompute->add_option("--wavelengths", o->wavelengths,
                         "Wavelengths: 3 = 680, 550, 440 nm (R, G, B); else N uniform over 360-830 nm")
      ->capture_default_str();
  precompute->add_option("--transmittance-size", o->transmittanceSize, "Transmittance table WxH (x_mu x x_r)")
      ->capture_default_str();
  precompute->add_option("--scattering-size", o->scatteringSize,
                         "Scattering tables R,MU,MU_S,NU (MU even); stored as (NU*MU_S) x (MU*R)")
      ->capture_default_str();
  precompute->add_option("--irradiance-size", o->irradianceSize, "Irradiance tables WxH (x_mu_s x x_r)")
      ->capture_default_str();
  precompute->add_option("--refraction-size", o->refractionSize,
                         "Refraction table WxH (x_mu x x_r), with --refraction")
      ->capture_default_str();
  precompute->add_option("--wavelength-batch", o->wavelengthBatch,
                         "Wavelengths computed together (0: as many as --memory allows): fewer hold less memory and "
                         "take more time; the tables are the same (docs/accuracy-vs-speed/atmosphere-tables.md, \"Wavelengths computed "
                         "together\")")
      ->capture_default_str();
  precompute->add_option("--memory", o->memoryMiB,
                         "MiB the batch of wavelengths computed together may hold (with --wavelength-batch 0): all "
                         "wavelengths at once when they fit, else all at once with the tables spilled (--spill) when "
                         "they fit so, else batches that do")
      ->capture_default_str();
  precompute->add_option("--spill", o->spill,
                         "auto: when the batch does not fit --memory otherwise; always; never. Spilled, the tables but "
                         "the scattering density go through a temporary file in $TMPDIR (a batch's tables in less than "
                         "half the memory, for a little more time; the same tables)")
      ->check(CLI::IsMember({"auto", "always", "never"}))
      ->capture_default_str();
  precompute->add_option("--output", o->output, "Directory to write (created if its parent exists)")->required();
  o->cache.addTo(precompute);

  precompute->callback([&action, o] {
    action = [o] {
      using atmosphere::kMaxScatteringCells, atmosphere::kMaxTableSide, atmosphere::kMaxOrders, atmosphere::kMaxWavelengths;
      const atmosphere::TableSizes& d = atmosphere::kDefaultTableSizes;
      const std::string sides = "2 to " + std::to_string(kMaxTableSide) + " texels a side, got ";
      const auto twoD = [&](const char* option, const std::string& text, const int(&example)[2]) {
        const auto size = parseSize(option, text, 2, "x", ("WxH (e.g. " + atmosphere::sizeText(example) + ")").c_str());
        if (size[0] < 2 || size[1] < 2 || size[0] > kMaxTableSide || size[1] > kMaxTableSide)
          throw CommandError(std::string(option) + ": expected " + sides + text);
        return size;
      };
      const auto transmittance = twoD("--transmittance-size", o->transmittanceSize, d.transmittance);
      const auto irradiance = twoD("--irradiance-size", o->irradianceSize, d.irradiance);
      const auto refraction = twoD("--refraction-size", o->refractionSize, d.refraction);
      const auto scattering = parseSize("--scattering-size", o->scatteringSize, 4, ",",
                                        ("R,MU,MU_S,NU (e.g. " + atmosphere::sizeText(d.scattering) + ")").c_str());
      const auto cell = [](int n) { return n >= 2 && n <= kMaxScatteringCells; };
      if (!cell(scattering[0]) || !cell(scattering[1]) || scattering[1] < 4 || scattering[1] % 2 != 0 ||
          !cell(scattering[2]) || !cell(scattering[3]))
        throw CommandError("--scattering-size: expected R, MU_S, NU in 2.." + std::to_string(kMaxScatteringCells) +
                           " and MU even in 4.." + std::to_string(kMaxScatteringCells) + ", got " + o->scatteringSize);
      const auto count = [](const char* option, int n, int least, int most, const char* what) {
        if (n < least || n > most)
          throw CommandError(std::string(option) + ": expected " + std::to_string(least) + what + " to " +
                             std::to_string(most) + ", got " + std::to_string(n));
      };
      count("--orders", o->orders, 1, kMaxOrders, "");
      count("--wavelengths", o->wavelengths, 1, kMaxWavelengths, "");
      count("--wavelength-batch", o->wavelengthBatch, 0, kMaxWavelengths, " (from --memory)");
      if (!(o->memoryMiB >= 1.0 && o->memoryMiB <= 1e7))
        throw CommandError("--memory: expected 1 to 1e7 MiB, got " + atmosphere::formatNumber(o->memoryMiB));

      // The output directory: its parent must exist; it must be (or become) a directory.
      const fs::path dir(o->output);
      std::error_code ec;
      const fs::path parent = dir.has_parent_path() ? dir.parent_path() : fs::path(".");
      if (o->output.empty()) throw CommandError("--output: empty path");
      if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw CommandError(o->output + ": not a directory");
      if (!fs::exists(dir, ec) && !fs::is_directory(parent, ec))
        throw CommandError(o->output + ": directory " + parent.string() + " does not exist");

      // One-line errors for the atmosphere before any work.
      const atmosphere::AtmosphereModelPtr model = atmosphereOption(o->preset, o->config);
      const atmosphere::Atmosphere& atm = model->rgb();

      auto source = vtkSmartPointer<vtkAtmosphereTablesSource>::New();
      source->SetAtmosphereModel(model);
      source->SetTables(vtkAtmosphereTablesSource::Bruneton | (o->refraction ? vtkAtmosphereTablesSource::Refraction : 0));
      source->SetRefractedPaths(o->refraction);
      source->SetOrders(o->orders);
      // The batch: as asked, else all wavelengths when they fit --memory (over ranks: then
      // shared out by the source), else the most that fit; spilled (--spill auto) when the
      // batch does not fit in memory.
      int batch = o->wavelengthBatch;
      {
        atmosphere::PrecomputeOptions po;
        po.scatteringR = scattering[0], po.scatteringMu = scattering[1];
        po.scatteringMuS = scattering[2], po.scatteringNu = scattering[3];
        po.orders = o->orders;
        const int scatterers = static_cast<int>(
            std::count_if(atm.components.begin(), atm.components.end(), [](const auto& c) { return c.scatters(); }));
        const auto budget = static_cast<std::size_t>(o->memoryMiB * 1024.0 * 1024.0);
        const int count = batch > 0 ? std::min(batch, o->wavelengths) : o->wavelengths;
        po.spillTables = o->spill == "always" ||
                         (o->spill == "auto" && atmosphere::batchBytesPerWavelength(po, scatterers) * count > budget);
        if (batch == 0) {
          const int fit = atmosphere::wavelengthBatchFor(po, scatterers, o->wavelengths, budget);
          if (fit < o->wavelengths) batch = fit;
        }
        source->SetSpillTables(po.spillTables);
      }
      source->SetWavelengthBatch(batch);
      source->SetSpreadOverRanks(true);  // under mpirun: the wavelength batches shared, rank 0 writes
      source->SetWavelengths(o->wavelengths);
      source->SetTransmittanceSize(transmittance[0], transmittance[1]);
      source->SetScatteringSize(scattering[0], scattering[1], scattering[2], scattering[3]);
      source->SetIrradianceSize(irradiance[0], irradiance[1]);
      source->SetRefractionWidth(refraction[0]);
      source->SetRefractionHeight(refraction[1]);
      // Every table goes into a sibling temporary directory first; then that directory
      // becomes DIR (a new one: one rename), or its files move into DIR (an existing one):
      // a kill while the tables are written leaves no half-filled DIR. The source writes
      // the Bruneton tables there itself, a batch of wavelengths at a time (FileBacked).
      const bool root = parallel::Ranks::world().root();
      const bool created = !fs::exists(dir, ec);
      const fs::path target = dir.filename().empty() ? dir.parent_path() : dir;  // "out/" is "out"
      const fs::path staging = target.parent_path() / ("." + target.filename().string() + ".tmp-" +
                                                       std::to_string(::getpid()));
      if (root) {
        // A killed run's staging directory (its process gone) goes now.
        const std::string stagingPrefix = "." + target.filename().string() + ".tmp-";
        const fs::path parentDir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
        for (fs::directory_iterator it(parentDir, ec), end; !ec && it != end; it.increment(ec)) {
          const std::string name = it->path().filename().string();
          if (name.rfind(stagingPrefix, 0) != 0) continue;
          const long pid = std::atol(name.c_str() + stagingPrefix.size());
          std::error_code removeEc;
          if (pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) fs::remove_all(it->path(), removeEc);
        }
        ec.clear();
        fs::remove_all(staging, ec);
        if (!fs::create_directory(staging, ec))
          throw CommandError(o->output + ": cannot create a directory beside it: " + ec.message());
      }
      source->SetFileBacked(true);
      source->SetScratchDirectory(staging.string().c_str());
      try {
        updateTablesSource(source, o->cache, "atmosphere tables (" + atm.name + ")");
      } catch (...) {
        if (root) fs::remove_all(staging, ec);
        throw;
      }
      if (!root) return 0;
      vtkMultiBlockDataSet* blocks = source->GetOutput();
      std::vector<std::string> names;
      try {
        for (unsigned i = 0; i < blocks->GetNumberOfBlocks(); ++i) {
          auto* image = vtkImageData::SafeDownCast(blocks->GetBlock(i));
          if (!image) continue;
          const std::map<std::string, std::string> parameters = filters::fieldParameters(image);
          const std::string name = parameters.at("kind") + ".exr";
          if (const auto file = parameters.find("file"); file != parameters.end()) {
            fs::rename(file->second, staging / name, ec);
            if (ec) throw CommandError(file->second + ": cannot rename: " + ec.message());
          } else {
            tables::writeExr((staging / name).string(), tableOf(image));
          }
          names.push_back(name);
        }
        if (created) {
          fs::rename(staging, target, ec);
          if (ec) throw CommandError(o->output + ": cannot create directory: " + ec.message());
        } else {
          for (const std::string& name : names) {
            fs::rename(staging / name, dir / name, ec);
            if (ec) throw CommandError((dir / name).string() + ": cannot write: " + ec.message());
          }
          fs::remove(staging, ec);
        }
      } catch (...) {
        fs::remove_all(staging, ec);
        throw;
      }
      std::vector<std::string> written;
      for (const std::string& name : names) written.push_back((dir / name).string());
      std::cout << "wrote " << written.size() << " tables (" << atm.name << ", " << o->orders << " orders, "
                << o->wavelengths << " wavelengths" << (o->refraction ? ", refracted paths" : "") << ") to "
                << o->output << ":\n";
      for (const std::string& p : written) std::cout << "  " << p << "\n";
      return 0;
    };
  });
}

} // namespace umbra::cli
