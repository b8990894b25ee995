/// @file
/// @brief Tests of models/state_space.h against independent truths: the closed forms of
/// theory.md §6.2 against Van Loan, the printed discrete sigmas of §8.2, the stationary
/// (Lyapunov) covariance of §6.1, the analytic damped-oscillator transition, and Monte Carlo
/// with a fixed seed.
///
/// Monte Carlo tolerance, derived rather than tuned: for M independent Gaussian draws of
/// variance Q the sample variance s² has standard error Q·√(2/(M−1)), a sample covariance
/// s_ij has Var s_ij ≈ (Q_ii Q_jj + Q_ij²)/(M−1), and the sample mean has standard error
/// √(Q/M). We accept |estimate − truth| < 4 standard errors (two-sided normal tail ≈ 6e-5 per
/// comparison); with the fixed seeds a failure means a wrong formula, not bad luck. Where the
/// simulation scheme itself is biased (Euler–Maruyama), its bias is computed exactly and added.
#include "models/state_space.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "test_support.h"

namespace imunoise::models {
namespace {

/// @name Worked example, theory.md §8.2 and §8.3 (b)
/// @{
constexpr double kExampleN = 1.16355e-4;  // white rate noise N [rad/√s]
constexpr double kExampleK = 6.80678e-6;  // rate random walk K [rad/s^{3/2}]
constexpr double kGmSigma = 1.314e-4;     // GM σ, §8.3 (b) peak match [rad/s]
constexpr double kGmTauC = 15.6;          // GM T_c, §8.3 (b) [s]
/// @}

/// max |A − B| / max(max |A|, max |B|): elementwise difference relative to the matrix scale.
double max_rel_diff(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  EXPECT_EQ(a.rows(), b.rows());
  EXPECT_EQ(a.cols(), b.cols());
  if (a.rows() != b.rows() || a.cols() != b.cols()) return std::numeric_limits<double>::infinity();
  const double scale = std::max(a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff());
  return scale == 0.0 ? 0.0 : (a - b).cwiseAbs().maxCoeff() / scale;
}

/// Expects the closed form and discretize() of the matching continuous model to agree.
void expect_matches_van_loan(const DiscreteStateModel& closed, const ContinuousStateModel& cont,
                             double dt_s, double tol) {
  const DiscreteStateModel vl = discretize(cont, dt_s);
  EXPECT_EQ(closed.method, "closed form");
  EXPECT_EQ(vl.method.rfind("van loan", 0), 0u) << vl.method;
  EXPECT_EQ(closed.state_names, vl.state_names);
  EXPECT_DOUBLE_EQ(vl.dt_s, dt_s);
  EXPECT_LT(max_rel_diff(closed.Phi, vl.Phi), tol) << "dt = " << dt_s;
  EXPECT_LT(max_rel_diff(closed.Qd, vl.Qd), tol) << "dt = " << dt_s;
}

TEST(StateSpace, RandomWalkClosedFormMatchesVanLoan) {
  for (const double dt : {0.005, 1.0, 100.0, 1e6}) {
    expect_matches_van_loan(random_walk_discrete(kExampleK, dt, "bg"),
                            random_walk_state(kExampleK, "bg"), dt, 1e-12);
  }
}

TEST(StateSpace, GaussMarkovClosedFormMatchesVanLoan) {
  // Δt/T_c from far below to far above one; ≥ 10 makes discretize() substep.
  for (const double ratio : {1e-4, 0.01, 1.0, 10.0, 200.0}) {
    const double dt = ratio * kGmTauC;
    expect_matches_van_loan(gauss_markov_discrete(kGmSigma, kGmTauC, dt, "bg"),
                            gauss_markov_state(kGmSigma, kGmTauC, "bg"), dt, 1e-12);
  }
  EXPECT_EQ(discretize(gauss_markov_state(kGmSigma, kGmTauC, "bg"), 200.0 * kGmTauC).method,
            "van loan, 2^8 substeps");  // ‖F‖Δt = 200 → 200/2^8 ≤ 1 < 200/2^7
}

TEST(StateSpace, AngleBiasClosedFormMatchesVanLoan) {
  for (const double dt : {0.005, 1.0, 100.0}) {
    expect_matches_van_loan(angle_bias_discrete(kExampleN, kExampleK, dt, "gx"),
                            angle_bias_state(kExampleN, kExampleK, "gx"), dt, 1e-12);
  }
}

TEST(StateSpace, AngleBiasQdMatchesTheory62HandFormula) {
  // theory.md §6.2 with §8.2 numbers at 200 Hz, evaluated here term by term:
  // N²Δt = 6.7692e-11, K²Δt³/3 = 1.9303e-18, K²Δt²/2 = 5.7915e-16, K²Δt = 2.3166e-13.
  const double dt = 1.0 / 200.0;
  const double n2dt = 1.16355e-4 * 1.16355e-4 * 0.005;
  const double k2 = 6.80678e-6 * 6.80678e-6;
  EXPECT_NEAR(n2dt, 6.7692e-11, 0.00005e-11);
  EXPECT_NEAR(k2 * dt, 2.3166e-13, 0.00005e-13);
  Eigen::Matrix2d expected;
  expected << n2dt + k2 * 1.25e-7 / 3.0, k2 * 2.5e-5 / 2.0, k2 * 2.5e-5 / 2.0, k2 * 0.005;
  for (const DiscreteStateModel& d :
       {angle_bias_discrete(kExampleN, kExampleK, dt, "gx"),
        discretize(angle_bias_state(kExampleN, kExampleK, "gx"), dt)}) {
    EXPECT_LT(max_rel_diff(d.Qd, expected), 1e-12) << d.method;
    // Each element on its own scale, not just relative to the largest one.
    EXPECT_NEAR(d.Qd(0, 1) / expected(0, 1), 1.0, 1e-10) << d.method;
    EXPECT_NEAR(d.Qd(1, 1) / expected(1, 1), 1.0, 1e-10) << d.method;
    EXPECT_EQ(d.Phi(0, 1), dt);
  }
}

TEST(StateSpace, DiscreteSigmasMatchTheory82Kalibr) {
  // σ_gd and σ_bgd as printed in theory.md §8.2 (4 digits).
  EXPECT_NEAR(white_noise_rate_sigma(kExampleN, 1.0 / 200.0), 1.6455e-3, 0.00005e-3);
  EXPECT_NEAR(std::sqrt(random_walk_discrete(kExampleK, 1.0 / 200.0, "bg").Qd(0, 0)), 4.813e-7,
              0.0005e-7);
  // N/√0.01 = 1.16355e-3 exactly, a tie that §8.2 rounds up: allow the half unit plus rounding.
  EXPECT_NEAR(white_noise_rate_sigma(kExampleN, 1.0 / 100.0), 1.1636e-3, 0.0000501e-3);
  EXPECT_NEAR(std::sqrt(random_walk_discrete(kExampleK, 1.0 / 100.0, "bg").Qd(0, 0)), 6.807e-7,
              0.0005e-7);
  // The increment form is the angle part of the [θ, b] Q_d with K = 0.
  const double dt = 1.0 / 200.0;
  EXPECT_NEAR(white_noise_increment_sigma(kExampleN, dt),
              std::sqrt(angle_bias_discrete(kExampleN, 0.0, dt, "gx").Qd(0, 0)), 1e-20);
  EXPECT_NEAR(white_noise_increment_sigma(kExampleN, dt) * white_noise_rate_sigma(kExampleN, dt),
              kExampleN * kExampleN, 1e-22);
}

TEST(StateSpace, GaussMarkovKeepsStationaryVariance) {
  const double var = kGmSigma * kGmSigma;
  for (const double dt : {1e-3, 0.1, 15.6, 100.0, 3000.0}) {
    const DiscreteStateModel closed = gauss_markov_discrete(kGmSigma, kGmTauC, dt, "bg");
    const DiscreteStateModel vl = discretize(gauss_markov_state(kGmSigma, kGmTauC, "bg"), dt);
    for (const DiscreteStateModel& d : {closed, vl}) {
      const double phi = d.Phi(0, 0);
      EXPECT_NEAR((phi * var * phi + d.Qd(0, 0)) / var, 1.0, 1e-14) << d.method << " dt=" << dt;
    }
  }
}

TEST(StateSpace, SecondOrderGaussMarkovKeepsStationaryCovariance) {
  const double sigma = 2.0, w = 0.5, zeta = 0.3;
  const ContinuousStateModel m = second_order_gauss_markov_state(sigma, w, zeta, "vib");
  const Eigen::Matrix2d p_inf = Eigen::Vector2d(sigma * sigma, w * w * sigma * sigma).asDiagonal();
  EXPECT_EQ(Eigen::MatrixXd(m.initial_variance.asDiagonal()), Eigen::MatrixXd(p_inf));
  // Continuous Lyapunov F P + P Fᵀ + G Q_c Gᵀ = 0 (theory.md §6.1: Var x = σ²).
  const Eigen::MatrixXd lyap = m.F * p_inf + p_inf * m.F.transpose() + m.G * m.Qc * m.G.transpose();
  EXPECT_LT(lyap.cwiseAbs().maxCoeff(), 1e-15 * p_inf.maxCoeff());

  // Independent Φ: the underdamped oscillator e^{FΔt} in closed form, ω_d = ω_n√(1 − ζ²).
  const double wd = w * std::sqrt(1.0 - zeta * zeta);
  for (const double dt : {0.01, 1.0, 10.0, 100.0}) {
    const DiscreteStateModel d = discretize(m, dt);
    const double e = std::exp(-zeta * w * dt), c = std::cos(wd * dt), s = std::sin(wd * dt);
    Eigen::Matrix2d phi;
    phi << e * (c + zeta * w / wd * s), e * s / wd, -e * w * w / wd * s,
        e * (c - zeta * w / wd * s);
    EXPECT_LT((d.Phi - phi).cwiseAbs().maxCoeff(), 1e-14) << "dt = " << dt;
    // Discrete Lyapunov: the stationary covariance is kept.
    EXPECT_LT(max_rel_diff(d.Phi * p_inf * d.Phi.transpose() + d.Qd, p_inf), 1e-14)
        << "dt = " << dt;
  }
}

TEST(StateSpace, LongStepsStayFiniteBySubstepping) {
  const double var = kGmSigma * kGmSigma;
  // theory.md §6.2 caveat: T_c = 15 s, Δt = 3000 s gave NaN in a single Van Loan step.
  const DiscreteStateModel d = discretize(gauss_markov_state(kGmSigma, 15.0, "bg"), 3000.0);
  ASSERT_TRUE(d.Phi.allFinite() && d.Qd.allFinite());
  EXPECT_GE(d.Phi(0, 0), 0.0);
  EXPECT_NEAR(d.Phi(0, 0) / std::exp(-200.0), 1.0, 1e-12);
  EXPECT_NEAR(d.Qd(0, 0) / var, 1.0, 1e-12);
  EXPECT_EQ(d.method, "van loan, 2^8 substeps");

  const DiscreteStateModel far = discretize(gauss_markov_state(kGmSigma, 15.0, "bg"), 1e6);
  ASSERT_TRUE(far.Phi.allFinite() && far.Qd.allFinite());
  EXPECT_GE(far.Phi(0, 0), 0.0);
  EXPECT_LT(far.Phi(0, 0), 1e-300);
  EXPECT_NEAR(far.Qd(0, 0) / var, 1.0, 1e-12);
  EXPECT_NE(far.method.find("substeps"), std::string::npos) << far.method;

  // White limit: T_c = 1 µs at Δt = 1 s, Q_c = 2σ²/T_c is huge, Q_d → σ².
  const DiscreteStateModel white = discretize(gauss_markov_state(kGmSigma, 1e-6, "bg"), 1.0);
  ASSERT_TRUE(white.Phi.allFinite() && white.Qd.allFinite());
  EXPECT_NEAR(white.Qd(0, 0) / var, 1.0, 1e-12);
  EXPECT_EQ(white.method, "van loan, 2^20 substeps");
}

TEST(StateSpace, BlockDiagonalDiscretizesBlockwise) {
  const std::array<ContinuousStateModel, 3> blocks{random_walk_state(kExampleK, "ba"),
                                                   gauss_markov_state(kGmSigma, kGmTauC, "bg"),
                                                   angle_bias_state(kExampleN, kExampleK, "gx")};
  const ContinuousStateModel all = block_diagonal(blocks);
  ASSERT_EQ(all.states(), 4);
  EXPECT_EQ(all.state_names, (std::vector<std::string>{"ba", "bg", "gx_angle", "gx_bias"}));
  EXPECT_EQ(all.noise_names,
            (std::vector<std::string>{"ba_driving_noise", "bg_driving_noise",
                                      "gx_angle_white_noise", "gx_bias_driving_noise"}));
  // The GM block forces substeps at Δt = 100 s that the other blocks alone would not take.
  for (const double dt : {0.005, 1.0, 100.0}) {
    const DiscreteStateModel d = discretize(all, dt);
    Eigen::MatrixXd phi = Eigen::MatrixXd::Zero(4, 4), qd = Eigen::MatrixXd::Zero(4, 4);
    int r = 0;
    for (const ContinuousStateModel& b : blocks) {
      const DiscreteStateModel db = discretize(b, dt);
      const auto n = db.Phi.rows();
      phi.block(r, r, n, n) = db.Phi;
      qd.block(r, r, n, n) = db.Qd;
      r += static_cast<int>(n);
    }
    EXPECT_LT(max_rel_diff(d.Phi, phi), 1e-12) << "dt = " << dt;
    EXPECT_LT(max_rel_diff(d.Qd, qd), 1e-12) << "dt = " << dt;
    // Blocks with small entries must not be swamped: compare the RW block on its own scale.
    EXPECT_NEAR(d.Qd(0, 0) / (kExampleK * kExampleK * dt), 1.0, 1e-12) << "dt = " << dt;
    EXPECT_EQ(d.Qd, d.Qd.transpose());
  }
}

TEST(StateSpace, ConstructorsFollowTheory61Table) {
  const ContinuousStateModel rc = random_constant_state(3.0, "sg");
  EXPECT_EQ(rc.F, Eigen::MatrixXd::Zero(1, 1));
  EXPECT_EQ(rc.G, Eigen::MatrixXd::Zero(1, 1));
  EXPECT_EQ(rc.Qc, Eigen::MatrixXd::Zero(1, 1));
  EXPECT_EQ(rc.initial_variance(0), 9.0);
  EXPECT_EQ(rc.state_names, std::vector<std::string>{"sg"});
  EXPECT_EQ(rc.noise_names, std::vector<std::string>{"sg_driving_noise"});
  const DiscreteStateModel rcd = discretize(rc, 10.0);
  EXPECT_EQ(rcd.Phi, Eigen::MatrixXd::Ones(1, 1));
  EXPECT_EQ(rcd.Qd, Eigen::MatrixXd::Zero(1, 1));

  const ContinuousStateModel gm = gauss_markov_state(2.0, 4.0, "bg");
  EXPECT_EQ(gm.F(0, 0), -0.25);
  EXPECT_EQ(gm.G(0, 0), 1.0);
  EXPECT_EQ(gm.Qc(0, 0), 2.0);  // 2σ²/T_c
  EXPECT_EQ(gm.initial_variance(0), 4.0);

  const ContinuousStateModel gm2 = second_order_gauss_markov_state(2.0, 0.5, 0.3, "vib");
  EXPECT_EQ(gm2.state_names, (std::vector<std::string>{"vib", "vib_rate"}));
  EXPECT_EQ(gm2.noise_names, std::vector<std::string>{"vib_driving_noise"});
  EXPECT_DOUBLE_EQ(gm2.Qc(0, 0), 4.0 * 0.3 * 0.125 * 4.0);  // 4ζω_n³σ²

  // Ramp: e^{FΔt} = I + FΔt exactly (F nilpotent), no noise; Φ P₀ Φᵀ grows the bias as R·Δt.
  const double ramp = 1e-5, dt = 7.0;
  const ContinuousStateModel rm = ramp_state(ramp, "bg");
  EXPECT_EQ(rm.state_names, (std::vector<std::string>{"bg", "bg_slope"}));
  EXPECT_EQ(rm.initial_variance, Eigen::Vector2d(0.0, ramp * ramp));
  const DiscreteStateModel rmd = discretize(rm, dt);
  EXPECT_EQ(rmd.Phi, (Eigen::Matrix2d() << 1.0, dt, 0.0, 1.0).finished());
  EXPECT_EQ(rmd.Qd, Eigen::MatrixXd::Zero(2, 2));
  const Eigen::MatrixXd p1 =
      rmd.Phi * Eigen::MatrixXd(rm.initial_variance.asDiagonal()) * rmd.Phi.transpose();
  EXPECT_NEAR(std::sqrt(p1(0, 0)), ramp * dt, 1e-20);

  const ContinuousStateModel ab = angle_bias_state(kExampleN, kExampleK, "gx");
  EXPECT_EQ(ab.G, Eigen::MatrixXd::Identity(2, 2));
  EXPECT_EQ(
      ab.Qc,
      Eigen::Vector2d(kExampleN * kExampleN, kExampleK * kExampleK).asDiagonal().toDenseMatrix());
}

TEST(StateSpace, EmptyModelDiscretizesToEmptyMatrices) {
  const ContinuousStateModel none = block_diagonal({});
  EXPECT_EQ(none.states(), 0);
  const DiscreteStateModel d = discretize(none, 1.0);
  EXPECT_EQ(d.Phi.size(), 0);
  EXPECT_EQ(d.Qd.size(), 0);
  EXPECT_TRUE(d.state_names.empty());
}

/// Sample mean and covariance of M realizations stored as columns.
struct SampleMoments {
  Eigen::VectorXd mean;
  Eigen::MatrixXd cov;  ///< with the 1/(M − 1) normalization
};

SampleMoments moments(const Eigen::MatrixXd& x) {
  const Eigen::VectorXd mean = x.rowwise().mean();
  const Eigen::MatrixXd centred = x.colwise() - mean;
  return {mean, centred * centred.transpose() / static_cast<double>(x.cols() - 1)};
}

/// Expects every element of the sample mean and covariance within 4 standard errors (plus the
/// scheme's known bias) of the truth; see the file comment.
void expect_within_4_se(const SampleMoments& s, const Eigen::VectorXd& mean,
                        const Eigen::MatrixXd& q, const Eigen::MatrixXd& scheme_bias, int m) {
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    EXPECT_LT(std::abs(s.mean(i) - mean(i)), 4.0 * std::sqrt(q(i, i) / m)) << "mean " << i;
    for (Eigen::Index j = 0; j < q.cols(); ++j) {
      const double se = std::sqrt((q(i, i) * q(j, j) + q(i, j) * q(i, j)) / (m - 1));
      EXPECT_LT(std::abs(s.cov(i, j) - q(i, j)), 4.0 * se + std::abs(scheme_bias(i, j)))
          << "cov " << i << "," << j << ": sample " << s.cov(i, j) << " vs " << q(i, j) << ", se "
          << se;
    }
  }
}

constexpr int kRealizations = 20000;  // M one-step realizations

TEST(StateSpace, GaussMarkovMonteCarloMatchesQd) {
  const double sigma = kGmSigma, tau = kGmTauC, dt = 20.0, x0 = 2.0 * kGmSigma;
  const DiscreteStateModel d = discretize(gauss_markov_state(sigma, tau, "bg"), dt);
  const Eigen::VectorXd mean = d.Phi * Eigen::VectorXd::Constant(1, x0);  // x0 ≠ 0 tests Φ too
  std::mt19937_64 rng(20240611);
  std::normal_distribution<double> normal;

  // Substep counts are kept small for run time (M·n normal draws, ≈ 1 s for the file): (a) is
  // exact for any n, and the O(h) bias of (b) is computed exactly and allowed for.
  // (a) Exact fine steps h = Δt/200: one AR(1) step is exact for GM, and exact steps compose.
  {
    const int n = 200;
    const double h = dt / n, a = std::exp(-h / tau),
                 s = sigma * std::sqrt(-std::expm1(-2 * h / tau));
    Eigen::MatrixXd x(1, kRealizations);
    for (int r = 0; r < kRealizations; ++r) {
      double v = x0;
      for (int j = 0; j < n; ++j) v = a * v + s * normal(rng);
      x(0, r) = v;
    }
    expect_within_4_se(moments(x), mean, d.Qd, Eigen::MatrixXd::Zero(1, 1), kRealizations);
  }
  // (b) Euler–Maruyama with 400 substeps: independent of any exponential. Its variance
  // q·h·(1 − c^{2n})/(1 − c²), c = 1 − h/T_c, differs from Q_d by O(h/T_c); that bias is
  // added to the tolerance (here ≈ 2e-3·Q_d, far below 4 standard errors ≈ 0.04·Q_d), and its
  // mean c^n·x₀ is shifted to Φx₀.
  {
    const int n = 400;
    const double h = dt / n, c = 1.0 - h / tau, q = 2.0 * sigma * sigma / tau;
    const double sq = std::sqrt(q * h);
    Eigen::MatrixXd x(1, kRealizations);
    for (int r = 0; r < kRealizations; ++r) {
      double v = x0;
      for (int j = 0; j < n; ++j) v = c * v + sq * normal(rng);
      x(0, r) = v;
    }
    const double em_var = q * h * (1.0 - std::pow(c, 2 * n)) / (1.0 - c * c);
    const double em_mean_bias = (std::pow(c, n) - d.Phi(0, 0)) * x0;
    EXPECT_LT(std::abs(em_var / d.Qd(0, 0) - 1.0), 5e-3);
    SampleMoments s = moments(x);
    s.mean(0) -= em_mean_bias;
    expect_within_4_se(s, mean, d.Qd, Eigen::MatrixXd::Constant(1, 1, em_var - d.Qd(0, 0)),
                       kRealizations);
  }
}

TEST(StateSpace, RandomWalkMonteCarloMatchesQd) {
  // Sum of 100 independent N(0, K²h) increments: exact for a Wiener process.
  const double dt = 100.0;
  const int n = 100;
  const DiscreteStateModel d = discretize(random_walk_state(kExampleK, "bg"), dt);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  const double s = kExampleK * std::sqrt(dt / n);
  Eigen::MatrixXd x(1, kRealizations);
  for (int r = 0; r < kRealizations; ++r) {
    double v = 0.0;
    for (int j = 0; j < n; ++j) v += s * normal(rng);
    x(0, r) = v;
  }
  expect_within_4_se(moments(x), Eigen::VectorXd::Zero(1), d.Qd, Eigen::MatrixXd::Zero(1, 1),
                     kRealizations);
}

TEST(StateSpace, AngleBiasMonteCarloMatchesQd) {
  // Δt = 100 s > τ_min = √3N/K = 29.6 s, so the K²Δt³/3 term dominates the angle variance
  // and the correlation Q₁₂/√(Q₁₁Q₂₂) ≈ 0.82: every element of Q_d matters.
  const double dt = 100.0;
  const int n = 200;
  const double h = dt / n;
  const DiscreteStateModel d = discretize(angle_bias_state(kExampleN, kExampleK, "gx"), dt);
  std::mt19937_64 rng(42);
  std::normal_distribution<double> normal;
  const double sn = kExampleN * std::sqrt(h), sk = kExampleK * std::sqrt(h);
  Eigen::MatrixXd x(2, kRealizations);
  for (int r = 0; r < kRealizations; ++r) {
    double theta = 0.0, b = 0.0;
    for (int j = 0; j < n; ++j) {  // Euler–Maruyama: θ uses the bias at the start of the step
      theta += b * h + sn * normal(rng);
      b += sk * normal(rng);
    }
    x(0, r) = theta;
    x(1, r) = b;
  }
  // Exact Euler–Maruyama moments: Var θ = N²Δt + K²h³·Σ_{m<n} m², Cov = K²h²·Σ_{m<n} m.
  const double k2 = kExampleK * kExampleK, nn = n;
  Eigen::Matrix2d em;
  em << kExampleN * kExampleN * dt + k2 * h * h * h * (nn - 1) * nn * (2 * nn - 1) / 6.0,
      k2 * h * h * nn * (nn - 1) / 2.0, k2 * h * h * nn * (nn - 1) / 2.0, k2 * dt;
  EXPECT_LT(max_rel_diff(em, d.Qd), 1e-2);  // the scheme's O(h) bias is small
  expect_within_4_se(moments(x), Eigen::VectorXd::Zero(2), d.Qd, em - d.Qd, kRealizations);
}

TEST(StateSpace, QdIsSymmetricPositiveSemidefinite) {
  const std::array<ContinuousStateModel, 6> models{
      random_walk_state(kExampleK, "a"),
      random_constant_state(1.0, "b"),
      gauss_markov_state(kGmSigma, kGmTauC, "c"),
      second_order_gauss_markov_state(2.0, 0.5, 0.3, "d"),
      ramp_state(1e-5, "e"),
      angle_bias_state(kExampleN, kExampleK, "f")};
  for (const double dt : {0.005, 1.0, 3000.0}) {
    const DiscreteStateModel d = discretize(block_diagonal(models), dt);
    EXPECT_EQ(d.Qd, d.Qd.transpose());
    const Eigen::VectorXd eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(d.Qd).eigenvalues();
    EXPECT_GE(eig.minCoeff(), -1e-15 * d.Qd.cwiseAbs().maxCoeff()) << "dt = " << dt;
  }
}

TEST(StateSpace, BadArgumentsAreContractViolations) {
  using test::expect_throw_containing;
  using E = ContractViolation;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const ContinuousStateModel rw = random_walk_state(1.0, "bg");
  expect_throw_containing<E>([] { random_walk_state(-1.0, "bg"); }, "random_walk_state");
  expect_throw_containing<E>([] { random_walk_state(-1.0, "bg"); }, "got -1");
  expect_throw_containing<E>([] { random_constant_state(-2.0, "s"); }, "random_constant_state");
  expect_throw_containing<E>([] { gauss_markov_state(1.0, 0.0, "bg"); }, "tau_c");
  expect_throw_containing<E>([] { gauss_markov_state(-1.0, 1.0, "bg"); }, "sigma");
  expect_throw_containing<E>([] { second_order_gauss_markov_state(1.0, 0.0, 0.3, "v"); },
                             "omega_n");
  expect_throw_containing<E>([] { second_order_gauss_markov_state(1.0, 1.0, -0.1, "v"); }, "zeta");
  expect_throw_containing<E>([&] { angle_bias_state(1.0, nan, "gx"); }, "got nan");
  expect_throw_containing<E>([] { ramp_state(-1.0, "bg"); }, "ramp_state");
  expect_throw_containing<E>([&] { discretize(rw, 0.0); }, "discretize: dt");
  expect_throw_containing<E>([&] { discretize(rw, nan); }, "got nan");
  expect_throw_containing<E>([&] { discretize(rw, -1.0); }, "got -1");
  expect_throw_containing<E>([] { gauss_markov_discrete(1.0, 1.0, 0.0, "bg"); },
                             "gauss_markov_discrete");
  expect_throw_containing<E>([] { gauss_markov_discrete(1.0, 0.0, 1.0, "bg"); }, "tau_c");
  expect_throw_containing<E>([] { random_walk_discrete(-1.0, 1.0, "bg"); }, "random_walk_discrete");
  expect_throw_containing<E>([&] { angle_bias_discrete(1.0, 1.0, nan, "gx"); },
                             "angle_bias_discrete");
  expect_throw_containing<E>([] { white_noise_rate_sigma(1.0, 0.0); }, "white_noise_rate_sigma");
  expect_throw_containing<E>([] { white_noise_increment_sigma(-1.0, 1.0); },
                             "white_noise_increment_sigma");

  ContinuousStateModel bad = rw;
  bad.G = Eigen::MatrixXd::Ones(2, 1);
  expect_throw_containing<E>([&] { discretize(bad, 1.0); }, "discretize: G");
  bad = rw;
  bad.Qc = Eigen::MatrixXd::Ones(2, 2);
  expect_throw_containing<E>([&] { discretize(bad, 1.0); }, "Qc");
  bad = rw;
  bad.F(0, 0) = nan;
  expect_throw_containing<E>([&] { discretize(bad, 1.0); }, "finite");
  bad = rw;
  bad.noise_names.clear();
  const std::array<ContinuousStateModel, 2> blocks{rw, bad};
  expect_throw_containing<E>([&] { block_diagonal(blocks); }, "block_diagonal: block 1");
}

}  // namespace
}  // namespace imunoise::models
