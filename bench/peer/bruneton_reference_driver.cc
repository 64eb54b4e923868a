// The spectral sky of Bruneton's CPU reference (atmosphere/reference/model.h of
// precomputed_atmospheric_scattering: double precision, its 47 wavelengths 360, 370, ...,
// 820 nm, 4 orders) at a
// fixed set of view and Sun geometries, per unit solar irradiance, as CSV into OUTPUT (the
// reference's progress bar takes stdout):
//
//   bruneton_reference_driver TEXTURE_CACHE_DIR/ OUTPUT.csv
//
//   altitude_m,view_zenith_deg,sun_zenith_deg,azimuth_deg,L_<nm>,... (47 columns, 1/sr)
//
// Built and run by bench/peer_reference_accuracy.sh against a checkout of the peer (with its
// external/dimensional_types and external/progress_bar); not part of umbra's build. The
// atmosphere is the peer's reference test atmosphere: its numbers (solar spectrum, ozone cross
// sections, Rayleigh and Mie coefficients) are public data, written out again here; umbra's
// side of the comparison reads the same numbers from bench/peer/bruneton-reference.json.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "atmosphere/reference/definitions.h"
#include "atmosphere/reference/model.h"

using namespace atmosphere::reference;

namespace {

// 360, 370, ..., 830 nm (48 values).
const double kSunWm2nm[48] = {
    1.11776, 1.14259, 1.01249, 1.14716, 1.72765, 1.73054, 1.6887, 1.61253, 1.91198, 2.03474, 2.02042, 2.02212,
    1.93377, 1.95809, 1.91686, 1.8298, 1.8685, 1.8931, 1.85149, 1.8504, 1.8341, 1.8345, 1.8147, 1.78158,
    1.7533, 1.6965, 1.68194, 1.64654, 1.6048, 1.52143, 1.55622, 1.5113, 1.474, 1.4482, 1.41018, 1.36775,
    1.34188, 1.31429, 1.28303, 1.26758, 1.2367, 1.2082, 1.18737, 1.14683, 1.12362, 1.1058, 1.07124, 1.04992};
const double kOzoneM2[48] = {
    1.18e-27, 2.182e-28, 2.818e-28, 6.636e-28, 1.527e-27, 2.763e-27, 5.52e-27, 8.451e-27, 1.582e-26,
    2.316e-26, 3.669e-26, 4.924e-26, 7.752e-26, 9.016e-26, 1.48e-25, 1.602e-25, 2.139e-25, 2.755e-25,
    3.091e-25, 3.5e-25, 4.266e-25, 4.672e-25, 4.398e-25, 4.701e-25, 5.019e-25, 4.305e-25, 3.74e-25,
    3.215e-25, 2.662e-25, 2.238e-25, 1.852e-25, 1.473e-25, 1.209e-25, 9.423e-26, 7.455e-26, 6.566e-26,
    5.105e-26, 4.15e-26, 4.228e-26, 3.237e-26, 2.451e-26, 2.801e-26, 2.534e-26, 1.624e-26, 1.465e-26,
    2.078e-26, 1.383e-26, 7.105e-27};

AtmosphereParameters referenceAtmosphere() {
  // Rayleigh 1.24062e-6 lambda^-4 (lambda in um) over 8 km; aerosols: Angstrom beta 5.328e-3
  // over 1.2 km, albedo 0.9, Cornette-Shanks g 0.8; ozone: 300 DU in a tent from 10 to 40 km
  // (number density 300 DU / 15 km at 25 km); ground albedo 0.1; Sun 0.2678 deg; mu_s >= cos 102 deg.
  const double ozoneMaxPerM3 = 300.0 * 2.687e20 / 15e3;
  std::vector<SpectralIrradiance> sun;
  std::vector<ScatteringCoefficient> rayleigh, mieScattering, mieExtinction, ozone;
  for (int i = 0; i < 48; ++i) {
    const double um = (360.0 + 10.0 * i) * 1e-3;
    sun.push_back(kSunWm2nm[i] * watt_per_square_meter_per_nm);
    rayleigh.push_back(1.24062e-6 / std::pow(um, 4.0) / m);
    mieScattering.push_back(0.9 * 5.328e-3 / 1200.0 / m);
    mieExtinction.push_back(5.328e-3 / 1200.0 / m);
    ozone.push_back(ozoneMaxPerM3 * kOzoneM2[i] / m);
  }
  AtmosphereParameters a;
  a.solar_irradiance = IrradianceSpectrum(360.0 * nm, 830.0 * nm, sun);
  a.sun_angular_radius = 0.2678 * deg;
  a.bottom_radius = 6360.0 * km;
  a.top_radius = 6420.0 * km;
  a.rayleigh_density.layers[1] = DensityProfileLayer(0.0 * m, 1.0, -1.0 / (8000.0 * m), 0.0 / m, 0.0);
  a.rayleigh_scattering = ScatteringSpectrum(360.0 * nm, 830.0 * nm, rayleigh);
  a.mie_density.layers[1] = DensityProfileLayer(0.0 * m, 1.0, -1.0 / (1200.0 * m), 0.0 / m, 0.0);
  a.mie_scattering = ScatteringSpectrum(360.0 * nm, 830.0 * nm, mieScattering);
  a.mie_extinction = ScatteringSpectrum(360.0 * nm, 830.0 * nm, mieExtinction);
  a.mie_phase_function_g = 0.8;
  a.absorption_density.layers[0] = DensityProfileLayer(25.0 * km, 0.0, 0.0 / km, 1.0 / (15.0 * km), -2.0 / 3.0);
  a.absorption_density.layers[1] = DensityProfileLayer(0.0 * km, 0.0, 0.0 / km, -1.0 / (15.0 * km), 8.0 / 3.0);
  a.absorption_extinction = ScatteringSpectrum(360.0 * nm, 830.0 * nm, ozone);
  a.ground_albedo = DimensionlessSpectrum(0.1);
  a.mu_s_min = cos(102.0 * deg);  // dimensional::cos of an Angle
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s TEXTURE_CACHE_DIR/ OUTPUT.csv\n", argv[0]);
    return 2;
  }
  std::FILE* out = std::fopen(argv[2], "w");
  if (!out) {
    std::fprintf(stderr, "%s: cannot write\n", argv[2]);
    return 1;
  }
  const AtmosphereParameters atmosphere = referenceAtmosphere();
  Model model(atmosphere, argv[1]);  // reads the textures there, else computes and saves them
  model.Init(4);
  std::fprintf(out, "altitude_m,view_zenith_deg,sun_zenith_deg,azimuth_deg");
  for (int l = 0; l < 47; ++l) std::fprintf(out, ",L_%d", 360 + 10 * l);  // the peer's samples: 360 + 10 l nm
  std::fprintf(out, "\n");
  const double kDeg = 3.14159265358979323846 / 180.0;
  for (double altitude : {1.0, 1000.0, 10000.0, 30000.0})
    for (double viewZenith : {0.0, 30.0, 60.0, 80.0, 88.0, 92.0, 120.0})
      for (double sunZenith : {0.0, 30.0, 60.0, 80.0, 89.0, 95.0})
        for (double azimuth : {0.0, 45.0, 90.0, 180.0}) {
          const Position camera(0.0 * m, 0.0 * m, atmosphere.bottom_radius + altitude * m);
          const double vz = viewZenith * kDeg, sz = sunZenith * kDeg, az = azimuth * kDeg;
          const Direction view(std::sin(vz) * std::cos(az), std::sin(vz) * std::sin(az), std::cos(vz));
          const Direction sun(std::sin(sz), 0.0, std::cos(sz));
          DimensionlessSpectrum transmittance;
          const RadianceSpectrum L = model.GetSkyRadiance(camera, view, 0.0 * m, sun, &transmittance);
          std::fprintf(out, "%.17g,%.17g,%.17g,%.17g", altitude, viewZenith, sunZenith, azimuth);
          for (int l = 0; l < 47; ++l)
            std::fprintf(out, ",%.17g", (L[l] / atmosphere.solar_irradiance[l]).to(1.0 / sr));
          std::fprintf(out, "\n");
        }
  return std::fclose(out) == 0 ? 0 : 1;
}
