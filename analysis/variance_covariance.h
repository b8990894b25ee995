/// @file
/// @brief The joint distribution of the overlapping Allan (or Hadamard) variance estimates of
/// one record under a noise model: their expectations, their covariance across averaging
/// factors and the EDF of each (theory.md §3.5: neighbouring τ are strongly correlated).
///
/// Each estimate is a quadratic form of the phase: σ̂²(m) = Σ_k d_k²/(c·m²τ0²·N_m), with d_k
/// the second (third) difference of the phase at lag m, c = 2 (6) and N_m = M − 2m (M − 3m)
/// terms for M = n + 1 phase samples. For a Gaussian process with a deterministic part μ,
/// Cov(d1_j², d2_k²) = 2·R12(k − j)² + 4·μ1_j·μ2_k·R12(k − j), R12 the cross-covariance of the
/// two difference sequences. R12 follows from the generalized covariance G(s) of the phase
/// (differences of order ≥ 2 annihilate its polynomial part), in closed form per term:
///   Q: Q²·[s = 0];  N: −N²|s|/2;  B: (B²/2π)·s²·ln|s|;  K: K²|s|³/12;
///   GM (σ, T_c): −σ²T_c²·(x + e^{−x} − 1 − x²/2), x = |s|/T_c;
/// the ramp and sinusoids are the deterministic part. Each G reproduces the AVAR and HVAR laws
/// of theory.md §4.1 (for B: the f₀ → ∞ limit). The double sum over lags is evaluated exactly
/// over the integer lags of short stretches and by Gauss–Legendre quadrature over long ones
/// (R12 is smooth between the lags a − b where a filter tap of one meets a tap of the other).
/// Cost: O(points² × taps² × a few hundred) — milliseconds for a 60-point curve, independent of
/// the record length.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "common/noise_coefficients.h"

namespace imunoise::analysis {

/// The expectations, covariance and EDF of the estimates at a list of averaging factors.
struct VarianceCovariance {
  std::vector<double> expected;  ///< E[σ̂²(m_i)] [rate unit²]
  Eigen::MatrixXd covariance;    ///< Cov(σ̂²(m_i), σ̂²(m_j)) [rate unit⁴]
  std::vector<double> edf;  ///< 2·E[σ̂²]²/Var(σ̂²): the EDF of each estimate under MODEL
};

/// The joint moments of the overlapping AVAR (HADAMARD: OHVAR) estimates at the averaging
/// factors M_LIST of a record of N_RATE_SAMPLES rate samples at τ0 = TAU0_S, for data that
/// follow MODEL (Q, N, B, K, GM: Gaussian; R and sinusoids: deterministic). Sinusoids enter the
/// expectation exactly and the covariance through their cross term with the noise, evaluated
/// with the noise spectrum at their frequency (theory.md §4.1 S_Ω, without the sampling sinc²).
/// @throws ContractViolation when τ0 ≤ 0, an m is < 1 or leaves fewer than 1 term, or MODEL
///   has a negative coefficient.
/// The correlation matrix of MOMENTS.covariance; a point without variance under the model (a
/// deterministic term alone) is uncorrelated, with a unit diagonal.
Eigen::MatrixXd correlation_matrix(const VarianceCovariance& moments);

/// The lower Cholesky factor of the correlation matrix CORRELATION. Neighbouring τ of a dense
/// grid correlate to within rounding of 1: a ridge of up to 1e−9 of the diagonal keeps the
/// factor real (invisible in any draw or fit); should rounding still leave it indefinite, the
/// factor of the nearest positive definite matrix (eigenvalues clipped, unit diagonal
/// restored).
Eigen::MatrixXd correlation_factor(const Eigen::MatrixXd& correlation);

/// The estimates of MOMENTS drawn from their joint distribution: each σ̂²_i = E_i·χ²_ν/ν (ν the
/// EDF under the model; exact quantiles below ν = 50, Wilson–Hilferty above) at the normal
/// score z = Lu, L the correlation_factor and u independent standard normals — a Gaussian
/// copula with the model's correlation across τ. The interval draws of pipeline/bootstrap.
class VarianceDraw {
 public:
  explicit VarianceDraw(VarianceCovariance moments);
  std::size_t size() const { return moments_.expected.size(); }
  /// One draw into AVAR (size()) from NORMALS (size() independent standard normals).
  void draw(std::span<const double> normals, std::span<double> avar) const;

 private:
  VarianceCovariance moments_;
  Eigen::MatrixXd factor_;
};

VarianceCovariance overlapping_variance_covariance(const NoiseCoefficients& model, double tau0_s,
                                                   std::int64_t n_rate_samples,
                                                   std::span<const std::int64_t> m_list,
                                                   bool hadamard = false);

}  // namespace imunoise::analysis
