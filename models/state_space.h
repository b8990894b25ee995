/// @file
/// @brief Linear stochastic state models of sensor errors and their exact discretization
/// (theory.md §6.1–6.2): ẋ = F x + G w, E[w(t) w(s)ᵀ] = Q_c δ(t − s), and the discrete
/// x_{k+1} = Φ x_k + w_k, E[w_k w_kᵀ] = Q_d over a step Δt. SI units throughout; every
/// state is labelled with its name and unit so exported matrices can be read by a person.
#pragma once

#include <Eigen/Dense>
#include <span>
#include <string>
#include <vector>

namespace imunoise::models {

/// Continuous-time model ẋ = F x + G w with white w of intensity Q_c (theory.md §6.1).
struct ContinuousStateModel {
  Eigen::MatrixXd F;                 ///< n×n dynamics [1/s]
  Eigen::MatrixXd G;                 ///< n×p noise input
  Eigen::MatrixXd Qc;                ///< p×p noise intensity (symmetric, ≥ 0) [state unit² / s]
  Eigen::VectorXd initial_variance;  ///< n: P₀ diagonal (random constants, GM σ², …)
  std::vector<std::string> state_names;  ///< n labels with unit, e.g. "bias_rw_rad_per_s"
  std::vector<std::string> noise_names;  ///< p labels, e.g. "bias_rw_driving_noise"

  int states() const { return static_cast<int>(F.rows()); }
};

/// Discrete model over one step Δt: x_{k+1} = Φ x_k + w_k, Cov w_k = Q_d.
struct DiscreteStateModel {
  Eigen::MatrixXd Phi;  ///< n×n transition
  Eigen::MatrixXd Qd;   ///< n×n process noise covariance (symmetric, ≥ 0)
  std::vector<std::string> state_names;
  double dt_s = 0.0;   ///< the step Δt [s]
  std::string method;  ///< "closed form", "van loan", "van loan, 2^k substeps"
};

/// @name Single-term continuous models (theory.md §6.1 table)
/// Labels are NAME plus a fixed suffix (NAME is used verbatim, so put a unit in it if wanted):
/// the states are listed per function, and every driving noise is NAME + "_driving_noise"
/// (angle_bias_state: NAME + "_angle_white_noise", NAME + "_bias_driving_noise").
/// @throws ContractViolation "FUNCTION: WHAT must be finite and >= 0 (got VALUE)" for a
/// negative or non-finite coefficient, "... > 0 ..." for T_c, ω_n or ζ ≤ 0.
/// @{

/// Random walk ḃ = K·w: F = 0, G = 1, Q_c = K². K ≥ 0 [unit/√s]. State NAME.
ContinuousStateModel random_walk_state(double random_walk, const std::string& name);
/// Random constant ḃ = 0 with P₀ = σ₀² (turn-on bias, scale factor); G = 0, Q_c = 0 (p = 1,
/// zero, so the noise column can still be labelled). State NAME.
ContinuousStateModel random_constant_state(double sigma0, const std::string& name);
/// First-order Gauss–Markov: F = −1/T_c, G = 1, Q_c = 2σ²/T_c, P₀ = σ². σ ≥ 0, T_c > 0.
/// State NAME.
ContinuousStateModel gauss_markov_state(double sigma, double tau_c_s, const std::string& name);
/// Second-order GM [x, ẋ]: F = [[0,1],[−ω_n², −2ζω_n]], G = [0,1]ᵀ, Q_c = 4ζω_n³σ²,
/// stationary Var x = σ² (P₀ = the stationary covariance diag(σ², ω_n²σ²)). ω_n > 0, ζ > 0.
/// States NAME, NAME + "_rate".
ContinuousStateModel second_order_gauss_markov_state(double sigma, double omega_n_rad_per_s,
                                                     double zeta, const std::string& name);
/// Rate ramp as [bias, slope] with a random-constant slope: F = [[0,1],[0,0]], Q_c = 0,
/// P₀ = diag(0, R²) — the deterministic drift R·t whose AVAR is R²τ²/2 (theory.md §4.1).
/// G = 0 (2×1) as in random_constant_state(). States NAME, NAME + "_slope".
ContinuousStateModel ramp_state(double ramp, const std::string& name);
/// Angle + random-walk bias [θ, b]: F = [[0,1],[0,0]], G = I, Q_c = diag(N², K²).
/// States NAME + "_angle", NAME + "_bias".
ContinuousStateModel angle_bias_state(double white_noise, double random_walk,
                                      const std::string& name);

/// @}

/// Block-diagonal assembly (states and noises concatenated in order); an empty span gives a
/// model with 0 states.
/// @throws ContractViolation when a block's F, G, Q_c, P₀ or labels disagree in size, or
/// F, G, Q_c hold a non-finite entry ("block_diagonal: block I: ...").
ContinuousStateModel block_diagonal(std::span<const ContinuousStateModel> blocks);

/// @name Discretization (theory.md §6.2)
/// @{

/// Exact Φ = e^{FΔt} and Q_d = ∫₀^Δt e^{Fs} G Q_c Gᵀ e^{Fᵀs} ds by Van Loan's method. The
/// direct form overflows when Δt ≫ the fastest time constant (e^{−FΔt} grows like e^{Δt/T_c};
/// theory.md §6.2 caveat), so the step is split into 2^k substeps, k ≥ 0 minimal with
/// ‖F‖_∞·h ≤ 1, each done by Van Loan, and recombined by doubling (Φ₂ = Φ², Q₂ = ΦQΦᵀ + Q):
/// never NaN for finite inputs, and exact to rounding. (For an unstable F, i.e. not one built
/// here, Φ can still overflow when the exact e^{FΔt} does.) Q_d is symmetrized. `method` is
/// "van loan" for k = 0, else "van loan, 2^k substeps" with k as a number. A 0-state model
/// gives 0×0 matrices. state_names may be empty (then copied empty).
/// @throws ContractViolation when Δt ≤ 0 or not finite, when the matrices disagree in
/// size or hold a non-finite entry, or when G Q_c Gᵀ overflows.
DiscreteStateModel discretize(const ContinuousStateModel& model, double dt_s);

/// Closed forms (theory.md §6.2): RW Φ = 1, Q_d = K²Δt; GM Φ = e^{−Δt/T_c},
/// Q_d = σ²(1 − e^{−2Δt/T_c}) (computed with expm1 so it stays accurate for Δt ≪ T_c);
/// [θ, b] Φ = [[1,Δt],[0,1]], Q_d = [[N²Δt + K²Δt³/3, K²Δt²/2],[K²Δt²/2, K²Δt]].
/// Labels and validation as the continuous constructors; method "closed form".
/// @throws ContractViolation for Δt ≤ 0 or not finite, or a bad coefficient.
DiscreteStateModel random_walk_discrete(double random_walk, double dt_s, const std::string& name);
DiscreteStateModel gauss_markov_discrete(double sigma, double tau_c_s, double dt_s,
                                         const std::string& name);
DiscreteStateModel angle_bias_discrete(double white_noise, double random_walk, double dt_s,
                                       const std::string& name);

/// Per-sample σ of white noise of density N for a filter that consumes rates: N/√Δt; and
/// the per-step σ of the angle (or velocity) increment: N·√Δt (theory.md §6.2).
/// @throws ContractViolation for N < 0, Δt ≤ 0 or either not finite.
double white_noise_rate_sigma(double white_noise, double dt_s);
double white_noise_increment_sigma(double white_noise, double dt_s);

/// @}

}  // namespace imunoise::models
