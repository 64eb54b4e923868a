// umbra inspect FILE.exr [--json]
#include "Commands.hpp"

#include "umbra/tables/Exr.h"
#include "umbra/tables/Summary.h"

#include <iostream>
#include <memory>

namespace umbra::cli {

void addInspectCommand(CLI::App& app, Action& action) {
  CLI::App* inspect = app.add_subcommand(
      "inspect", "Describe a table file: size, channels, header parameters, per-channel min/max/mean, non-finite count");
  struct Options {
    std::string path;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  inspect->add_option("FILE", o->path, "EXR file written by umbra")->required();
  inspect->add_flag("--json", o->json, "Print JSON instead of text");
  inspect->callback([&action, o] {
    action = [o] {
      const tables::TableSummary summary = tables::summarize(tables::readExr(o->path), o->path);
      if (o->json)
        std::cout << tables::toJson(summary).dump(2) << "\n";
      else
        std::cout << tables::formatText(summary);
      return 0;
    };
  });
}

} // namespace umbra::cli
