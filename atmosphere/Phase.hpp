#pragma once
// Scattering phase functions p(cos theta) in 1/sr, each normalised so that its integral
// over the sphere is 1 (2 pi int_{-1}^{1} p(mu) dmu = 1). theta is the scattering angle:
// cos theta = 1 is straight on (forward), -1 back towards the light.
//   Rayleigh                 3/(16 pi) (1 + mu^2)                           Costa Eq. 9
//   Penndorf                 0.7629 (1 + 0.932 mu^2) / (4 pi)               Costa Eq. 10
//                            (0.7629 is 1 / (1 + 0.932/3) = 0.762970 rounded;
//                             we use the exact normalisation)
//   Henyey-Greenstein(g)     (1 - g^2) / (4 pi (1 + g^2 - 2 g mu)^{3/2})
//   DoubleHenyeyGreenstein   alpha HG(g1) + (1 - alpha) HG(g2)                Costa Eq. 16
//     Costa prints (1 + g_1^2) in both numerators; that function does not integrate to
//     1 (it gives (1 + g^2) / (1 - g^2)), so we read it as the usual two-term HG of
//     Kattawar 1975, whose numerators are (1 - g_i^2).
//   Cornette-Shanks(g)       3/(8 pi) (1 - g^2)/(2 + g^2) (1 + mu^2) / (1 + g^2 - 2 g mu)^{3/2}
//                            (Cornette & Shanks 1992; Bruneton 2017's Mie phase, g = 0.8)
//   Tabulated                samples (mu_i, p_i) with mu from -1 to 1, linear in mu
//                            between them, rescaled so that its exact integral is 1
//                            (the hook for Lorenz-Mie phase functions)
#include <string>
#include <cstdint>
#include <vector>

namespace umbra::atmosphere {

class PhaseFunction {
public:
  enum class Kind {
    Isotropic,
    Rayleigh,
    Penndorf,
    HenyeyGreenstein,
    DoubleHenyeyGreenstein,
    CornetteShanks,
    Tabulated
  };

  PhaseFunction() = default;  ///< isotropic, 1 / (4 pi)

  static PhaseFunction isotropic();
  static PhaseFunction rayleigh();
  static PhaseFunction penndorf();
  /// |g| <= 1 - 1e-6; throws std::invalid_argument otherwise.
  static PhaseFunction henyeyGreenstein(double g);
  /// |g1|, |g2| <= 1 - 1e-6, alpha (the weight of the g1 lobe) in [0, 1].
  static PhaseFunction doubleHenyeyGreenstein(double g1, double g2, double alpha);
  static PhaseFunction cornetteShanks(double g);
  /// cosTheta strictly increasing from -1 to 1 (ends within 1e-9, then snapped), values
  /// finite and >= 0 with a positive integral. The values need not be normalised.
  static PhaseFunction tabulated(std::vector<double> cosTheta, std::vector<double> values);
  /// Same, from scattering angles in degrees strictly increasing from 0 to 180.
  static PhaseFunction tabulatedDegrees(const std::vector<double>& angleDeg,
                                        const std::vector<double>& values);
  /// The phase function of a mixture: sum_i w_i p_i / sum_i w_i (w_i >= 0, e.g. each
  /// part's scattering coefficient), tabulated: on the parts' own samples when every part
  /// is tabulated on the same ones (Lorenz-Mie's), else every 0.25 degrees. Throws
  /// std::invalid_argument on mismatched sizes or weights that do not sum above 0.
  static PhaseFunction mixture(const std::vector<PhaseFunction>& parts, const std::vector<double>& weights);

  /// p(cos theta) in 1/sr; cosTheta is clamped to [-1, 1].
  double operator()(double cosTheta) const;

  /// Tabulated: where cos theta falls among the samples, as operator() finds it: between
  /// samples i - 1 and i with weight f on i (i = 0: before the first, i = size: after the
  /// last). valueIn(interval(c)) == operator()(c); tables on the same cosThetaSamples()
  /// (Lorenz-Mie's, one per wavelength) share the interval.
  struct Interval {
    std::size_t i = 0;
    double f = 0.0;
  };
  Interval interval(double cosTheta) const;
  double valueIn(const Interval& s) const;

  /// The asymmetry parameter <cos theta> = 2 pi int p(mu) mu dmu (exact for every kind).
  double asymmetry() const;

  Kind kind() const { return kind_; }
  double g() const { return g1_; }       ///< HG, Cornette-Shanks; g1 of the double HG
  double g2() const { return g2_; }      ///< double HG
  double alpha() const { return alpha_; }  ///< double HG: weight of the g1 lobe
  const std::vector<double>& cosThetaSamples() const { return mu_; }
  const std::vector<double>& values() const { return p_; }  ///< normalised samples

  /// "henyey-greenstein(g=0.8)" and the like, for messages and cache keys.
  std::string describe() const;

private:
  Kind kind_ = Kind::Isotropic;
  double g1_ = 0.0, g2_ = 0.0, alpha_ = 1.0;
  std::vector<double> mu_, p_;
  /// Tabulated: bucket_[k] = the first sample above -1 + 2 k / kBuckets (k <= kBuckets), so
  /// that a lookup searches only the samples of its bucket (the same result as searching all).
  static constexpr int kBuckets = 1024;
  std::vector<std::uint32_t> bucket_;
};

const char* kindName(PhaseFunction::Kind kind);

}  // namespace umbra::atmosphere
