// umbra precompute shadow --occluder BODY [--size N] [--distance-range MIN:MAX] --output FILE.exr
// umbra precompute eclipse --occluder earth|mars --atmosphere PRESET [--size N] [--limb-size N]
//                          [--limb-lut-size N] [--layers N] [--draft-tables] [--distance-range MIN:MAX] --output DIR
//   writes DIR/eclipse-shadow-atmosphere.exr (the shadow LuT, R G B = I/I_sun) and
//   DIR/eclipse-limb-luminance.exr (the limb-luminance LuT, slices stacked), both with their
//   parameters in the header; DIR is created when its parent exists.
#include "Commands.hpp"
#include "OutputFile.hpp"
#include "Ranks.hpp"
#include "ShadowCommon.hpp"
#include "ShadowLutData.h"
#include "vtkEclipseShadowLutSource.h"
#include "vtkLimbLuminanceSource.h"

#include "umbra/tables/Exr.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>

namespace umbra::cli {

void addPrecomputeCommand(CLI::App& app, Action& action) {
  CLI::App* precompute = app.add_subcommand("precompute", "Precompute lookup tables and write them as EXR");
  precompute->require_subcommand(1);
  CLI::App* shadow = precompute->add_subcommand(
      "shadow", "The eclipse-shadow lookup table of an occluder (I/I_sun over the LuT coordinates u, v of Eq. 4)");

  struct Options {
    std::string occluder, output, distanceRange;
    int size = 256;
    double limbDarkening = 0.6;
    CacheOptions cache;
  };
  auto o = std::make_shared<Options>();
  shadow->add_option("--occluder", o->occluder, "Occluding body: Earth, Moon, Mars, Phobos, Deimos")->required();
  shadow->add_option("--size", o->size, "Texels along u and v")->capture_default_str()->check(CLI::Range(8, 4096));
  shadow->add_option("--limb-darkening", o->limbDarkening, "Linear limb-darkening coefficient of the Sun (Eq. 1)")->check(CLI::Range(0.0, 1.0))
      ->capture_default_str()->check(CLI::Range(0.0, 1.0));
  shadow->add_option("--output,-o", o->output, "EXR file to write")->required();
  addDistanceRangeOption(shadow, o->distanceRange);
  o->cache.addTo(shadow);

  shadow->callback([&action, o] {
    action = [o] {
      const auto start = std::chrono::steady_clock::now();
      output::checkWritable(o->output, {".exr"});
      o->cache.overRanks = true;  // under mpirun: the texels shared by the ranks, rank 0 writes
      const OccluderChoice occ = chooseOccluder(o->occluder, "", "");
      eclipse::LutRange range;
      if (!o->distanceRange.empty()) range = distanceRangeOption(o->distanceRange, occ, true, o->size);
      auto source =
          updateShadowLut(o->size, o->limbDarkening, o->cache, &occ, nullptr, o->distanceRange.empty() ? nullptr : &range);
      if (!parallel::Ranks::world().root()) return 0;
      vtkImageData* image = source->GetOutput();
      tables::writeExr(o->output, filters::toTable(filters::fromImageData(image), filters::fieldParameters(image)));
      std::cout << "wrote " << o->output << " (" << o->size << "x" << o->size << " shadow LuT of " << occ.name
                << ")" << ranksNote(start) << "\n";
      return 0;
    };
  });

  addPrecomputeEclipseCommand(*precompute, action);
}

void addPrecomputeEclipseCommand(CLI::App& precompute, Action& action) {
  namespace fs = std::filesystem;
  CLI::App* eclipse = precompute.add_subcommand(
      "eclipse", "The eclipse tables of an occluder with an atmosphere: the shadow LuT (refracted and scattered "
                 "light included) and the limb-luminance LuT (eclipse paper, 5.2-5.3)");
  struct Options {
    std::string occluder, output, distanceRange;
    int size = 256, limbLutSize = 64, layers = 1;
    EclipseAtmosphereChoice atmosphere;
    CacheOptions cache;
  };
  auto o = std::make_shared<Options>();
  eclipse->add_option("--occluder", o->occluder, "Occluding body (with an atmosphere): Earth, Mars")->required();
  eclipse->add_option("--size", o->size, "Texels along u and v of the shadow LuT")->capture_default_str()->check(CLI::Range(8, 4096));
  eclipse->add_option("--limb-lut-size", o->limbLutSize, "Texels along u and v, and columns, of the limb-luminance LuT")
      ->capture_default_str()->check(CLI::Range(2, 1024));
  eclipse->add_option("--layers", o->layers, "Rows kept of each limb view in the limb-luminance LuT")
      ->capture_default_str()->check(CLI::Range(1, 64));
  eclipse->add_option("--output,-o", o->output, "Directory to write (created if its parent exists)")->required();
  addDistanceRangeOption(eclipse, o->distanceRange);
  o->atmosphere.addTo(eclipse);
  o->cache.addTo(eclipse);

  eclipse->callback([&action, o] {
    action = [o] {
      const auto start = std::chrono::steady_clock::now();
      if (o->atmosphere.atmosphere.empty()) throw CommandError("--atmosphere: required (an airless occluder: 'umbra precompute shadow')");
      if (o->layers > o->atmosphere.limbSize)
        throw CommandError("--layers: at most --limb-size (" + std::to_string(o->atmosphere.limbSize) + ")");
      const fs::path dir(o->output);
      std::error_code ec;
      const fs::path parent = dir.has_parent_path() ? dir.parent_path() : fs::path(".");
      if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw CommandError(o->output + ": not a directory");
      if (!fs::exists(dir, ec) && !fs::is_directory(parent, ec))
        throw CommandError(o->output + ": directory " + parent.string() + " does not exist");
      OccluderChoice occ = chooseOccluder(o->occluder, "", "");
      occ.radiusM = o->atmosphere.bottomRadiusM();
      o->cache.overRanks = true;  // under mpirun: the texels shared by the ranks, rank 0 writes

      eclipse::LutRange range;
      if (!o->distanceRange.empty()) range = distanceRangeOption(o->distanceRange, occ, false, o->size);
      auto shadow =
          updateShadowLut(o->size, 0.6, o->cache, &occ, &o->atmosphere, o->distanceRange.empty() ? nullptr : &range);
      auto limb = vtkSmartPointer<vtkLimbLuminanceSource>::New();
      o->atmosphere.configure(limb, occ);
      limb->SetWidth(o->limbLutSize);
      limb->SetHeight(o->limbLutSize);
      limb->SetColumns(o->limbLutSize);
      limb->SetLayers(o->layers);
      limb->SetLimbRows(o->atmosphere.limbSize);
      // The same distances: the limb-luminance LuT over their u and v ranges too.
      if (!o->distanceRange.empty()) limb->SetLutRange(distanceRangeOption(o->distanceRange, occ, false, o->limbLutSize));
      // The same atmosphere tables, made once for both LuTs (also without the cache).
      if (shadow->GetNumberOfInputConnections(0) > 0) limb->SetInputConnection(shadow->GetInputConnection(0, 0));
      updateEclipseSource(limb, std::string("limb-luminance LuT") + (o->distanceRange.empty() ? "" : " (ranged)"), o->cache);

      if (!parallel::Ranks::world().root()) return 0;
      const bool created = !fs::exists(dir, ec);
      if (created && !fs::create_directory(dir, ec))
        throw CommandError(o->output + ": cannot create directory: " + ec.message());
      std::vector<std::string> written;
      try {
        for (vtkImageData* image : {shadow->GetOutput(), limb->GetOutput()}) {
          int dims[3];
          image->GetDimensions(dims);
          auto* values = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
          tables::Table t;
          t.width = dims[0];
          t.height = dims[1] * dims[2];
          t.channels = {"R", "G", "B"};
          t.data.assign(values->GetPointer(0), values->GetPointer(0) + 3 * static_cast<std::size_t>(t.width) * t.height);
          t.parameters = filters::fieldParameters(image);
          const std::string path = (dir / (t.parameters.at("kind") + ".exr")).string();
          tables::writeExr(path, t);
          written.push_back(path);
        }
      } catch (...) {
        for (const std::string& p : written) fs::remove(p, ec);
        if (created) fs::remove(dir, ec);
        throw;
      }
      std::cout << "wrote the eclipse tables of " << occ.name << " through " << o->atmosphere.atmosphere << " to "
                << o->output << ranksNote(start) << ":\n";
      for (const std::string& p : written) std::cout << "  " << p << "\n";
      return 0;
    };
  });
}

} // namespace umbra::cli
