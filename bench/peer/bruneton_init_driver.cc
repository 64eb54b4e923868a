// A driver of Bruneton's precomputed_atmospheric_scattering (the peer of
// bench/peer_side_by_side.sh, built by that script against a checkout of it, never part of
// umbra's build): one OpenGL 3.3 core context, then atmosphere::Model with the Earth of
// Bruneton (2017)'s paper at the peer's own table sizes (its constants.h: the same as
// umbra's defaults), and Model::Init with 4 scattering orders; prints the seconds it took.
//
//   bruneton_init_driver WAVELENGTHS   (3: the peer's RGB; 15: its precomputed luminance)
//
// The spectra are those of the paper's Earth: Rayleigh 5.802 / 13.558 / 33.1 per Mm at
// 680 / 550 / 440 nm (lambda^-4 between), Mie 3.996 per Mm scattering and 4.440
// extinction, g 0.8, scale heights 8 km and 1.2 km, the ozone layer as two linear pieces
// (peak at 25 km, 15 km wide on each side) with a band of 0.65 per Mm around 600 nm, ground
// albedo 0.1, the Sun down to 102 degrees. The work Model::Init does does not depend on
// these values.
#include "atmosphere/model.h"

#include <GL/freeglut.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

int main(int argc, char** argv) {
  const int precomputed = argc > 1 ? std::atoi(argv[1]) : 3;
  if (precomputed != 3 && precomputed != 15) {
    std::fprintf(stderr, "usage: %s 3|15\n", argv[0]);
    return 2;
  }
  glutInitContextVersion(3, 3);
  glutInitContextProfile(GLUT_CORE_PROFILE);
  glutInit(&argc, argv);
  glutInitDisplayMode(GLUT_RGBA);
  glutInitWindowSize(16, 16);
  glutCreateWindow("peer");
  if (!gladLoadGL()) {
    std::fprintf(stderr, "no OpenGL 3.3 core context\n");
    return 1;
  }

  using atmosphere::DensityProfileLayer;
  std::vector<double> nm, sun, rayleigh, mieScattering, mieExtinction, ozone, albedo;
  for (int l = 360; l <= 830; l += 10) {
    const double um = l * 1e-3;
    nm.push_back(l);
    sun.push_back(1.5);                                      // W m^-2 nm^-1, about the Sun's
    rayleigh.push_back(13.558e-3 * std::pow(0.55 / um, 4));  // per km
    mieScattering.push_back(3.996e-3);
    mieExtinction.push_back(4.440e-3);
    ozone.push_back(0.65e-3 * std::exp(-std::pow((l - 600.0) / 120.0, 2)));
    albedo.push_back(0.1);
  }
  const std::vector<DensityProfileLayer> rayleighDensity{DensityProfileLayer(0.0, 1.0, -1.0 / 8.0, 0.0, 0.0)};
  const std::vector<DensityProfileLayer> mieDensity{DensityProfileLayer(0.0, 1.0, -1.0 / 1.2, 0.0, 0.0)};
  const std::vector<DensityProfileLayer> ozoneDensity{DensityProfileLayer(25.0, 0.0, 0.0, 1.0 / 15.0, -2.0 / 3.0),
                                                      DensityProfileLayer(0.0, 0.0, 0.0, -1.0 / 15.0, 8.0 / 3.0)};
  const auto t0 = std::chrono::steady_clock::now();
  atmosphere::Model model(nm, sun, 0.004675, 6360.0, 6420.0, rayleighDensity, rayleigh, mieDensity, mieScattering,
                          mieExtinction, 0.8, ozoneDensity, ozone, albedo, 102.0 * M_PI / 180.0, 1000.0,
                          static_cast<unsigned>(precomputed), false, false);
  model.Init(4);
  glFinish();
  std::printf("peer Model::Init, %d wavelengths: %.2f s\n", precomputed,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  return 0;
}
