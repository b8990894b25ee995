/// @file
/// @brief Predicted drift of a stationary free-inertial INS by covariance propagation
/// (theory.md §7.6): the error-state model of ins/error_state_model.h at a stationary
/// nominal, exact Φ and Q_d once (F is constant at rest), P_{k+1} = ΦP_kΦᵀ + Q_d, and the
/// horizontal position, velocity and attitude σ at the requested times. P₀ is either zero
/// (the "errors start at 0" method of theory.md §8.4) or that left by a stationary alignment
/// of length T_a (leveling + gyro-bias removal, theory.md §7.3, §7.6).
#pragma once

#include <array>
#include <cstddef>
#include <string_view>
#include <vector>

#include "common/units.h"
#include "ins/error_state_model.h"

namespace imunoise::ins {

/// The sources of the drift budget (DriftPrediction::horizontal_variance_budget_m2).
enum class DriftBudgetTerm {
  white_noise,       ///< N of gyro and accel, during navigation (process noise)
  bias_instability,  ///< B (bias_gm and B's multi-GM terms, the first
                     ///< SensorAxisNoise::bias_instability_terms of gm_terms), during
                     ///< navigation (process noise)
  random_walk,       ///< K, during navigation (process noise)
  gauss_markov,      ///< the fitted GM terms (the rest of gm_terms), during navigation
  ramp,              ///< R: the ramp slope, whole (its alignment residual included)
  alignment,         ///< P₀ left by the alignment (window means of N, K, GM; GM start values;
                     ///< without alignment: the model's P₀ except the ramp slope)
  heading,           ///< the initial heading σ (and its Earth-rate bias-removal coupling)
};
inline constexpr std::size_t kDriftBudgetTerms = 7;
/// Variance per DriftBudgetTerm, in enum order [m²].
using DriftBudgetRow = std::array<double, kDriftBudgetTerms>;
/// Snake-case name of a budget term ("white_noise", …, "heading").
constexpr std::string_view name_of(DriftBudgetTerm term) {
  constexpr std::array<std::string_view, kDriftBudgetTerms> names{
      "white_noise", "bias_instability", "random_walk", "gauss_markov",
      "ramp",        "alignment",        "heading"};
  return names[static_cast<std::size_t>(term)];
}
/// The symbol of a budget term as the report writes it ("N", "B", "K", "GM", "R",
/// "alignment", "heading").
constexpr std::string_view symbol_of(DriftBudgetTerm term) {
  constexpr std::array<std::string_view, kDriftBudgetTerms> symbols{
      "N", "B", "K", "GM", "R", "alignment", "heading"};
  return symbols[static_cast<std::size_t>(term)];
}

struct DriftPredictionOptions {
  double latitude_rad = 45.0 * units::kDeg;  ///< L of the stationary nominal [rad]
  double height_m = 0.0;                     ///< h above the ellipsoid [m]
  double heading_rad = 0.0;                  ///< ψ of the level IMU, from north [rad]
  /// Which bias terms act (ins::BiasModel): both = RW (K, turn-on σ, ramp) and GM (B, GM
  /// terms) together; random_walk drops every GM term, gauss_markov drops K, the turn-on σ and
  /// the ramp.
  BiasModel bias = BiasModel::both;
  /// false: Ω_ie = 0 in F (no Earth-rate, Coriolis or Foucault coupling), the Schuler-only
  /// simplification of theory.md §7.5/§8.4 (ErrorStateOptions::earth_rate).
  bool earth_rate_coupling = true;
  /// Propagation step Δt [s], > 0 (Φ and Q_d are exact for any Δt; only the output grid
  /// depends on it).
  double step_s = 1.0;
  /// Output times [s]: finite, > 0, sorted (non-decreasing), each a whole number of steps
  /// (within 1e-9 relative); at most 1e8 steps in all.
  std::vector<double> times_s;
  /// Length T_a of the stationary alignment before navigation [s], ≥ 0; 0 = no alignment:
  /// P₀ = the model's (turn-on σ², GM σ²) and navigation errors start at 0 (theory.md §8.4).
  double alignment_time_s = 0.0;
  /// σ of the initial heading error δψ_D [rad], ≥ 0 (a given heading's uncertainty or a
  /// gyrocompass σ), taken independent of everything else.
  double heading_sigma_rad = 0.0;
  /// true: also fill DriftPrediction::horizontal_variance_budget_m2 (7 more propagations).
  bool budget = false;
};

/// 1σ predictions at each output time (all vectors as long as time_s).
struct DriftPrediction {
  std::vector<double> time_s;  ///< the requested times [s]
  /// @name Position error [m]
  /// @{
  std::vector<double> north_sigma_m, east_sigma_m;
  std::vector<double> horizontal_drms_m;  ///< √(σ_N² + σ_E²)
  /// @}
  std::vector<double> velocity_horizontal_drms_m_per_s;  ///< √(σ_vN² + σ_vE²) [m/s]
  /// @name Attitude error [rad]: small-angle roll, pitch, heading errors of the level IMU,
  /// (δφ, δθ, δψ) = C_nb δψ^n, i.e. δψ N, E, D rotated into the body axes by the heading
  /// @{
  std::vector<double> roll_sigma_rad, pitch_sigma_rad, heading_sigma_rad;
  /// @}
  /// With DriftPredictionOptions::budget: σ_N² + σ_E² split by source (DriftBudgetTerm), one
  /// row per time; the sources are independent, so each row sums to horizontal_drms_m² (to
  /// rounding). Empty otherwise.
  std::vector<DriftBudgetRow> horizontal_variance_budget_m2;
};

/// Covariance propagation of the stationary INS error state for NOISE under OPTIONS.
///
/// Model: ins_error_state_model(stationary_nominal(L, h, ψ), NOISE, {bias = both,
/// height_hold = true, earth_rate = options.earth_rate_coupling}) — the vertical channel is
/// held, as in every stationary analysis (theory.md §7.2); the BiasModel option zeroes the
/// dropped terms instead of changing the layout, so an RW state (F = 0) is always there to
/// hold the constant parts of P₀. Scale factors are not modelled (at rest they act only
/// through s_a on the held vertical and s_g times Earth rate, theory.md §6.3).
///
/// Every GM term (bias_gm and gm_terms) is its own state, each ramp R a slope state (P₀ = R²)
/// integrated by the RW bias state; the alignment formulas below apply per GM term (the terms
/// are independent, so their contributions add) and the ramp leaves its window mean minus end
/// value, ∓R·T_a/2 (see aligned_initial_covariance in the .cpp).
///
/// P₀ with alignment (T_a > 0), per theory.md §7.6; every term is exact for the linear model:
/// - Leveling zeroes the mean horizontal specific force, so the tilt cancels the window mean
///   of the accel error. Written relative to the RW bias at the end of the window (the
///   accel RW state then starts at 0 and grows by Q_d alone), the equivalent tilt is
///   δψ_E = e_N/g, δψ_N = −e_E/g with e = C_bn(white mean + RW mean − RW end + GM mean):
///   per horizontal axis Var = (N_a²/T_a + K_a²T_a/3 + Var m_GM)/g², i.e. the σ of the accel
///   mean over T_a divided by g. The turn-on accel bias cancels exactly and does not appear
///   (so the roll/pitch σ reported are this equivalent tilt, which is what drives the
///   position error; the true tilt also holds the unknowable constant accel bias / g).
/// - Gyro-bias removal b̂_g = ω̄ − Ĉ_nb ω_ie^n leaves on the gyro RW state
///   N_g²/T_a + K_g²T_a/3 + Var m_GM (window mean of white noise, RW end minus RW mean, GM
///   mean); the later K_g²t growth comes from Q_d and is not added twice. The turn-on gyro
///   bias cancels. With Earth-rate coupling the removal used the erroneous attitude, which
///   adds C_nb [ω_ie×] δψ₀ to that state: the navigator is self-consistent and an attitude
///   error alone causes no drift at rest (theory.md §7.3).
/// - GM states (both sensors) at their stationary σ², correlated with the window mean they
///   fed: Cov(m_GM, b_GM(T_a)) = σ²(1 − e^{−x})/x, Var m_GM = (2σ²/x)(1 − (1 − e^{−x})/x),
///   x = T_a/T_c (from the autocovariance σ²e^{−|τ|/T_c}).
/// - Heading: heading_sigma_rad², independent. Velocity, position: 0.
///
/// P₀ without alignment: the model's initial variance (turn-on σ² on the RW states, GM σ²
/// stationary, R² on ramp slopes) plus heading_sigma_rad² on δψ_D; navigation errors 0
/// (theory.md §8.4).
///
/// Budget (options.budget): each DriftBudgetTerm propagated alone (linear system, independent
/// sources); the correlated (window mean, end value) pair of a GM term, and the Earth-rate
/// coupling of an attitude error into the gyro-bias residual, stay inside the group of their
/// source, so no cross-term is left to assign and the rows sum to the variance.
///
/// @throws InputError for a bad nominal (as stationary_nominal()), bad noise (as
///   ins_error_state_model()), step_s not finite and > 0, times not finite, > 0, sorted and
///   whole multiples of step_s (or more than 1e8 steps), alignment_time_s or
///   heading_sigma_rad negative or not finite.
DriftPrediction predict_stationary_drift(const InsSensorNoise& noise,
                                         const DriftPredictionOptions& options);

}  // namespace imunoise::ins
