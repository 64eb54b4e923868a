#pragma once
// The precomputation's innermost loops, each compiled for AVX2 and for the baseline CPU and
// chosen when the program loads (lobeValues: AVX-512 where there is one). Their own file, so
// that the compiler's vectorising options apply to them alone (atmosphere/CMakeLists.txt).
#include "precompute/Parametrisation.hpp"

namespace umbra::atmosphere::stages {

/// The sun's (mu_s, nu) at a view-ray sample for n texels of a row, as cells (sNuCorner):
/// mu_s = xr sx + yr muS0, nu = tx sx + ty muS0 (sx, muS0: the sun in the ray's frame).
void sNuTexels(const ScatterGeometry& geometry, double xr, double yr, double tx, double ty, const double* sx,
               const double* muS0, int n, int* x00, double* ws, double* wn);

/// out[0..width * channels) = the (r, mu) interpolation of a 4D table: the cell's four
/// rows of (mu_s, nu) texels blended with their weights, in one pass.
void blendRows(const FloatTable3D& T, const RMuCell& a, double* out);

/// The sun at a view-ray sample (radius r, frame xr, yr) for n texels of a row (the sun
/// sx, muS0 in the ray's frame): its visibility (sunVisibility) and the column coordinate
/// in [0, columns - 1] of its transmittance in a table of that many columns.
void sunTexels(const ShellRadii& shell, double alpha, double r, double xr, double yr, const double* sx,
               const double* muS0, int n, int columns, double* vis, double* fx);

/// p_j = A (1 + B c_j^2) / (1 + g^2 - 2 g c_j)^{3/2} for j < n: the density's inner loop.
/// lobeValuesPlain is the portable loop; lobeValues takes AVX-512 where the CPU has it.
void lobeValuesPlain(double A, double B, double g, const double* c, double* p, int n);
void lobeValues(double A, double B, double g, const double* c, double* p, int n);

/// Model::tablePosition of n cosines: the table entries index[j] and weights weight[j].
void tablePositions(const double* c, int n, int* index, double* weight);

/// A tabulated phase function per wavelength, interleaved (T[i * stride + l], uniform in the
/// cosine; stride a multiple of 4, the lanes past the wavelengths zero), at n directions and
/// their mirrors (table entry index[j] and weight[j] on the next one; the mirrors' at n + j),
/// each direction's value averaged with its mirror's and summed against the solid angles
/// wdo[j] (norm[l]) and against the incoming light L[j * stride + l] (sum[l]), for l < stride:
/// the density's inner loop for Lorenz-Mie phases.
void tableSums(const double* T, int stride, const int* index, const double* weight, int n, const double* wdo,
               const double* L, double* norm, double* sum);

/// sum_j a_j b_j.
double dot(const double* a, const double* b, int n);

}  // namespace umbra::atmosphere::stages
