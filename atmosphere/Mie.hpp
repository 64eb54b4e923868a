#pragma once
// Lorenz–Mie theory for homogeneous spheres and its average over a log-normal size
// distribution: the exact aerosol optics that the atmosphere paper (section 4.3, Eqs.
// 17–20) replaces by van de Hulst's and Götz's approximations. It gives the reference the
// approximations are measured against, and the bulk coefficients and phase-function table
// of an aerosol preset.
//
// Conventions (Bohren & Huffman 1983, "Absorption and Scattering of Light by Small
// Particles", chapter 4): time dependence exp(-i w t), relative refractive index
// m = n + i k with k >= 0, size parameter x = 2 pi r / lambda (lambda in the medium).
// Wiscombe's MIEV0 writes m = n - i k; its S1, S2, a_n, b_n are the complex conjugates of
// the ones here, its efficiencies are the same.
//
//   Q_ext = (2/x^2) sum (2n+1) Re(a_n + b_n)                       (B&H Eq. 4.62)
//   Q_sca = (2/x^2) sum (2n+1) (|a_n|^2 + |b_n|^2)                  (B&H Eq. 4.61)
//   g Q_sca = (4/x^2) sum [ n(n+2)/(n+1) Re(a_n a*_{n+1} + b_n b*_{n+1})
//                           + (2n+1)/(n(n+1)) Re(a_n b*_n) ]        (B&H p. 120)
//   Q_back = (1/x^2) |sum (2n+1) (-1)^n (a_n - b_n)|^2             (B&H p. 122)
//   S1 = sum (2n+1)/(n(n+1)) (a_n pi_n + b_n tau_n),  S2 = the same with a, b swapped
//                                                                     (B&H Eq. 4.74)
//
// How a_n, b_n are evaluated (Mie.cpp has the derivation): with the Riccati–Bessel
// functions psi_n(z) = z j_n(z), xi_n(x) = x h_n^(1)(x) and D_n = psi_n'/psi_n,
//   a_n = (psi_n/xi_n) (D_n(mx)/m - D_n(x)) / (D_n(mx)/m - xi_n'/xi_n)
//   b_n = (psi_n/xi_n) (m D_n(mx) - D_n(x)) / (m D_n(mx) - xi_n'/xi_n)
// D_n by downward recurrence from n = max(n_max, |mx|) + 15 (Wiscombe 1980), the ratio
// psi_n/xi_n and xi_n'/xi_n by upward recurrences of ratios. Only ratios appear, so nothing
// underflows or cancels as x -> 0 (the Rayleigh limit comes out to double precision at
// x = 1e-6) and nothing overflows for x up to ~1e4 and beyond.
// Number of terms: n_max = x + 4 x^(1/3) + 2 (Wiscombe 1980, Appl. Opt. 19, 1505).

#include <complex>
#include <vector>

namespace umbra::atmosphere {

struct MieEfficiencies {
  double qExt = 0, qSca = 0, qBack = 0, g = 0;  ///< efficiencies (cross-section / pi r^2), asymmetry parameter
};

/// Wiscombe's number of terms for size parameter x: floor(x + 4 x^(1/3) + 2), at least 1.
int mieTermCount(double sizeParameter);

/// The Mie coefficients a_n, b_n for n = 1..n_max (a[0] is a_1). Throws
/// std::invalid_argument for x <= 0, non-finite input or Im(m) < 0.
void mieCoefficients(double sizeParameter, std::complex<double> m, std::vector<std::complex<double>>& a,
                     std::vector<std::complex<double>>& b);

/// One homogeneous sphere: size parameter x = 2 pi r / lambda, relative complex refractive
/// index m (n + i k, k >= 0). Valid and NaN-free for 1e-6 <= x <= ~2e4. For k = 0 exactly,
/// Q_ext is set to Q_sca (they are equal; the sum over Re(a_n + b_n) would lose relative
/// accuracy below x ~ 1e-4 because Re(a_1) ~ x^6 while |a_1| ~ x^3).
MieEfficiencies mieSphere(double sizeParameter, std::complex<double> m);

/// The same, plus the amplitude functions S1, S2 at the given cos(theta) values
/// (theta = scattering angle; S1 perpendicular, S2 parallel to the scattering plane).
/// The phase function of the sphere, normalised to 1 over the sphere, is
///   p(theta) = (|S1|^2 + |S2|^2) / (2 pi x^2 Q_sca)   [1/sr].
MieEfficiencies mieSphere(double sizeParameter, std::complex<double> m, const std::vector<double>& cosTheta,
                          std::vector<std::complex<double>>& s1, std::vector<std::complex<double>>& s2);

/// Log-normal number distribution of radii:
///   dN/d ln r = N / (sqrt(2 pi) ln sigma_g) exp(-(ln r - ln r_m)^2 / (2 ln^2 sigma_g)).
struct LogNormalSizes {
  double medianRadiusM;       ///< r_m [m]
  double geometricStdDev;     ///< sigma_g >= 1 (1: all particles have radius r_m)
  double numberDensityPerM3;  ///< N [1/m^3]
  /// The distribution cut to [minRadiusM, maxRadiusM] (0: not cut), N that of the whole
  /// distribution: OPAC's components are tabulated so (Hess et al. 1998, Table 1).
  double minRadiusM = 0.0, maxRadiusM = 0.0;
};

/// The log-normal distribution with a given effective radius and effective variance
/// (Hansen & Travis 1974, Space Sci. Rev. 16, 527, Eqs. 2.53-2.54 for the log-normal:
/// r_eff = <r^3>/<r^2> = r_m exp(5/2 ln^2 sigma_g), v_eff = exp(ln^2 sigma_g) - 1), the
/// parameters planetary retrievals publish. v_eff = 0: one radius. Throws
/// std::invalid_argument for r_eff <= 0, v_eff < 0 or a negative density.
LogNormalSizes logNormalFromEffective(double effectiveRadiusM, double effectiveVariance, double numberDensityPerM3);

struct MieAerosol {
  double scatteringPerM = 0, extinctionPerM = 0, absorptionPerM = 0;  ///< bulk coefficients at the given number density [1/m]
  double asymmetry = 0;          ///< scattering-weighted mean cosine
  std::vector<double> cosTheta;  ///< phase-function table abscissae (ascending, -1..1), uniform in theta
  std::vector<double> phase;     ///< normalised: integral over the sphere = 1 [1/sr]
  // How the size quadrature went:
  int sizeNodes = 0;             ///< radius nodes used (1 for sigma_g = 1)
  double minSizeParameter = 0, maxSizeParameter = 0;  ///< size-parameter range of the window
  bool converged = false;        ///< the last halving met the tolerances (see mieLogNormal)
  double quadratureChange = 0;   ///< largest relative change any output saw in the last halving
};

/// Bulk optics of a log-normal population of spheres at one wavelength (in the medium).
///
/// Quadrature: the trapezoidal rule in u = ln(r/r_m)/ln(sigma_g), the standard-normal
/// variable, which converges like a spectral method for a Gaussian-weighted smooth
/// integrand.
/// - Window: centred on the cross-section-weighted median (u = 2 ln sigma_g) and extended
///   each way, on a coarse 0.25 grid, until two nodes in a row add < 1e-10 of the total to
///   both C_ext and C_sca; at least u in [-4, 4] (± 4 sigma in ln r); never beyond x = 2e4.
/// - Step: starts at min(0.25, pi / (omega ln(sigma_g) x_c)) (Nyquist for the interference
///   oscillations cos(omega x) of Q(x) and |S|^2 at the window's centre x_c,
///   omega = 2 + 4|m|) and is halved, reusing all earlier nodes, until one halving changes
///   C_ext, C_sca (and g C_sca, against C_sca) by < 1e-8 and every phase sample by < 1e-6,
///   relative. Then extraLevels more halvings are done (convergence checks: 1 doubles the
///   nodes). At most 16385 nodes before the extra levels; `converged` says whether the
///   tolerances were met, `quadratureChange` what the last halving changed.
/// - Typical cost (one core): r_m = 0.1 um, sigma_g = 1.6, lambda = 550 nm,
///   m = 1.5 + 0.01i: 1633 nodes, x from 0.12 to 48, 0.02 s; r_m = 0.3 um, sigma_g = 1.5,
///   m = 1.53 + 0.006i: 4097 nodes, 0.06 s. The cost grows like x_max^2: fog droplets
///   (r_m = 5 um, sigma_g = 1.6 at 400 nm, x up to 3300) take ~2 s and 15000 nodes.
/// - Limits: sharp Mie resonances of (nearly) non-absorbing spheres are narrower than any
///   step; they leave ~1e-7..1e-6 (bulk) and up to ~1e-4 (phase samples) of noise once the
///   distribution reaches x ~ 100 (e.g. m = 1.5, r_m = 0.1 um, sigma_g = 2 at 550 nm), and
///   the quadrature then stops at the node cap, unconverged. So do distributions whose
///   oscillations at the window's centre are faster than the cap resolves (x_c >~ 1000).
///   The forward-scattering samples of the phase table grow like r^6 and are truncated with
///   the window like everything else, i.e. at the 1e-10 level of C_sca, not of their own.
///
/// bulkTolerance and phaseTolerance (in (0, 1)) replace the 1e-8 and 1e-6 above: a table
/// for rendering needs far less (atmosphere presets use 1e-4 and 1e-2, ~10 times fewer
/// nodes for Martian dust).
/// phaseSamples (>= 2) table entries at theta_j = pi (1 - j/(phaseSamples - 1)).
/// sigma_g = 1 gives the single sphere of radius r_m. Throws std::invalid_argument for
/// non-positive wavelength or radius, sigma_g < 1, negative density, Im(m) < 0,
/// phaseSamples < 2, extraLevels outside [0, 8].
MieAerosol mieLogNormal(double wavelengthM, std::complex<double> m, const LogNormalSizes& sizes,
                        int phaseSamples = 181, int extraLevels = 0, double bulkTolerance = 1e-8,
                        double phaseTolerance = 1e-6);

} // namespace umbra::atmosphere
