/// @file
/// @brief The joint moments of overlapping AVAR/HVAR estimates under a noise model (see
/// variance_covariance.h for the formulas).
#include "analysis/variance_covariance.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <utility>

#include "analysis/chi_square.h"
#include "common/errors.h"

namespace imunoise::analysis {
namespace {

/// Stretches of at most this many lags are summed lag by lag; longer ones by quadrature (the
/// two agree to ~1e−5 relative on the EDF of flicker FM at m = 10⁴).
constexpr std::int64_t kDirectSumLags = 64;

/// The difference filter of one averaging factor: taps c at phase offsets (in samples).
struct DifferenceFilter {
  std::array<double, 4> tap{};
  std::array<std::int64_t, 4> offset{};
  int taps = 0;
  std::int64_t terms = 0;  ///< N_m, the number of differences in the record
  double norm = 0.0;       ///< c·m²τ0²: σ̂² = Σ d²/(norm·N_m)
};

DifferenceFilter difference_filter(std::int64_t m, bool hadamard, std::int64_t n_phase,
                                   double tau0_s) {
  DifferenceFilter f;
  if (hadamard) {
    f.tap = {1.0, -3.0, 3.0, -1.0};
    f.taps = 4;
  } else {
    f.tap = {1.0, -2.0, 1.0, 0.0};
    f.taps = 3;
  }
  for (int a = 0; a < f.taps; ++a) f.offset[static_cast<std::size_t>(a)] = a * m;
  f.terms = n_phase - (f.taps - 1) * m;
  const double tau_s = static_cast<double>(m) * tau0_s;
  f.norm = (hadamard ? 6.0 : 2.0) * tau_s * tau_s;
  return f;
}

/// x + e^{−x} − 1 − x²/2 for x ≥ 0, accurate where the terms cancel: the series below 0.1
/// (truncation ~x⁶/60480 relative), else expm1 (which leaves a cancellation of ~3/x digits).
double gm_shape(double x) {
  if (x < 0.1) {
    const double x3 = x * x * x;
    return x3 *
           (-1.0 / 6.0 +
            x * (1.0 / 24.0 + x * (-1.0 / 120.0 +
                                   x * (1.0 / 720.0 + x * (-1.0 / 5040.0 + x * (1.0 / 40320.0))))));
  }
  return x + std::expm1(-x) - 0.5 * x * x;
}

/// The generalized covariance of the phase of the Gaussian continuous terms (N, B, K, GM) at a
/// lag of S seconds, up to a quadratic polynomial in S (which every difference of order ≥ 2
/// annihilates, for the cross-covariance of two such filters too).
double phase_generalized_covariance(const NoiseCoefficients& c, double s) {
  const double a = std::abs(s);
  double g = 0.0;
  if (c.white_noise > 0.0) g -= 0.5 * c.white_noise * c.white_noise * a;
  if (c.random_walk > 0.0) g += c.random_walk * c.random_walk * a * a * a / 12.0;
  if (c.bias_instability > 0.0 && a > 0.0) {
    g += c.bias_instability * c.bias_instability / (2.0 * std::numbers::pi) * a * a * std::log(a);
  }
  for (const GaussMarkov& gm : c.gauss_markov) {
    if (gm.sigma > 0.0)
      g -= gm.sigma * gm.sigma * gm.tau_c_s * gm.tau_c_s * gm_shape(a / gm.tau_c_s);
  }
  return g;
}

/// The two-sided rate PSD S_Ω(f) of the Gaussian terms (theory.md §4.1),
/// for the cross term of the sinusoids.
double rate_psd_two_sided(const NoiseCoefficients& c, double f_hz) {
  const double w = 2.0 * std::numbers::pi * f_hz;
  double s = c.white_noise * c.white_noise;
  s += c.bias_instability * c.bias_instability / w;
  s += c.random_walk * c.random_walk / (w * w);
  for (const GaussMarkov& gm : c.gauss_markov) {
    const double wt = w * gm.tau_c_s;
    s += 2.0 * gm.sigma * gm.sigma * gm.tau_c_s / (1.0 + wt * wt);
  }
  return s;
}

/// Σ_l w(l)·R12(l)² and Σ_l w(l)·R12(l) over every lag l = k − j of the two filters, R12 the
/// cross-covariance of their difference sequences.
class LagSums {
 public:
  LagSums(const NoiseCoefficients& model, double tau0_s, const DifferenceFilter& f1,
          const DifferenceFilter& f2)
      : model_(model), tau0_s_(tau0_s), f1_(f1), f2_(f2) {}

  /// {Σ w R², Σ w R}.
  std::array<double, 2> sums() const {
    const std::int64_t l_min = -(f1_.terms - 1), l_max = f2_.terms - 1;
    std::vector<std::int64_t> nodes{l_min, l_max, 0, f2_.terms - f1_.terms};
    std::int64_t a_max = 0, b_max = 0;
    for (int a = 0; a < f1_.taps; ++a) {
      for (int b = 0; b < f2_.taps; ++b) nodes.push_back(tap_lag(a, b));
    }
    a_max = f1_.offset[static_cast<std::size_t>(f1_.taps - 1)];
    b_max = f2_.offset[static_cast<std::size_t>(f2_.taps - 1)];
    // B and GM decay beyond the taps (as 1/l² and e^{−l·τ0/T_c}): geometric nodes out to 256
    // spans (R12² is then below 1e−9 of its peak) or 30 correlation times.
    // Beyond that the sum is cut: the rest is below 1e−7 of it, and R12 there is the difference
    // of terms ~(l/span)⁴ larger than itself, which double precision cannot resolve (summed
    // over a long record's 10⁷ lags, that rounding was what the variance picked up).
    const bool tails = model_.bias_instability > 0.0 || !model_.gauss_markov.empty();
    std::int64_t tail = 0;  // the lags summed beyond the taps on each side
    if (tails) {
      const std::int64_t span = a_max + b_max;
      double reach = 256.0 * static_cast<double>(span);
      for (const GaussMarkov& gm : model_.gauss_markov) {
        reach = std::max(reach, 30.0 * gm.tau_c_s / tau0_s_);
      }
      reach = std::min(reach, static_cast<double>(l_max - l_min));
      for (double d = static_cast<double>(span);; d *= 2.0) {
        tail = static_cast<std::int64_t>(std::min(d, reach));
        nodes.push_back(a_max + tail);
        nodes.push_back(-b_max - tail);
        if (d >= reach) break;
      }
    }
    for (std::int64_t& n : nodes) n = std::clamp(n, l_min, l_max);
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());

    std::array<double, 2> total{0.0, 0.0};
    // Without tails R12 vanishes outside [−b_max, a_max] (N, K: polynomials the filters
    // annihilate; Q: only where taps meet); with them the sum ends `tail` lags further out.
    const std::int64_t lo = std::max(l_min, -b_max - tail);
    const std::int64_t hi = std::min(l_max, a_max + tail);
    for (std::size_t i = 0; i + 1 < nodes.size(); ++i) {
      const std::int64_t p = nodes[i], q = nodes[i + 1];
      if (q <= lo || p >= hi) continue;
      add_segment(std::max(p, lo), std::min(q, hi), total);
    }
    add(total, static_cast<double>(hi), 1.0);
    // Q: the white phase adds to R12 only at the lags where two taps meet.
    if (model_.quantization > 0.0) {
      std::vector<std::int64_t> meets;
      for (int a = 0; a < f1_.taps; ++a) {
        for (int b = 0; b < f2_.taps; ++b) meets.push_back(tap_lag(a, b));
      }
      std::sort(meets.begin(), meets.end());
      meets.erase(std::unique(meets.begin(), meets.end()), meets.end());
      for (const std::int64_t l : meets) {
        if (l < l_min || l > l_max) continue;
        const double w = weight(l);
        const double rc = continuous_r12(static_cast<double>(l));
        const double r = rc + quantization_r12(l);
        total[0] += w * (r * r - rc * rc);
        total[1] += w * (r - rc);
      }
    }
    return total;
  }

  /// R12 at lag 0 with Q (the variance of one difference when both filters are the same).
  double r12_at_zero() const { return continuous_r12(0.0) + quantization_r12(0); }

 private:
  std::int64_t tap_lag(int a, int b) const {
    return f1_.offset[static_cast<std::size_t>(a)] - f2_.offset[static_cast<std::size_t>(b)];
  }

  /// The number of pairs (j, k), 0 ≤ j < N1, 0 ≤ k < N2, with k − j = l (linear between nodes).
  double weight(double l) const {
    const double n1 = static_cast<double>(f1_.terms), n2 = static_cast<double>(f2_.terms);
    return std::max(0.0, std::min(n1, n2 - l) - std::max(0.0, -l));
  }

  double continuous_r12(double l) const {
    double r = 0.0;
    for (int a = 0; a < f1_.taps; ++a) {
      for (int b = 0; b < f2_.taps; ++b) {
        const double s = (l + static_cast<double>(f2_.offset[static_cast<std::size_t>(b)] -
                                                  f1_.offset[static_cast<std::size_t>(a)])) *
                         tau0_s_;
        r += f1_.tap[static_cast<std::size_t>(a)] * f2_.tap[static_cast<std::size_t>(b)] *
             phase_generalized_covariance(model_, s);
      }
    }
    return r;
  }

  double quantization_r12(std::int64_t l) const {
    double r = 0.0;
    for (int a = 0; a < f1_.taps; ++a) {
      for (int b = 0; b < f2_.taps; ++b) {
        if (tap_lag(a, b) == l)
          r += f1_.tap[static_cast<std::size_t>(a)] * f2_.tap[static_cast<std::size_t>(b)];
      }
    }
    return r * model_.quantization * model_.quantization;
  }

  void add(std::array<double, 2>& total, double l, double factor) const {
    const double w = weight(l);
    const double r = continuous_r12(l);
    total[0] += factor * w * r * r;
    total[1] += factor * w * r;
  }

  /// Σ_{l=p}^{q−1} of w·R12² and w·R12 (continuous part): exactly over short stretches, else
  /// by 8-point Gauss–Legendre with the Euler–Maclaurin end correction (f(p) − f(q))/2. Between
  /// nodes R12 is a polynomial of degree ≤ 3 for N and K (f of degree ≤ 7: GL8 is exact), and
  /// smooth for B and GM.
  void add_segment(std::int64_t p, std::int64_t q, std::array<double, 2>& total) const {
    if (q - p <= kDirectSumLags) {
      for (std::int64_t l = p; l < q; ++l) add(total, static_cast<double>(l), 1.0);
      return;
    }
    static constexpr std::array<double, 8> kNode{
        -0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
        0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
    static constexpr std::array<double, 8> kWeight{
        0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
        0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
    const double mid = 0.5 * static_cast<double>(p + q), half = 0.5 * static_cast<double>(q - p);
    for (std::size_t i = 0; i < kNode.size(); ++i)
      add(total, mid + half * kNode[i], half * kWeight[i]);
    add(total, static_cast<double>(p), 0.5);
    add(total, static_cast<double>(q), -0.5);
  }

  const NoiseCoefficients& model_;
  double tau0_s_;
  const DifferenceFilter& f1_;
  const DifferenceFilter& f2_;
};

/// The deterministic part of the differences: the ramp's constant μ (AVAR: R·τ²; HVAR: 0).
double ramp_mean(const NoiseCoefficients& c, std::int64_t m, double tau0_s, bool hadamard) {
  if (hadamard || c.ramp == 0.0) return 0.0;
  const double tau_s = static_cast<double>(m) * tau0_s;
  return c.ramp * tau_s * tau_s;
}

/// The filter's response H(ω) = Σ_a c_a e^{iωaτ0} at a sinusoid's angular frequency.
std::complex<double> filter_response(const DifferenceFilter& f, double omega, double tau0_s) {
  std::complex<double> h = 0.0;
  for (int a = 0; a < f.taps; ++a) {
    h += f.tap[static_cast<std::size_t>(a)] *
         std::polar(1.0,
                    omega * tau0_s * static_cast<double>(f.offset[static_cast<std::size_t>(a)]));
  }
  return h;
}

}  // namespace

VarianceCovariance overlapping_variance_covariance(const NoiseCoefficients& model, double tau0_s,
                                                   std::int64_t n_rate_samples,
                                                   std::span<const std::int64_t> m_list,
                                                   bool hadamard) {
  IMUNOISE_EXPECT(tau0_s > 0.0 && std::isfinite(tau0_s), "variance covariance: tau0 must be > 0");
  IMUNOISE_EXPECT(model.quantization >= 0.0 && model.white_noise >= 0.0 &&
                      model.bias_instability >= 0.0 && model.random_walk >= 0.0 &&
                      model.ramp >= 0.0,
                  "variance covariance: negative coefficient");
  for (const GaussMarkov& gm : model.gauss_markov) {
    IMUNOISE_EXPECT(gm.sigma >= 0.0 && gm.tau_c_s > 0.0,
                    "variance covariance: invalid Gauss-Markov term");
  }
  const std::int64_t n_phase = n_rate_samples + 1;
  std::vector<DifferenceFilter> filters;
  filters.reserve(m_list.size());
  for (const std::int64_t m : m_list) {
    IMUNOISE_EXPECT(m >= 1, "variance covariance: averaging factor < 1");
    filters.push_back(difference_filter(m, hadamard, n_phase, tau0_s));
    IMUNOISE_EXPECT(filters.back().terms >= 1, "variance covariance: record too short for m");
  }
  const std::size_t n = filters.size();
  VarianceCovariance out;
  out.expected.resize(n);
  out.edf.resize(n);
  out.covariance.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));

  // Sinusoids: phase amplitude A/ω; their mean square enters E[d²] exactly, their cross term
  // with the noise 4·N·½|X|²|H1|²|H2|²·S_x(ω) with the discrete phase spectrum
  // S_x = τ0·S_Ω(f)/(4 sin²(πfτ0)) + Q².
  struct Line {
    double omega, half_x2, phase_psd;
  };
  std::vector<Line> lines;
  for (const Sinusoid& s : model.sinusoids) {
    if (s.amplitude <= 0.0 || s.frequency_hz <= 0.0) continue;
    const double omega = 2.0 * std::numbers::pi * s.frequency_hz;
    const double x = s.amplitude / omega;
    const double sn = std::sin(std::numbers::pi * s.frequency_hz * tau0_s);
    const double psd = tau0_s * rate_psd_two_sided(model, s.frequency_hz) / (4.0 * sn * sn) +
                       model.quantization * model.quantization;
    lines.push_back({omega, 0.5 * x * x, psd});
  }

  for (std::size_t i = 0; i < n; ++i) {
    const DifferenceFilter& fi = filters[i];
    const LagSums self(model, tau0_s, fi, fi);
    const double mu = ramp_mean(model, m_list[i], tau0_s, hadamard);
    double mean_square = self.r12_at_zero() + mu * mu;
    for (const Line& line : lines)
      mean_square += line.half_x2 * std::norm(filter_response(fi, line.omega, tau0_s));
    out.expected[i] = mean_square / fi.norm;
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i; j < n; ++j) {
      const DifferenceFilter& fi = filters[i];
      const DifferenceFilter& fj = filters[j];
      const std::array<double, 2> s = LagSums(model, tau0_s, fi, fj).sums();
      const double mu_i = ramp_mean(model, m_list[i], tau0_s, hadamard);
      const double mu_j = ramp_mean(model, m_list[j], tau0_s, hadamard);
      double numerator = 2.0 * s[0] + 4.0 * mu_i * mu_j * s[1];
      const double pairs = static_cast<double>(std::min(fi.terms, fj.terms));
      for (const Line& line : lines) {
        numerator += 4.0 * pairs * line.half_x2 *
                     std::norm(filter_response(fi, line.omega, tau0_s)) *
                     std::norm(filter_response(fj, line.omega, tau0_s)) * line.phase_psd;
      }
      const double cov = numerator / (fi.norm * static_cast<double>(fi.terms) * fj.norm *
                                      static_cast<double>(fj.terms));
      out.covariance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = cov;
      out.covariance(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(i)) = cov;
    }
    const double var = out.covariance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i));
    out.edf[i] = var > 0.0 ? 2.0 * out.expected[i] * out.expected[i] / var : 0.0;
  }
  return out;
}

namespace {

/// The χ²_ν/ν variate whose normal score is Z: its exact quantile at Φ(Z) (tails from erfc so
/// neither loses digits) for ν < 50; above, the Wilson–Hilferty cube (1 − 2/9ν + Z·√(2/9ν))³,
/// within 1e−4 relative of the exact quantile for |Z| ≤ 4 there and a few hundred times
/// cheaper (the exact one iterates a continued fraction of ~8.5·√(ν/2) terms; the draws of a
/// long record have ν up to ~10⁶ at short τ).
double chi_square_over_dof(double z, double nu) {
  if (nu >= 50.0) {
    const double c = 2.0 / (9.0 * nu);
    const double w = std::max(0.0, 1.0 - c + z * std::sqrt(c));
    return w * w * w;
  }
  const double tail = 0.5 * std::erfc(std::fabs(z) / std::sqrt(2.0));
  return (z <= 0.0 ? chi_square_quantile(tail, nu) : chi_square_upper_quantile(tail, nu)) / nu;
}

}  // namespace

Eigen::MatrixXd correlation_matrix(const VarianceCovariance& moments) {
  const Eigen::Index n = moments.covariance.rows();
  Eigen::MatrixXd correlation(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) {
      const double vi = moments.covariance(i, i), vj = moments.covariance(j, j);
      correlation(i, j) = vi > 0.0 && vj > 0.0 && std::isfinite(vi * vj)
                              ? moments.covariance(i, j) / std::sqrt(vi * vj)
                              : (i == j ? 1.0 : 0.0);
    }
  }
  return correlation;
}

Eigen::MatrixXd correlation_factor(const Eigen::MatrixXd& correlation) {
  const Eigen::Index n = correlation.rows();
  for (double ridge = 0.0; ridge <= 1e-9; ridge = ridge == 0.0 ? 1e-12 : ridge * 10.0) {
    Eigen::LLT<Eigen::MatrixXd> llt(correlation + ridge * Eigen::MatrixXd::Identity(n, n));
    if (llt.info() == Eigen::Success) return llt.matrixL();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(correlation);
  const double floor = 1e-10 * std::max(1.0, eigen.eigenvalues().maxCoeff());
  Eigen::MatrixXd clipped = eigen.eigenvectors() *
                            eigen.eigenvalues().cwiseMax(floor).asDiagonal() *
                            eigen.eigenvectors().transpose();
  const Eigen::VectorXd scale = clipped.diagonal().cwiseSqrt().cwiseInverse();
  clipped = scale.asDiagonal() * clipped * scale.asDiagonal();
  return Eigen::LLT<Eigen::MatrixXd>(clipped + floor * Eigen::MatrixXd::Identity(n, n)).matrixL();
}

VarianceDraw::VarianceDraw(VarianceCovariance moments)
    : moments_(std::move(moments)), factor_(correlation_factor(correlation_matrix(moments_))) {}

void VarianceDraw::draw(std::span<const double> normals, std::span<double> avar) const {
  const Eigen::Index n = factor_.rows();
  IMUNOISE_EXPECT(normals.size() == static_cast<std::size_t>(n) && avar.size() == normals.size(),
                  "VarianceDraw::draw: " + std::to_string(n) + " normals and values expected");
  const Eigen::VectorXd z =
      factor_.triangularView<Eigen::Lower>() * Eigen::Map<const Eigen::VectorXd>(normals.data(), n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double nu = moments_.edf[static_cast<std::size_t>(i)];
    // EDF 0: no variance under the model (VarianceCovariance), the expectation.
    avar[static_cast<std::size_t>(i)] = moments_.expected[static_cast<std::size_t>(i)] *
                                        (nu > 0.0 ? chi_square_over_dof(z(i), nu) : 1.0);
  }
}

}  // namespace imunoise::analysis
