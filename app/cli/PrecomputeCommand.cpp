// umbra precompute shadow --occluder BODY [--size N] --output FILE.exr
#include "Commands.hpp"
#include "OutputFile.hpp"
#include "ShadowCommon.hpp"
#include "ShadowLutData.h"
#include "vtkEclipseShadowLutSource.h"

#include "umbra/tables/Exr.h"

#include <vtkImageData.h>

#include <iostream>
#include <memory>

namespace umbra::cli {

void addPrecomputeCommand(CLI::App& app, Action& action) {
  CLI::App* precompute = app.add_subcommand("precompute", "Precompute lookup tables and write them as EXR");
  precompute->require_subcommand(1);
  CLI::App* shadow = precompute->add_subcommand(
      "shadow", "The eclipse-shadow lookup table of an occluder (I/I_sun over the LuT coordinates u, v of Eq. 4)");

  struct Options {
    std::string occluder, output;
    int size = 256;
    double limbDarkening = 0.6;
    CacheOptions cache;
  };
  auto o = std::make_shared<Options>();
  shadow->add_option("--occluder", o->occluder, "Occluding body: Earth, Moon, Mars, Phobos, Deimos")->required();
  shadow->add_option("--size", o->size, "Texels along u and v")->capture_default_str()->check(CLI::Range(8, 4096));
  shadow->add_option("--limb-darkening", o->limbDarkening, "Linear limb-darkening coefficient of the Sun (Eq. 1)")
      ->capture_default_str()->check(CLI::Range(0.0, 1.0));
  shadow->add_option("--output,-o", o->output, "EXR file to write")->required();
  o->cache.addTo(shadow);

  shadow->callback([&action, o] {
    action = [o] {
      output::checkWritable(o->output, {".exr"});
      const OccluderChoice occ = chooseOccluder(o->occluder, "", "");
      auto source = updateShadowLut(o->size, o->limbDarkening, o->cache, &occ);
      vtkImageData* image = source->GetOutput();
      tables::writeExr(o->output, filters::toTable(filters::fromImageData(image), filters::fieldParameters(image)));
      std::cout << "wrote " << o->output << " (" << o->size << "x" << o->size << " shadow LuT of " << occ.name
                << ")\n";
      return 0;
    };
  });
}

} // namespace umbra::cli
