#include "Mie.hpp"
#include "ParallelErrors.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace umbra::atmosphere {
namespace {

using cplx = std::complex<double>;
constexpr double kPi = 3.14159265358979323846;

/// Largest size parameter the log-normal quadrature evaluates.
constexpr double kMaxSizeParameter = 2e4;

void checkSphere(double x, cplx m) {
  if (!(x > 0.0) || !std::isfinite(x))
    throw std::invalid_argument("Mie: size parameter must be positive and finite, got " + std::to_string(x));
  if (!std::isfinite(m.real()) || !std::isfinite(m.imag()))
    throw std::invalid_argument("Mie: refractive index must be finite");
  if (m.imag() < 0.0)
    throw std::invalid_argument("Mie: Im(m) must be >= 0 (m = n + ik, Bohren & Huffman's convention)");
  if (m == cplx(0.0, 0.0)) throw std::invalid_argument("Mie: refractive index must not be 0");
}

/// 1/z, with an exact zero (a node of psi_n hit exactly) moved off by a tiny amount: the
/// ratios that follow are then huge but finite, and cancel in a_n, b_n as they should.
template <class T>
T safeInverse(T z) {
  if (z == T(0)) z = T(1e-300);
  return T(1) / z;
}

/// psi_{n-1}(z)/psi_n(z) = J_{n-1/2}(z)/J_{n+1/2}(z) as the continued fraction that the
/// three-term recurrence gives, f = b_0 - 1/(b_1 - 1/(b_2 - ...)) with b_j = (2n+1+2j)/z,
/// evaluated by the modified Lentz method (Lentz 1976, Appl. Opt. 15, 668; Thompson &
/// Barnett 1986). It converges in a few tens of terms for n > |z|, where it is used.
///
/// Why not start from D = 0 as B&H's BHMIE does: for real (or nearly real) z the downward
/// recurrence is only neutrally stable in the oscillatory region n < |z|, so the error of
/// the starting value is not damped. With D = 0 at n = |mx| + 15, m = 1.5 and x = 1000
/// give Q_sca = 2.01308 instead of Wiscombe's 2.013945.
template <class T>
T psiRatio(int n, T z) {
  constexpr double kTiny = 1e-300, kEps = 1e-15;
  constexpr int kMaxTerms = 1000000;
  const T invZ = T(1) / z;
  auto b = [&](int j) { return double(2 * n + 1 + 2 * j) * invZ; };
  T f = b(0);
  if (f == T(0)) f = T(kTiny);
  T c = f, d = T(0);
  for (int j = 1; j < kMaxTerms; ++j) {
    d = b(j) - d;
    if (d == T(0)) d = T(kTiny);
    c = b(j) - T(1) / c;
    if (c == T(0)) c = T(kTiny);
    d = T(1) / d;
    const T delta = c * d;
    f *= delta;
    if (std::abs(delta - T(1)) < kEps) break;
  }
  return f;
}

// Derivation of the ratio form used below. With A_n = D_n(mx)/m + n/x (B&H Eq. 4.88),
//   a_n = (A_n psi_n - psi_{n-1}) / (A_n xi_n - xi_{n-1})
//       = (psi_n/xi_n) (A_n - psi_{n-1}/psi_n) / (A_n - xi_{n-1}/xi_n),
// and psi_{n-1}/psi_n = D_n(x) + n/x, xi_{n-1}/xi_n = D3_n + n/x with D3_n = xi_n'/xi_n
// (from f_n' = f_{n-1} - n f_n / z, true of every Riccati–Bessel function). So
//   a_n = R_n (D_n(mx)/m - D_n(x)) / (D_n(mx)/m - D3_n),   R_n = psi_n(x)/xi_n(x),
// and likewise b_n with m D_n(mx). The three ratios come from recurrences of ratios:
//   P_n = psi_{n-1}/psi_n = D_n(x) + n/x      (D_n downward, see below)
//   E_n = xi_{n-1}/xi_n = 1 / ((2n-1)/x - E_{n-1}),  E_0 = xi_{-1}/xi_0 = i   (upward:
//         xi is the dominant solution of f_{n+1} = (2n+1)/x f_n - f_{n-1}, so stable)
//   R_n = R_{n-1} E_n / P_n,  R_0 = sin x / (-i e^{ix}) = sin^2 x + i sin x cos x.
// For small x the numerator of b_n, m D_n(mx) - D_n(x), is the difference of two numbers
// close to (n+1)/x; it is formed instead as Q_n(x) - m Q_n(mx) with
// Q_n(z) = psi_{n+1}/psi_n = 1/(D_{n+1}(z) + (n+1)/z), since D_n(z) = (n+1)/z - Q_n(z).
// Nothing here forms psi_n or xi_n themselves, so nothing under- or overflows.

void computeCoefficients(double x, cplx m, std::vector<cplx>& a, std::vector<cplx>& b) {
  const int nmax = mieTermCount(x);
  const cplx mx = m * x;
  // Wiscombe's (1980) starting index for the downward recurrence of D_n: beyond both
  // n_max and |mx|, plus 15.
  const int nstart = std::max(nmax, static_cast<int>(std::ceil(std::abs(mx)))) + 15;

  // D_{n-1}(z) = n/z - 1/(D_n(z) + n/z) (B&H Eq. 4.89), from the exact D_nstart.
  const double invX = 1.0 / x;
  const cplx invMx = 1.0 / mx;
  std::vector<double> dx(nstart + 1);
  std::vector<cplx> dmx(nstart + 1);
  dx[nstart] = psiRatio(nstart, x) - nstart * invX;
  dmx[nstart] = psiRatio(nstart, mx) - double(nstart) * invMx;
  for (int n = nstart; n >= 1; --n) {
    dx[n - 1] = n * invX - safeInverse(dx[n] + n * invX);
    dmx[n - 1] = double(n) * invMx - safeInverse(dmx[n] + double(n) * invMx);
  }

  a.assign(nmax, cplx(0.0));
  b.assign(nmax, cplx(0.0));
  const double sx = std::sin(x), cx = std::cos(x);
  cplx ratio(sx * sx, sx * cx);  // R_0 = psi_0/xi_0
  cplx e(0.0, 1.0);              // E_0
  for (int n = 1; n <= nmax; ++n) {
    e = safeInverse((2 * n - 1) * invX - e);
    const double p = dx[n] + n * invX;
    ratio *= e * safeInverse(p);
    const cplx d3 = e - n * invX;
    const double qx = safeInverse(dx[n + 1] + (n + 1) * invX);
    const cplx qmx = safeInverse(dmx[n + 1] + double(n + 1) * invMx);
    const cplx dmOverM = dmx[n] / m;
    const cplx mDm = m * dmx[n];
    a[n - 1] = ratio * (dmOverM - dx[n]) / (dmOverM - d3);
    b[n - 1] = ratio * (qx - m * qmx) / (mDm - d3);
  }
}

MieEfficiencies efficienciesFrom(double x, cplx m, const std::vector<cplx>& a, const std::vector<cplx>& b) {
  const int nmax = static_cast<int>(a.size());
  double ext = 0.0, sca = 0.0, asym = 0.0;
  cplx back(0.0);
  for (int n = 1; n <= nmax; ++n) {
    const cplx an = a[n - 1], bn = b[n - 1];
    const double w = 2.0 * n + 1.0;
    ext += w * (an.real() + bn.real());
    sca += w * (std::norm(an) + std::norm(bn));
    back += ((n % 2) ? -w : w) * (an - bn);
    asym += w / (double(n) * (n + 1.0)) * (an * std::conj(bn)).real();
    if (n < nmax) {
      const cplx an1 = a[n], bn1 = b[n];
      asym += double(n) * (n + 2.0) / (n + 1.0) * (an * std::conj(an1) + bn * std::conj(bn1)).real();
    }
  }
  const double invX2 = 1.0 / (x * x);
  MieEfficiencies q;
  q.qSca = 2.0 * invX2 * sca;
  q.qExt = (m.imag() == 0.0) ? q.qSca : 2.0 * invX2 * ext;
  q.qBack = invX2 * std::norm(back);
  q.g = (sca > 0.0) ? 2.0 * asym / sca : 0.0;  // (4/x^2) asym / Q_sca
  return q;
}

/// S1, S2 at every cos(theta) (B&H Eqs. 4.46–4.47 for pi_n, tau_n; Eq. 4.74):
///   pi_{n+1} = ((2n+1)/n) mu pi_n - ((n+1)/n) pi_{n-1},  tau_n = n mu pi_n - (n+1) pi_{n-1}.
/// The order loop is outside and the angle loop inside, so that the inner loop is plain
/// real arithmetic on arrays that the compiler vectorises.
void amplitudes(const std::vector<double>& mu, const std::vector<cplx>& a, const std::vector<cplx>& b,
                std::vector<cplx>& s1, std::vector<cplx>& s2) {
  const std::size_t J = mu.size();
  const int nmax = static_cast<int>(a.size());
  std::vector<double> pi(J, 1.0), piPrev(J, 0.0), s1r(J, 0.0), s1i(J, 0.0), s2r(J, 0.0), s2i(J, 0.0);
  for (int n = 1; n <= nmax; ++n) {
    const double f = (2.0 * n + 1.0) / (double(n) * (n + 1.0));
    const double ar = f * a[n - 1].real(), ai = f * a[n - 1].imag();
    const double br = f * b[n - 1].real(), bi = f * b[n - 1].imag();
    const double dn = n, dn1 = n + 1.0, c1 = (2.0 * n + 1.0) / n, c2 = (n + 1.0) / n;
    for (std::size_t j = 0; j < J; ++j) {
      const double p = pi[j], q = piPrev[j], x = mu[j];
      const double t = dn * x * p - dn1 * q;
      s1r[j] += ar * p + br * t;
      s1i[j] += ai * p + bi * t;
      s2r[j] += ar * t + br * p;
      s2i[j] += ai * t + bi * p;
      piPrev[j] = p;
      pi[j] = c1 * x * p - c2 * q;
    }
  }
  s1.resize(J);
  s2.resize(J);
  for (std::size_t j = 0; j < J; ++j) {
    s1[j] = cplx(s1r[j], s1i[j]);
    s2[j] = cplx(s2r[j], s2i[j]);
  }
}

} // namespace

int mieTermCount(double x) {
  if (!(x > 0.0)) return 1;
  return std::max(1, static_cast<int>(x + 4.0 * std::cbrt(x) + 2.0));
}

void mieCoefficients(double x, std::complex<double> m, std::vector<std::complex<double>>& a,
                     std::vector<std::complex<double>>& b) {
  checkSphere(x, m);
  computeCoefficients(x, m, a, b);
}

MieEfficiencies mieSphere(double x, std::complex<double> m) {
  checkSphere(x, m);
  std::vector<cplx> a, b;
  computeCoefficients(x, m, a, b);
  return efficienciesFrom(x, m, a, b);
}

MieEfficiencies mieSphere(double x, std::complex<double> m, const std::vector<double>& cosTheta,
                          std::vector<std::complex<double>>& s1, std::vector<std::complex<double>>& s2) {
  checkSphere(x, m);
  std::vector<cplx> a, b;
  computeCoefficients(x, m, a, b);
  amplitudes(cosTheta, a, b, s1, s2);
  return efficienciesFrom(x, m, a, b);
}

LogNormalSizes logNormalFromEffective(double effectiveRadiusM, double effectiveVariance, double numberDensityPerM3) {
  if (!(effectiveRadiusM > 0.0) || !std::isfinite(effectiveRadiusM))
    throw std::invalid_argument("effective radius must be positive");
  if (!(effectiveVariance >= 0.0) || !std::isfinite(effectiveVariance))
    throw std::invalid_argument("effective variance must be >= 0");
  if (!(numberDensityPerM3 >= 0.0) || !std::isfinite(numberDensityPerM3))
    throw std::invalid_argument("number density must be >= 0");
  const double s2 = std::log1p(effectiveVariance);  // ln^2 sigma_g
  return {effectiveRadiusM * std::exp(-2.5 * s2), std::exp(std::sqrt(s2)), numberDensityPerM3};
}

namespace {

void checkLogNormalArguments(double wavelengthM, const LogNormalSizes& sizes, int phaseSamples, int extraLevels,
                             double bulkTolerance, double phaseTolerance) {
  if (!(wavelengthM > 0.0) || !std::isfinite(wavelengthM))
    throw std::invalid_argument("mieLogNormal: wavelength must be positive");
  if (!(sizes.medianRadiusM > 0.0) || !std::isfinite(sizes.medianRadiusM))
    throw std::invalid_argument("mieLogNormal: median radius must be positive");
  if (!(sizes.geometricStdDev >= 1.0) || !std::isfinite(sizes.geometricStdDev))
    throw std::invalid_argument("mieLogNormal: geometric standard deviation must be >= 1");
  if (!(sizes.numberDensityPerM3 >= 0.0) || !std::isfinite(sizes.numberDensityPerM3))
    throw std::invalid_argument("mieLogNormal: number density must be >= 0");
  if (phaseSamples < 2) throw std::invalid_argument("mieLogNormal: phaseSamples must be >= 2");
  if (!(sizes.minRadiusM >= 0.0) || !(sizes.maxRadiusM >= 0.0) ||
      (sizes.maxRadiusM > 0.0 && !(sizes.maxRadiusM > sizes.minRadiusM)))
    throw std::invalid_argument("mieLogNormal: the radius cut must be 0 or 0 <= min < max");
  if (extraLevels < 0 || extraLevels > 8) throw std::invalid_argument("mieLogNormal: extraLevels must be in [0, 8]");
  if (!(bulkTolerance > 0.0 && bulkTolerance < 1.0) || !(phaseTolerance > 0.0 && phaseTolerance < 1.0))
    throw std::invalid_argument("mieLogNormal: tolerances must be in (0, 1)");
}

/// The integral over a log-normal size distribution, in u = ln(r/r_m)/s, of the cross
/// sections per particle times the normal density phi(u): C_ext, C_sca, g C_sca and
/// dC_sca/dOmega = (|S1|^2 + |S2|^2) / (2 k^2) at each angle, as one vector
/// [ext, sca, gsca, diff_0 .. diff_{P-1}].
struct SizeIntegral {
  double k, s, xm;  // wavenumber, ln(sigma_g), size parameter at the median radius
  double minRadiusM, maxRadiusM;  // the cut (0: none)
  cplx m;
  const std::vector<double>& cosTheta;
  int P, Q;

  SizeIntegral(double wavelengthM, cplx index, const LogNormalSizes& sizes, const std::vector<double>& cosines)
      : k(2.0 * kPi / wavelengthM), s(std::log(sizes.geometricStdDev)), xm(k * sizes.medianRadiusM),
        minRadiusM(sizes.minRadiusM), maxRadiusM(sizes.maxRadiusM), m(index),
        cosTheta(cosines), P(static_cast<int>(cosines.size())), Q(3 + P) {}

  double sizeAt(double u) const { return xm * std::exp(s * u); }

  /// Adds `weight` times the integrand at u to acc[0..Q).
  void add(double u, double weight, double* acc, std::vector<cplx>& s1, std::vector<cplx>& s2) const {
    const double x = sizeAt(u);
    const double r = x / k;
    const MieEfficiencies q = mieSphere(x, m, cosTheta, s1, s2);
    const double w = weight * std::exp(-0.5 * u * u) / std::sqrt(2.0 * kPi);
    const double area = kPi * r * r;
    acc[0] += w * area * q.qExt;
    acc[1] += w * area * q.qSca;
    acc[2] += w * area * q.qSca * q.g;
    const double toCross = w / (2.0 * k * k);
    for (int j = 0; j < P; ++j) acc[3 + j] += toCross * (std::norm(s1[j]) + std::norm(s2[j]));
  }

  /// The window [uLo, uHi] of the integral, on a coarse grid (efficiencies only): from the
  /// centre of the cross-section-weighted distribution (u = 2s) outwards until two nodes in
  /// a row add < 1e-10 of the running total to both C_ext and C_sca, and at least to
  /// |u| = 4. (A Rayleigh-like C_sca ~ r^6 peaks at u = 6s; the march follows it there.)
  std::pair<double, double> window() const {
    constexpr double kWindowTolerance = 1e-10;
    constexpr int kMaxCoarseSteps = 400;
    const double uc = 2.0 * s;
    auto coarse = [&](double u, double& ext, double& sca) {
      const double x = sizeAt(u);
      const double r = x / k;
      const MieEfficiencies q = mieSphere(x, m);
      const double w = std::exp(-0.5 * u * u) * kPi * r * r;
      ext = w * q.qExt;
      sca = w * q.qSca;
    };
    double sumExt = 0.0, sumSca = 0.0;
    coarse(uc, sumExt, sumSca);
    double uHi = uc, uLo = uc;
    for (int dir : {+1, -1}) {
      int quiet = 0;
      double u = uc;
      for (int step = 1; step <= kMaxCoarseSteps; ++step) {
        const double next = uc + dir * step * kCoarseStep;
        if (dir > 0 && sizeAt(next) > kMaxSizeParameter) break;
        if (dir < 0 && sizeAt(next) < 1e-100) break;
        u = next;
        double ext, sca;
        coarse(u, ext, sca);
        sumExt += ext;
        sumSca += sca;
        const bool small = ext <= kWindowTolerance * sumExt && sca <= kWindowTolerance * sumSca;
        quiet = small ? quiet + 1 : 0;
        if (quiet >= 2 && std::abs(u) >= 4.0) break;
      }
      (dir > 0 ? uHi : uLo) = u;
    }
    if (uHi < 4.0 && sizeAt(4.0) <= kMaxSizeParameter) uHi = 4.0;
    uLo = std::min(uLo, -4.0);
    return {uLo, uHi};
  }

  /// The sum of the integrand over nodes first, first + stride, ... (count of them) of a
  /// grid of `intervals` steps of h from uLo (its end points at half weight), in fixed
  /// blocks summed in order, so that the result does not depend on the number of threads.
  std::vector<double> sumNodes(double uLo, long intervals, long first, long count, long stride, double h) const {
    constexpr long kBlock = 16;
    const long blocks = (count + kBlock - 1) / kBlock;
    std::vector<double> partial(static_cast<std::size_t>(blocks) * Q, 0.0);
    ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 1)
    for (long blk = 0; blk < blocks; ++blk) errors.run([&] {
      std::vector<cplx> s1, s2;
      double* acc = partial.data() + blk * Q;
      for (long c = blk * kBlock; c < std::min(count, (blk + 1) * kBlock); ++c) {
        const long i = first + c * stride;
        const double endWeight = (i == 0 || i == intervals) ? 0.5 : 1.0;
        add(uLo + i * h, endWeight, acc, s1, s2);
      }
    });
    errors.rethrow();
    std::vector<double> sum(Q, 0.0);
    for (long blk = 0; blk < blocks; ++blk)
      for (int q = 0; q < Q; ++q) sum[q] += partial[blk * Q + q];
    return sum;
  }

  /// The trapezoidal rule over the window, halving the step until a halving changes every
  /// quantity by less than its tolerance (each level reuses the nodes of the one before),
  /// then `extraLevels` more. The first step resolves, at the Nyquist limit, the
  /// interference oscillations cos(omega x) at the centre of the window, omega = 2 + 4|m|.
  /// Changes are relative to each quantity, except g C_sca, whose change is measured
  /// against C_sca (g may be ~0). Sets the quadrature's figures in `out`.
  std::vector<double> integrate(int extraLevels, double bulkTolerance, double phaseTolerance, MieAerosol& out) const {
    constexpr long kMaxIntervals = 16384;
    auto [uLo, uHi] = window();
    if (minRadiusM > 0.0) uLo = std::max(uLo, std::log(k * minRadiusM / xm) / s);
    if (maxRadiusM > 0.0) uHi = std::min(uHi, std::log(k * maxRadiusM / xm) / s);
    if (!(uHi > uLo)) {  // the cut holds none of the distribution's window
      out.converged = true;
      out.minSizeParameter = out.maxSizeParameter = xm;
      return std::vector<double>(Q, 0.0);
    }
    const double width = uHi - uLo;
    const double omega = 2.0 + 4.0 * std::abs(m);
    const double hStart = std::min(kCoarseStep, kPi / (omega * s * sizeAt(2.0 * s)));
    long intervals = std::clamp(static_cast<long>(std::ceil(width / hStart)), 8L, kMaxIntervals);
    double h = width / intervals;
    std::vector<double> nodeSum = sumNodes(uLo, intervals, 0, intervals + 1, 1, h);
    std::vector<double> total(Q), previous(Q);
    for (int q = 0; q < Q; ++q) total[q] = h * nodeSum[q];
    int levelsLeft = -1;  // extra halvings still to do after convergence (-1: not converged yet)
    double change = 1.0;
    while (true) {
      if (levelsLeft < 0 && 2 * intervals > kMaxIntervals) levelsLeft = extraLevels;  // cap: give up
      if (levelsLeft == 0) break;
      intervals *= 2;
      h = width / intervals;
      const std::vector<double> added = sumNodes(uLo, intervals, 1, intervals / 2, 2, h);  // the new midpoints
      previous = total;
      for (int q = 0; q < Q; ++q) {
        nodeSum[q] += added[q];
        total[q] = h * nodeSum[q];
      }
      change = 0.0;
      bool ok = true;
      for (int q = 0; q < Q; ++q) {
        const double scale = std::abs(q == 2 ? total[1] : total[q]);
        const double rel = scale > 0.0 ? std::abs(total[q] - previous[q]) / scale : 0.0;
        change = std::max(change, rel);
        if (rel > (q < 3 ? bulkTolerance : phaseTolerance)) ok = false;
      }
      if (levelsLeft > 0) {
        --levelsLeft;
      } else if (ok) {
        out.converged = true;
        levelsLeft = extraLevels;
      }
    }
    out.quadratureChange = change;
    out.sizeNodes = static_cast<int>(intervals + 1);
    out.minSizeParameter = sizeAt(uLo);
    out.maxSizeParameter = sizeAt(uHi);
    return total;
  }

  static constexpr double kCoarseStep = 0.25;
};

} // namespace

MieAerosol mieLogNormal(double wavelengthM, std::complex<double> m, const LogNormalSizes& sizes, int phaseSamples,
                        int extraLevels, double bulkTolerance, double phaseTolerance) {
  checkLogNormalArguments(wavelengthM, sizes, phaseSamples, extraLevels, bulkTolerance, phaseTolerance);
  checkSphere(2.0 * kPi * sizes.medianRadiusM / wavelengthM, m);
  const int P = phaseSamples;
  MieAerosol out;
  out.cosTheta.resize(P);
  for (int j = 0; j < P; ++j) out.cosTheta[j] = std::cos(kPi * (1.0 - double(j) / (P - 1)));
  out.cosTheta.front() = -1.0;
  out.cosTheta.back() = 1.0;

  const SizeIntegral integral(wavelengthM, m, sizes, out.cosTheta);
  std::vector<double> total(integral.Q, 0.0);
  if (integral.s == 0.0) {
    // All particles have radius r_m.
    std::vector<cplx> s1, s2;
    integral.add(0.0, std::sqrt(2.0 * kPi), total.data(), s1, s2);  // cancels phi(0)
    out.sizeNodes = 1;
    out.minSizeParameter = out.maxSizeParameter = integral.xm;
    out.converged = true;
  } else {
    total = integral.integrate(extraLevels, bulkTolerance, phaseTolerance, out);
  }

  const double n = sizes.numberDensityPerM3;
  const double ext = total[0], sca = total[1];
  out.extinctionPerM = n * ext;
  out.scatteringPerM = n * sca;
  out.absorptionPerM = std::max(0.0, out.extinctionPerM - out.scatteringPerM);
  out.asymmetry = sca > 0.0 ? total[2] / sca : 0.0;
  out.phase.resize(P);
  for (int j = 0; j < P; ++j) out.phase[j] = sca > 0.0 ? total[3 + j] / sca : 1.0 / (4.0 * kPi);
  return out;
}

} // namespace umbra::atmosphere
