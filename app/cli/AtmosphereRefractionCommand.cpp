// umbra atmosphere refraction --preset NAME --altitude M --zenith-deg A:B:STEP --csv FILE
#include "Commands.hpp"
#include "OutputFile.hpp"
#include "AtmosphereCommon.hpp"
#include "ShadowCommon.hpp"  // lengthOption

#include "Atmosphere.hpp"
#include "SightLines.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <regex>

namespace umbra::cli {
namespace {

struct Range {
  double from, to, step;
};

Range parseRange(const std::string& option, const std::string& text) {
  const std::string number = R"(([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?))";
  std::smatch m;
  if (!std::regex_match(text, m, std::regex(number + ":" + number + ":" + number)))
    throw CommandError(option + ": expected FROM:TO:STEP in degrees (e.g. 0:90:0.5), got '" + text + "'");
  const Range r{std::stod(m[1]), std::stod(m[2]), std::stod(m[3])};
  if (!(r.step > 0.0) || r.to < r.from || r.from < 0.0 || r.to > 180.0 || (r.to - r.from) / r.step > 1e6)
    throw CommandError(option + ": expected 0 <= FROM <= TO <= 180 and 0 < STEP (at most 1e6 rows), got '" + text + "'");
  return r;
}

} // namespace

void addAtmosphereRefractionCommand(CLI::App& atmosphereCmd, Action& action) {
  CLI::App* refraction = atmosphereCmd.add_subcommand(
      "refraction", "Lines of sight from an observer to space: total deviation, lowest altitude and transmittance "
                    "(R, G, B = 680, 550, 440 nm), over a range of geometric view-zenith angles. Each line is traced "
                    "on its own (RK4): the reference that the refraction table of the renders is checked against");
  struct Options {
    std::string preset, config, altitude = "0", zenith = "0:90:1", csv, step = "10km";
  };
  auto o = std::make_shared<Options>();
  addAtmosphereOptions(refraction, o->preset, o->config);
  refraction->add_option("--altitude", o->altitude, "Observer altitude above the ground (units m, km)")->capture_default_str();
  refraction->add_option("--zenith-deg", o->zenith, "Geometric view-zenith angles FROM:TO:STEP in degrees")->capture_default_str();
  refraction->add_option("--step", o->step, "RK4 step along the ray (units m, km)")->capture_default_str();
  refraction->add_option("--csv", o->csv,
                         "CSV file to write (zenith_deg,deviation_deg,contact_altitude_m,transmittance_r,transmittance_g,"
                         "transmittance_b)")->required();

  refraction->callback([&action, o] {
    action = [o] {
      output::checkWritable(o->csv, {".csv"});
      const Range zenith = parseRange("--zenith-deg", o->zenith);
      const double altitudeM = lengthOption("--altitude", o->altitude);
      const double stepM = lengthOption("--step", o->step);
      if (!(stepM >= 1.0 && stepM <= 1e6)) throw CommandError("--step: expected 1 m to 1000 km, got " + o->step);
      const atmosphere::AtmosphereModelPtr model = atmosphereOption(o->preset, o->config);
      const atmosphere::Atmosphere& atm = model->rgb();
      if (!(altitudeM >= 0.0)) throw CommandError("--altitude: expected a length >= 0, got " + o->altitude);

      output::OutputFile out(o->csv);
      {
        std::ofstream f(out.tempPath());
        f << "zenith_deg,deviation_deg,contact_altitude_m,transmittance_r,transmittance_g,transmittance_b\n";
        const double pi = 3.14159265358979323846;
        const long rows = std::lround(std::floor((zenith.to - zenith.from) / zenith.step + 1e-9)) + 1;
        char line[256];
        for (long k = 0; k < rows; ++k) {
          const double zenithDeg = zenith.from + k * zenith.step;
          const atmosphere::SightLine s = atmosphere::traceSightLine(atm, altitudeM, zenithDeg * pi / 180.0, 550.0, stepM);
          std::snprintf(line, sizeof line, "%.6f,%.9g,%.6f,%.9g,%.9g,%.9g\n", zenithDeg, s.deviationRad * 180.0 / pi,
                        s.contactAltitudeM, s.transmittance[0], s.transmittance[1], s.transmittance[2]);
          f << line;
        }
        if (!f.flush()) throw CommandError(o->csv + ": cannot write");
      }
      out.commit();
      std::cout << "wrote " << o->csv << " (" << atm.name << ", observer at " << altitudeM << " m)\n";
      return 0;
    };
  });
}

} // namespace umbra::cli
