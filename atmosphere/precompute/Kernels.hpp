#pragma once
// The precomputation's innermost loops, each compiled for AVX2 and for the baseline CPU and
// chosen when the program loads (lobePairSums: AVX-512 where there is one). Their own file, so
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

/// One lobe, p(c) = A (1 + B c^2) / (1 + g^2 - 2 g c)^{3/2}, at one view v over the density's n directions w_j and their
/// mirrors (w_y negated): pair_j = (p(w_j . v) + p(w'_j . v)) / 2, out[0] = sum_j pair_j wdo[j]
/// and out[1 + u] = sum_j pair_j L[rows[u] * n + j] for u < users; pair (n values) is
/// scratch. The density's inner loop for closed-form lobes, in one pass over the directions.
/// lobePairSumsPlain is the portable loop; lobePairSums takes AVX-512 where the CPU has it.
void lobePairSumsPlain(double A, double B, double g, const double* wx, const double* wy, const double* wz, double vx,
                       double vy, double vz, int n, const double* wdo, const double* L, const int* rows, int users,
                       double* pair, double* out);
void lobePairSums(double A, double B, double g, const double* wx, const double* wy, const double* wz, double vx,
                  double vy, double vz, int n, const double* wdo, const double* L, const int* rows, int users,
                  double* pair, double* out);

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

}  // namespace umbra::atmosphere::stages
