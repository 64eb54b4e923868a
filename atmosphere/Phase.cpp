#include "Phase.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace umbra::atmosphere {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kPenndorfAnisotropy = 0.932;  // Costa Eq. 10 (Penndorf 1957)

constexpr double kMaxAsymmetry = 1.0 - 1e-6;

std::string number(double x) {
  std::ostringstream out;
  out.precision(10);
  out << x;
  return out.str();
}

// |g| at most 1 - 1e-6: the forward peak of HG(g) is (1 + g) / (1 - g)^2 / (4 pi), 2e12 /sr
// there; closer to 1 it grows past what the tables' double sums keep finite.
void checkG(double g, const char* name) {
  if (!std::isfinite(g) || !(std::abs(g) <= kMaxAsymmetry))
    throw std::invalid_argument(std::string(name) + ": expected a number in [-0.999999, 0.999999], got " + number(g));
}

double hg(double g, double mu) {
  const double d = 1.0 + g * g - 2.0 * g * mu;
  return (1.0 - g * g) / (4.0 * kPi * d * std::sqrt(d));
}

}  // namespace

const char* kindName(PhaseFunction::Kind kind) {
  switch (kind) {
    case PhaseFunction::Kind::Isotropic: return "isotropic";
    case PhaseFunction::Kind::Rayleigh: return "rayleigh";
    case PhaseFunction::Kind::Penndorf: return "penndorf";
    case PhaseFunction::Kind::HenyeyGreenstein: return "henyey-greenstein";
    case PhaseFunction::Kind::DoubleHenyeyGreenstein: return "double-henyey-greenstein";
    case PhaseFunction::Kind::CornetteShanks: return "cornette-shanks";
    case PhaseFunction::Kind::Tabulated: return "tabulated";
  }
  return "?";
}

PhaseFunction PhaseFunction::isotropic() { return PhaseFunction(); }

PhaseFunction PhaseFunction::rayleigh() {
  PhaseFunction p;
  p.kind_ = Kind::Rayleigh;
  return p;
}

PhaseFunction PhaseFunction::penndorf() {
  PhaseFunction p;
  p.kind_ = Kind::Penndorf;
  return p;
}

PhaseFunction PhaseFunction::henyeyGreenstein(double g) {
  checkG(g, "g");
  PhaseFunction p;
  p.kind_ = Kind::HenyeyGreenstein;
  p.g1_ = g;
  return p;
}

PhaseFunction PhaseFunction::doubleHenyeyGreenstein(double g1, double g2, double alpha) {
  checkG(g1, "g1");
  checkG(g2, "g2");
  if (!std::isfinite(alpha) || alpha < 0.0 || alpha > 1.0)
    throw std::invalid_argument("alpha: expected a number in [0, 1], got " + number(alpha));
  PhaseFunction p;
  p.kind_ = Kind::DoubleHenyeyGreenstein;
  p.g1_ = g1;
  p.g2_ = g2;
  p.alpha_ = alpha;
  return p;
}

PhaseFunction PhaseFunction::cornetteShanks(double g) {
  checkG(g, "g");
  PhaseFunction p;
  p.kind_ = Kind::CornetteShanks;
  p.g1_ = g;
  return p;
}

PhaseFunction PhaseFunction::mixture(const std::vector<PhaseFunction>& parts, const std::vector<double>& weights) {
  if (parts.empty() || parts.size() != weights.size())
    throw std::invalid_argument("a mixture needs one weight per part and at least one part");
  double total = 0.0;
  for (double w : weights) {
    if (!std::isfinite(w) || w < 0.0) throw std::invalid_argument("mixture weight " + number(w) + ": expected >= 0");
    total += w;
  }
  if (!(total > 0.0)) throw std::invalid_argument("mixture weights: expected a positive sum");
  bool shared = true;
  for (const PhaseFunction& p : parts)
    shared = shared && p.kind_ == Kind::Tabulated && p.mu_ == parts.front().mu_;
  std::vector<double> mu;
  if (shared) {
    mu = parts.front().mu_;
  } else {
    constexpr int kSamples = 721;  // every 0.25 degrees
    for (int i = 0; i < kSamples; ++i) mu.push_back(std::cos(kPi * (kSamples - 1 - i) / (kSamples - 1)));
  }
  std::vector<double> values(mu.size(), 0.0);
  for (std::size_t j = 0; j < parts.size(); ++j) {
    if (weights[j] == 0.0) continue;
    for (std::size_t k = 0; k < mu.size(); ++k)
      values[k] += weights[j] / total * (shared ? parts[j].p_[k] : parts[j](mu[k]));
  }
  return tabulated(std::move(mu), std::move(values));
}

PhaseFunction PhaseFunction::tabulated(std::vector<double> cosTheta, std::vector<double> values) {
  if (cosTheta.size() != values.size())
    throw std::invalid_argument("values: expected as many values as angles (" +
                                std::to_string(cosTheta.size()) + "), got " +
                                std::to_string(values.size()));
  if (cosTheta.size() < 2)
    throw std::invalid_argument("expected at least 2 samples, got " + std::to_string(cosTheta.size()));
  if (!(std::abs(cosTheta.front() + 1.0) <= 1e-9) || !(std::abs(cosTheta.back() - 1.0) <= 1e-9))
    throw std::invalid_argument("expected samples from cos theta = -1 to 1 (0 to 180 degrees), got " +
                                number(cosTheta.front()) + " to " + number(cosTheta.back()));
  cosTheta.front() = -1.0;
  cosTheta.back() = 1.0;
  double integral = 0.0;
  for (std::size_t i = 0; i < cosTheta.size(); ++i) {
    if (i > 0 && !(cosTheta[i] > cosTheta[i - 1]))
      throw std::invalid_argument("expected strictly monotonic angles, got cos theta " +
                                  number(cosTheta[i]) + " after " + number(cosTheta[i - 1]));
    if (!std::isfinite(values[i]) || values[i] < 0.0)
      throw std::invalid_argument("values[" + std::to_string(i) + "]: expected a finite value >= 0, got " +
                                  number(values[i]));
    if (i > 0) integral += 0.5 * (cosTheta[i] - cosTheta[i - 1]) * (values[i] + values[i - 1]);
  }
  integral *= 2.0 * kPi;
  if (!(integral > 0.0)) throw std::invalid_argument("expected a phase function with a positive integral");
  for (double& v : values) v /= integral;
  PhaseFunction p;
  p.kind_ = Kind::Tabulated;
  p.mu_ = std::move(cosTheta);
  p.p_ = std::move(values);
  p.bucket_.resize(kBuckets + 1);
  for (int k = 0; k <= kBuckets; ++k)
    p.bucket_[k] = static_cast<std::uint32_t>(std::upper_bound(p.mu_.begin(), p.mu_.end(), -1.0 + 2.0 * k / kBuckets) - p.mu_.begin());
  return p;
}

PhaseFunction PhaseFunction::tabulatedDegrees(const std::vector<double>& angleDeg,
                                              const std::vector<double>& values) {
  if (angleDeg.size() != values.size())
    throw std::invalid_argument("values: expected as many values as angles (" +
                                std::to_string(angleDeg.size()) + "), got " +
                                std::to_string(values.size()));
  std::vector<double> mu(angleDeg.size()), p(values.size());
  for (std::size_t i = 0; i < angleDeg.size(); ++i) {
    if (!std::isfinite(angleDeg[i]) || angleDeg[i] < -1e-7 || angleDeg[i] > 180.0 + 1e-7)
      throw std::invalid_argument("anglesDeg[" + std::to_string(i) + "]: expected an angle in [0, 180], got " +
                                  number(angleDeg[i]));
    if (i > 0 && !(angleDeg[i] > angleDeg[i - 1]))
      throw std::invalid_argument("anglesDeg[" + std::to_string(i) +
                                  "]: expected strictly increasing angles, got " + number(angleDeg[i]) +
                                  " after " + number(angleDeg[i - 1]));
    // reversed: cos theta increases as theta decreases
    const std::size_t j = angleDeg.size() - 1 - i;
    mu[j] = std::cos(angleDeg[i] * kPi / 180.0);
    p[j] = values[i];
  }
  return tabulated(std::move(mu), std::move(p));
}

double PhaseFunction::operator()(double cosTheta) const {
  const double mu = std::clamp(cosTheta, -1.0, 1.0);
  switch (kind_) {
    case Kind::Isotropic: return 1.0 / (4.0 * kPi);
    case Kind::Rayleigh: return 3.0 / (16.0 * kPi) * (1.0 + mu * mu);
    case Kind::Penndorf:
      return (1.0 + kPenndorfAnisotropy * mu * mu) / (4.0 * kPi * (1.0 + kPenndorfAnisotropy / 3.0));
    case Kind::HenyeyGreenstein: return hg(g1_, mu);
    case Kind::DoubleHenyeyGreenstein: return alpha_ * hg(g1_, mu) + (1.0 - alpha_) * hg(g2_, mu);
    case Kind::CornetteShanks: {
      const double g = g1_;
      const double d = 1.0 + g * g - 2.0 * g * mu;
      return 3.0 / (8.0 * kPi) * (1.0 - g * g) / (2.0 + g * g) * (1.0 + mu * mu) / (d * std::sqrt(d));
    }
    case Kind::Tabulated: return valueIn(interval(mu));
  }
  return 0.0;
}

PhaseFunction::Interval PhaseFunction::interval(double cosTheta) const {
  if (kind_ != Kind::Tabulated) throw std::logic_error("PhaseFunction::interval of a closed-form phase function");
  const double mu = std::clamp(cosTheta, -1.0, 1.0);
  // The bucket's samples, one bucket wider each side (the bucket's edges are rounded).
  const int k = std::clamp(static_cast<int>((mu + 1.0) * (0.5 * kBuckets)), 0, kBuckets - 1);
  const auto upper = std::upper_bound(mu_.begin() + bucket_[std::max(k - 1, 0)],
                                      mu_.begin() + bucket_[std::min(k + 2, kBuckets)], mu);
  const std::size_t i = static_cast<std::size_t>(upper - mu_.begin());
  if (i == 0 || i == mu_.size()) return {i, 0.0};
  return {i, (mu - mu_[i - 1]) / (mu_[i] - mu_[i - 1])};
}

double PhaseFunction::valueIn(const Interval& s) const {
  if (s.i >= p_.size()) return p_.back();
  if (s.i == 0) return p_.front();
  return p_[s.i - 1] + s.f * (p_[s.i] - p_[s.i - 1]);
}

double PhaseFunction::asymmetry() const {
  switch (kind_) {
    case Kind::Isotropic:
    case Kind::Rayleigh:
    case Kind::Penndorf: return 0.0;
    case Kind::HenyeyGreenstein: return g1_;
    case Kind::DoubleHenyeyGreenstein: return alpha_ * g1_ + (1.0 - alpha_) * g2_;
    case Kind::CornetteShanks: {
      const double g = g1_;
      return 3.0 * g * (4.0 + g * g) / (5.0 * (2.0 + g * g));
    }
    case Kind::Tabulated: {
      // exact for the piecewise-linear p: int over [m0, m1] of p mu dmu
      // = h/6 (p0 (2 m0 + m1) + p1 (m0 + 2 m1))
      double sum = 0.0;
      for (std::size_t i = 0; i + 1 < mu_.size(); ++i) {
        const double m0 = mu_[i], m1 = mu_[i + 1];
        sum += (m1 - m0) / 6.0 * (p_[i] * (2.0 * m0 + m1) + p_[i + 1] * (m0 + 2.0 * m1));
      }
      return 2.0 * kPi * sum;
    }
  }
  return 0.0;
}

std::string PhaseFunction::describe() const {
  std::string s = kindName(kind_);
  switch (kind_) {
    case Kind::HenyeyGreenstein:
    case Kind::CornetteShanks: return s + "(g=" + number(g1_) + ")";
    case Kind::DoubleHenyeyGreenstein:
      return s + "(g1=" + number(g1_) + ", g2=" + number(g2_) + ", alpha=" + number(alpha_) + ")";
    case Kind::Tabulated: return s + "(" + std::to_string(mu_.size()) + " samples)";
    default: return s;
  }
}

}  // namespace umbra::atmosphere
