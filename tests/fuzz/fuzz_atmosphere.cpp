// Atmosphere files (atmosphere/Atmosphere.cpp): any text gives a model or an AtmosphereError.
#include "Atmosphere.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

// Lorenz-Mie optics (a "mie" model, or the mars preset's dust) are computed while the file
// is read: bounded (atmosphere/Mie.hpp) but seconds per wavelength, which would starve the
// fuzzer; such inputs are left to the extremes sweep (tests/cli/test_extremes.cpp).
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  if (text.find("mie") != std::string::npos || text.find("mars") != std::string::npos) return 0;
  try {
    umbra::atmosphere::parseAtmosphere(text, "fuzz.json",
                                       {440.0, 550.0, 680.0}, "/nonexistent");
  } catch (const umbra::atmosphere::AtmosphereError&) {
  }
  return 0;
}
