#pragma once
// The precomputation's innermost loops, each compiled for AVX-512, AVX2 and the baseline CPU
// and chosen when the program loads (lobeValues and cosineModes: AVX-512 written out where
// there is one). Their own file, so that the compiler's vectorising options apply to them
// alone (atmosphere/CMakeLists.txt).
#include "precompute/Parametrisation.hpp"

#include <cstddef>
#include <vector>

namespace umbra::atmosphere::stages {

/// The sun's (mu_s, nu) at a view-ray sample for n texels of a row, as cells (sNuCorner):
/// mu_s = xr sx + yr muS0, nu = tx sx + ty muS0 (sx, muS0: the sun in the ray's frame).
void sNuTexels(const ScatterGeometry& geometry, double xr, double yr, double tx, double ty, const double* sx,
               const double* muS0, int n, int* x00, double* ws, double* wn);

/// out[0..width * channels) = the (r, mu) interpolation of a 4D table: the cell's four
/// rows of (mu_s, nu) texels blended with their weights, in one pass.
void blendRows(const FloatTable3D& T, const RMuCell& a, double* out);

/// acc[x * nl + l] += w T[l] blend(x00[x] cell, bilinear in ws[x], wn[x]) for x < n, l < nl:
/// a view-ray sample's share of the multiple scattering at n texels of a row (blend: a row
/// of (mu_s, nu) texels from blendRows, nl channels, the next nu up muS texels on).
void gatherTexels(const double* blend, int nl, int muS, const int* x00, const double* ws, const double* wn, int n,
                  double w, const double* T, double* acc);

/// The sun at a view-ray sample (radius r, frame xr, yr) for n texels of a row (the sun
/// sx, muS0 in the ray's frame): its visibility (sunVisibility) and the column coordinate
/// in [0, columns - 1] of its transmittance in a table of that many columns.
void sunTexels(const ShellRadii& shell, double alpha, double r, double xr, double yr, const double* sx,
               const double* muS0, int n, int columns, double* vis, double* fx);

/// p_j = A (1 + B c_j^2) / (1 + g^2 - 2 g c_j)^{3/2} for j < n: a closed-form lobe.
/// lobeValuesPlain is the portable loop; lobeValues takes AVX-512 where the CPU has it.
void lobeValuesPlain(double A, double B, double g, const double* c, double* p, int n);
void lobeValues(double A, double B, double g, const double* c, double* p, int n);

/// out[m] = sum_q f[q] cosines[q * modes + m] for m < modes, q < n: a function's cosine
/// modes from its samples (the weights in the cosines). cosineModesPlain is the portable
/// loop; cosineModes takes AVX-512 where the CPU has it and modes is a multiple of 8.
void cosineModesPlain(const double* f, const double* cosines, int n, int modes, double* out);
void cosineModes(const double* f, const double* cosines, int n, int modes, double* out);

/// The density's integrals in azimuth by cosine modes (ScatteringDensity.cpp). The light of
/// a ring of directions, known at the nPh azimuths phi_i = (i + 1/2) pi / nPh and (the same)
/// at their mirrors -phi_i, is the cosine series L(phi) = sum_{m < nPh} alpha_m cos(m phi)
/// through those 2 nPh points; a lobe p(a + b cos(phi - phi_v)) seen from azimuth phi_v has
/// the modes gamma_m = int_0^2pi p(a + b cos D) cos(m D) dD (midpoint rule, Q = 8 nPh points
/// on [0, pi]); then int_0^2pi L(phi) p(a + b cos(phi - phi_v)) dphi = sum_m alpha_m gamma_m
/// cos(m phi_v).
struct AzimuthModes {
  explicit AzimuthModes(int nPh);
  int nPh, Q;
  std::vector<double> qCos;      ///< cos D_q, D_q = (q + 1/2) pi / Q
  std::vector<double> qModes;    ///< [q * nPh + m]: 2 pi / Q cos(m D_q), for cosineModes
  std::vector<double> phiModes;  ///< [i * nPh + m]: (2 - [m = 0]) / nPh cos(m phi_i), for cosineModes
};

/// out[u * modes + m] = sum_lt alpha[(rows[u] * rings + lt) * modes + m] gamma[u * gammaStride +
/// lt * modes + m] for u < count: the light's modes (of wavelength rows[u]) times a lobe's
/// (gammaStride 0: one lobe for all), summed over the rings of directions.
void modeProducts(const double* alpha, const int* rows, int count, const double* gamma, std::size_t gammaStride,
                  int rings, int modes, double* out);

/// Model::tablePosition of n cosines: the table entries index[j] and weights weight[j].
void tablePositions(const double* c, int n, int* index, double* weight);

}  // namespace umbra::atmosphere::stages
