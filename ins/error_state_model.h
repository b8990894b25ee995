/// @file
/// @brief Linearized continuous-time INS error-state model in NED (theory.md §6.3, §7.4;
/// Groves 2013 §14.2.4 eqs. 14.64–14.71): ẋ = F x + G w about a nominal trajectory point,
/// with the IMU noise of a fitted model as white inputs and bias/scale-factor states.
///
/// Conventions (one sheet, used by every block):
/// - C_bn maps body (FRD) vectors into NED: x^n = C_bn x^b.
/// - Every error is estimate − truth. The attitude error δψ ("phi" angle, body w.r.t. the
///   true n-frame, resolved in n) is defined by Ĉ_bn = (I + [δψ×]) C_bn to first order.
/// - Sensor errors are measured − true: δω = ω̃_ib^b − ω_ib^b = b_g + diag(ω_ib^b) s_g + n_g,
///   δf = f̃_ib^b − f_ib^b = b_a + diag(f_ib^b) s_a + n_a; they enter as δψ̇ += C_bn δω and
///   δv̇ += C_bn δf (theory.md §7.4). A positive gyro bias on the body axis pointing east
///   thus tilts δψ_E positive and drives δv_N = −g·δψ_E·t negative.
/// - Position error in metres NED: δr_N = (R_N+h)δL, δr_E = (R_E+h)cosL δλ, δr_D = −δh.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include "common/noise_coefficients.h"
#include "models/state_space.h"

namespace imunoise::ins {

/// The trajectory point the errors are linearized about (SI; latitude geodetic, |L| < π/2).
struct NominalState {
  double latitude_rad = 0.0;                                   ///< L [rad]
  double height_m = 0.0;                                       ///< h above the ellipsoid [m]
  Eigen::Vector3d v_ned_m_per_s = Eigen::Vector3d::Zero();     ///< v_eb^n [m/s]
  Eigen::Matrix3d C_bn = Eigen::Matrix3d::Identity();          ///< body (FRD) → NED, orthonormal
  Eigen::Vector3d f_ib_b_m_per_s2 = Eigen::Vector3d::Zero();   ///< specific force f_ib^b [m/s²]
  Eigen::Vector3d w_ib_b_rad_per_s = Eigen::Vector3d::Zero();  ///< angular rate ω_ib^b [rad/s]
};

/// An IMU at rest on the Earth at (L, h), level, heading ψ from north (C_bn = R_z(ψ)):
/// v = 0, f_ib^b = C_bnᵀ(−g^n) with g^n = gravity_ned(L, h) (g_N included) and
/// ω_ib^b = C_bnᵀ ω_ie^n — the stationary nominal of theory.md §7.6.
/// @throws InputError for a latitude, height or heading that is not finite or |L| ≥ π/2.
NominalState stationary_nominal(double latitude_rad, double height_m, double heading_rad);

/// Error terms of one axis of one sensor, SI (gyro: rad…, accelerometer: m/s…); all ≥ 0.
struct SensorAxisNoise {
  double white_noise = 0.0;         ///< N, ARW/VRW density (two-sided) [rad/√s | m/s/√s]
  double random_walk = 0.0;         ///< K, bias random walk [rad/s^{3/2} | m/s^{5/2}]
  GaussMarkov bias_gm;              ///< GM bias σ [rad/s | m/s²], T_c [s] > 0; σ = 0 → none
  double turn_on_bias_sigma = 0.0;  ///< σ of the random-constant part, P₀ of the RW bias state
                                    ///< [rad/s | m/s²]
  double scale_factor_sigma = 0.0;  ///< σ_s of the scale-factor error [-] (ratio, not ppm)
  /// Correlation time T_s of the scale factor [s] > 0; ∞ = random constant.
  double scale_factor_tau_c_s = std::numeric_limits<double>::infinity();
  /// Further first-order GM bias terms (B as a sum of GMs, fitted GM terms), each its own
  /// state beside bias_gm: F = −1/T_c, Q_c = 2σ²/T_c, P₀ = σ² (theory.md §4.4, §6.1). Terms
  /// with σ = 0 get no state.
  std::vector<GaussMarkov> gm_terms{};
  /// R, rate ramp [rad/s² | m/s³] ≥ 0: an unknown constant slope s (P₀ = R², the AVAR R²τ²/2
  /// of theory.md §4.1 read as a slope of either sign with E s² = R²) integrated by the RW bias
  /// state (ḃ_RW = K w + s). 0 = no state. Not carried with BiasModel::gauss_markov (no RW
  /// state to integrate it).
  double ramp = 0.0;
  /// How many of the first gm_terms stand for B (its multi-GM representation); the rest are
  /// fitted GM terms. Only the drift budget tells them apart (ins::DriftBudgetTerm).
  std::size_t bias_instability_terms = 0;
  /// Q, angle (velocity) quantization [rad | m/s]: white noise of the integrated signal, no
  /// error state (its position effect stays bounded); read only where the per-sample scatter
  /// of the rate matters (pipeline::check_stationary: 2Q²/Δt² per sample, theory.md §4.1).
  double quantization = 0.0;
};

/// x, y, z axes (body FRD) of the gyro and the accelerometer.
struct InsSensorNoise {
  std::array<SensorAxisNoise, 3> gyro;
  std::array<SensorAxisNoise, 3> accel;
};

/// Which bias states carry the per-axis bias terms.
enum class BiasModel {
  random_walk,   ///< one RW state per axis: Q_c = K², P₀ = turn-on σ²; the GM term is dropped
  gauss_markov,  ///< one GM state per axis: F = −1/T_c, Q_c = 2σ²/T_c, P₀ = σ²; K and the
                 ///< turn-on σ are not representable and are dropped (the caller chooses)
  both           ///< RW state + GM state per axis; the bias felt by the INS is their sum
};

struct ErrorStateOptions {
  bool scale_factors = false;  ///< add s_a, s_g (6 states)
  BiasModel bias = BiasModel::random_walk;
  /// Zero the rows of δv_D and δr_D in F and G, i.e. hold the vertical channel: the
  /// stationary-analysis convention of theory.md §7.2 (the physical vertical channel is
  /// unstable, e-folding √(R/2g) ≈ 570 s). Horizontal errors are then the ones to report.
  bool height_hold = false;
  /// false: Ω_ie = 0 in the navigation block of F — no Earth-rate term in δψ̇, no Coriolis
  /// term in δv̇, no ∂ω_ie/∂L — leaving Schuler coupling only, the simplification of the
  /// single-channel analyses of theory.md §7.5 and §8.4. The nominal itself (its sensed
  /// ω_ib^b, used only by the gyro scale-factor coupling) and gravity are unchanged.
  bool earth_rate = true;
};

/// One per-axis state of SensorAxisNoise::gm_terms or ::ramp (ErrorStateLayout::axis_states).
struct AxisState {
  enum class Kind { gm_term, ramp_slope } kind = Kind::gm_term;
  bool gyro = true;  ///< gyro (true) or accelerometer axis
  int axis = 0;      ///< body x, y, z = 0, 1, 2
  int term = 0;      ///< index in gm_terms (gm_term)
  int state = 0;     ///< offset in the state vector
  int noise = 0;     ///< offset of its driving noise (zero intensity for a ramp slope)
};

/// Where each block sits in the state and noise vectors of ins_error_state_model().
/// Sizes: random_walk or gauss_markov 15, both 21; scale factors add 6 (21 or 27); then one
/// state per GM term and per ramp of the noise (axis_states), gyro x y z then accel x y z.
struct ErrorStateLayout {
  /// @name State offsets, 3 states each, the same for every option (theory.md §6.3)
  /// @{
  static constexpr int kAttitude = 0;   ///< δψ N, E, D [rad]
  static constexpr int kVelocity = 3;   ///< δv^n [m/s]
  static constexpr int kPosition = 6;   ///< δr^n [m]
  static constexpr int kAccelBias = 9;  ///< b_a x, y, z [m/s²] (RW, or GM for gauss_markov)
  static constexpr int kGyroBias = 12;  ///< b_g [rad/s] (RW, or GM for gauss_markov)
  /// @}
  std::optional<int> accel_bias_gm;  ///< b_a GM states (BiasModel::both): 15
  std::optional<int> gyro_bias_gm;   ///< b_g GM states (BiasModel::both): 18
  std::optional<int> accel_scale;    ///< s_a [-]: 15 or 21
  std::optional<int> gyro_scale;     ///< s_g [-]: 18 or 24
  int states = 15;

  /// @name Noise offsets in w, 3 inputs each
  /// @{
  static constexpr int kGyroWhiteNoise = 0;   ///< n_g → δψ through C_bn
  static constexpr int kAccelWhiteNoise = 3;  ///< n_a → δv through C_bn
  static constexpr int kGyroBiasNoise = 6;    ///< drives the b_g states at kGyroBias
  static constexpr int kAccelBiasNoise = 9;   ///< drives the b_a states at kAccelBias
  /// @}
  std::optional<int> gyro_bias_gm_noise;   ///< drives gyro_bias_gm (both): 12
  std::optional<int> accel_bias_gm_noise;  ///< drives accel_bias_gm (both): 15
  std::optional<int> gyro_scale_noise;     ///< drives gyro_scale: 12 or 18
  std::optional<int> accel_scale_noise;    ///< drives accel_scale: 15 or 21
  int noises = 12;                         ///< always states − 3
  /// States of gm_terms and ramps, after every block above (empty without such terms).
  std::vector<AxisState> axis_states;
};

/// The layout ins_error_state_model() produces for OPTIONS and a noise without gm_terms and
/// ramps (height_hold does not change it).
ErrorStateLayout error_state_layout(const ErrorStateOptions& options);
/// The layout for OPTIONS and NOISE: the blocks above plus NOISE's gm_terms (σ > 0) and ramps
/// (R > 0, not with BiasModel::gauss_markov) as axis_states.
ErrorStateLayout error_state_layout(const ErrorStateOptions& options, const InsSensorNoise& noise);

/// The continuous error-state model ẋ = F x + G w, E[w wᵀ] = Q_c δ(t − s) at NOMINAL.
///
/// F navigation block: the phi-angle model of theory.md §7.4 (Groves 14.64–14.71) —
/// δψ̇ = −ω_in^n × δψ − δω_in^n, δv̇ = −(C_bn f^b) × δψ − (2ω_ie^n + ω_en^n) × δv
/// + v × δ(2ω_ie^n + ω_en^n) + δg^n, with Schuler, Earth-rate and Coriolis coupling for any
/// velocity. It is built in (δL, δλ, δh) and carried to metres by the time-varying
/// δr = T δp, T = diag(R_N+h, (R_E+h)cosL, −1): F_r = T F_p T⁻¹ + Ṫ T⁻¹, where Ṫ T⁻¹ (zero
/// at rest) gives the −v_D/(R+h), −v_N tanL/(R+h) terms of metre-form models such as
/// KF-GINS. Unlike Groves, the latitude derivatives of R_N, R_E and g^n are kept, so F is
/// the exact Jacobian of the §7.2 mechanization (the extra terms are ≤ e² relative to their
/// neighbours, or ~1e-8 s⁻² for ∂g_D/∂L per metre north; tests check F by finite differences).
/// The vertical δr_D → δv_D term is ∂g_D/∂h of gravity_ned() (≈ 2g/R, unstable) unless
/// options.height_hold. options.earth_rate = false drops every Ω_ie term.
///
/// Sensor blocks: δψ̇ += C_bn(b_g [+ b_g,gm] + Σ b_g,j + diag(ω_ib^b) s_g + n_g), δv̇ +=
/// C_bn(b_a [+ b_a,gm] + Σ b_a,j + diag(f_ib^b) s_a + n_a); RW biases F = 0 (plus the ramp
/// slope, ḃ_RW += s); GM biases F = −1/T_c; scale factors F = 0 (T_s = ∞) or −1/T_s. A GM
/// term with σ = 0 leaves its state inert (F = 0, Q_c = 0). The gm_terms b_j and ramp slopes
/// s are the axis_states of the layout.
///
/// w = [n_g, n_a, w_bg, w_ba, (w_bg,gm, w_ba,gm), (w_sg, w_sa)] (gyro before accel in each
/// pair; theory.md §6.3 lists w_ba first — the order here is fixed by ErrorStateLayout), G
/// maps the white noises through C_bn and each driving noise to its own state with 1, and
/// Q_c = diag(N_g², N_a², K² or 2σ²/T_c, …, 2σ_s²/T_s or 0). P₀ (initial_variance): 0 for
/// the navigation errors, turn-on σ² (RW), σ² (GM, stationary), σ_s² (scale factors).
///
/// @throws InputError when the nominal is not finite, |L| ≥ π/2, R + h ≤ 0 or C_bn is not a
/// rotation (‖C_bnᵀC_bn − I‖ > 1e-6 or det < 0); when a noise term is negative or not finite,
/// a GM with σ > 0 has T_c not in (0, ∞), or a scale-factor T_s ≤ 0 or NaN.
models::ContinuousStateModel ins_error_state_model(const NominalState& nominal,
                                                   const InsSensorNoise& noise,
                                                   const ErrorStateOptions& options);

}  // namespace imunoise::ins
