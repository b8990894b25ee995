/// @file
/// @brief Linear state models of sensor errors and their exact discretization (see
/// state_space.h, theory.md §6.1–6.2).
#include "models/state_space.h"

#include <cmath>
#include <cstddef>
#include <sstream>
#include <string>
#include <unsupported/Eigen/MatrixFunctions>
#include <utility>
#include <vector>

#include "common/errors.h"

namespace imunoise::models {
namespace {

/// Largest number of step halvings. ‖F‖_∞·Δt ≤ DBL_MAX² < 2^2048 for finite inputs, so
/// 2^2048 substeps always reach ‖F‖_∞·h ≤ 1; the cap only guards the loop.
constexpr int kMaxHalvings = 2100;

/// A value for an error message: %g-style, so 1e-07, nan and -inf stay readable.
std::string show(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

/// Throws ContractViolation("WHERE: WHAT (got VALUE)") unless `ok`.
void require(bool ok, const std::string& where, const std::string& what, double value) {
  if (!ok) throw ContractViolation(where + ": " + what + " (got " + show(value) + ")");
}

void require_non_negative(double value, const std::string& where, const std::string& what) {
  require(std::isfinite(value) && value >= 0.0, where, what + " must be finite and >= 0", value);
}

void require_positive(double value, const std::string& where, const std::string& what) {
  require(std::isfinite(value) && value > 0.0, where, what + " must be finite and > 0", value);
}

void require_step(double dt_s, const std::string& where) { require_positive(dt_s, where, "dt"); }

/// Throws ContractViolation unless F is n×n, G is n×p, Q_c is p×p, all entries are
/// finite, and the labels (when present) and P₀ have the matching sizes. `names_required`:
/// block_diagonal() concatenates labels and P₀, so there they must be complete; discretize()
/// only copies the state labels and accepts a model without any.
void check_model(const ContinuousStateModel& m, const std::string& where, bool names_required) {
  const auto n = m.F.rows();
  const auto p = m.G.cols();
  const auto fail = [&](const std::string& what) {
    std::ostringstream out;
    out << where << ": " << what << " (F " << m.F.rows() << "x" << m.F.cols() << ", G "
        << m.G.rows() << "x" << m.G.cols() << ", Qc " << m.Qc.rows() << "x" << m.Qc.cols()
        << ", initial_variance " << m.initial_variance.size() << ", state_names "
        << m.state_names.size() << ", noise_names " << m.noise_names.size() << ")";
    throw ContractViolation(out.str());
  };
  if (m.F.cols() != n) fail("F must be square");
  if (m.G.rows() != n) fail("G must have as many rows as F");
  if (m.Qc.rows() != p || m.Qc.cols() != p) fail("Qc must be p x p with p = G columns");
  const bool states_labelled = static_cast<Eigen::Index>(m.state_names.size()) == n;
  if ((names_required || !m.state_names.empty()) && !states_labelled) {
    fail("state_names must have one label per state");
  }
  if (names_required) {
    if (m.initial_variance.size() != n) fail("initial_variance must have one entry per state");
    if (static_cast<Eigen::Index>(m.noise_names.size()) != p) {
      fail("noise_names must have one label per noise input");
    }
  }
  if (!m.F.allFinite() || !m.G.allFinite() || !m.Qc.allFinite()) {
    fail("F, G and Qc must be finite");
  }
}

ContinuousStateModel scalar_model(double f, double g, double qc, double p0, std::string state,
                                  std::string noise) {
  ContinuousStateModel m;
  m.F = Eigen::MatrixXd::Constant(1, 1, f);
  m.G = Eigen::MatrixXd::Constant(1, 1, g);
  m.Qc = Eigen::MatrixXd::Constant(1, 1, qc);
  m.initial_variance = Eigen::VectorXd::Constant(1, p0);
  m.state_names = {std::move(state)};
  m.noise_names = {std::move(noise)};
  return m;
}

/// One substep h by Van Loan [VL78] (theory.md §6.2): A = [[−Fh, W],[0, Fᵀh]], E = e^A,
/// Φ = E₂₂ᵀ, Q = h·Φ·E₁₂. Called with ‖F‖_∞·h ≤ 1 so e^{−Fh} stays below e and nothing
/// overflows. W = GQ_cGᵀ arrives scaled to ‖W‖₁ = 1 and is put into A *without* the
/// factor h (Q is linear in W, so Q is multiplied by h instead): A then has ‖A‖₁ ≤ 2 and
/// Eigen's Padé approximant needs no squarings. With W·h in A, a random walk at
/// Δt = 10⁶ s took 18 squarings that turned the 1-ulp Padé error of E₂₂ into 3e-11.
std::pair<Eigen::MatrixXd, Eigen::MatrixXd> van_loan_step(const Eigen::MatrixXd& F,
                                                          const Eigen::MatrixXd& W, double h) {
  const auto n = F.rows();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  A.topLeftCorner(n, n) = -F * h;
  A.topRightCorner(n, n) = W;
  A.bottomRightCorner(n, n) = F.transpose() * h;
  const Eigen::MatrixXd E = A.exp();
  Eigen::MatrixXd Phi = E.bottomRightCorner(n, n).transpose();
  Eigen::MatrixXd Q = h * (Phi * E.topRightCorner(n, n));
  return {std::move(Phi), std::move(Q)};
}

DiscreteStateModel closed_form(Eigen::MatrixXd Phi, Eigen::MatrixXd Qd,
                               std::vector<std::string> names, double dt_s) {
  return {std::move(Phi), std::move(Qd), std::move(names), dt_s, "closed form"};
}

}  // namespace

ContinuousStateModel random_walk_state(double random_walk, const std::string& name) {
  require_non_negative(random_walk, "random_walk_state", "random walk K");
  return scalar_model(0.0, 1.0, random_walk * random_walk, 0.0, name, name + "_driving_noise");
}

ContinuousStateModel random_constant_state(double sigma0, const std::string& name) {
  require_non_negative(sigma0, "random_constant_state", "sigma0");
  // G = 0 and Q_c = 0 keep p = 1 so every model has a noise column to label (theory.md §6.1).
  return scalar_model(0.0, 0.0, 0.0, sigma0 * sigma0, name, name + "_driving_noise");
}

ContinuousStateModel gauss_markov_state(double sigma, double tau_c_s, const std::string& name) {
  require_non_negative(sigma, "gauss_markov_state", "sigma");
  require_positive(tau_c_s, "gauss_markov_state", "tau_c");
  // Q_c = 2σ²/T_c makes the stationary variance σ² (theory.md §6.1, GM1 row).
  return scalar_model(-1.0 / tau_c_s, 1.0, 2.0 * sigma * sigma / tau_c_s, sigma * sigma, name,
                      name + "_driving_noise");
}

ContinuousStateModel second_order_gauss_markov_state(double sigma, double omega_n_rad_per_s,
                                                     double zeta, const std::string& name) {
  const std::string where = "second_order_gauss_markov_state";
  require_non_negative(sigma, where, "sigma");
  require_positive(omega_n_rad_per_s, where, "omega_n");
  require_positive(zeta, where, "zeta");
  const double w = omega_n_rad_per_s;
  const double var = sigma * sigma;
  ContinuousStateModel m;
  m.F.resize(2, 2);
  m.F << 0.0, 1.0, -w * w, -2.0 * zeta * w;
  m.G = Eigen::Vector2d(0.0, 1.0);
  // 4ζω_n³σ² solves F P + P Fᵀ + G Q_c Gᵀ = 0 with P = diag(σ², ω_n²σ²) (theory.md §6.1 GM2).
  m.Qc = Eigen::MatrixXd::Constant(1, 1, 4.0 * zeta * w * w * w * var);
  m.initial_variance = Eigen::Vector2d(var, w * w * var);
  m.state_names = {name, name + "_rate"};
  m.noise_names = {name + "_driving_noise"};
  return m;
}

ContinuousStateModel ramp_state(double ramp, const std::string& name) {
  require_non_negative(ramp, "ramp_state", "ramp R");
  ContinuousStateModel m;
  m.F.resize(2, 2);
  m.F << 0.0, 1.0, 0.0, 0.0;
  // Like random_constant_state: one zero noise column, so the slope never wanders.
  m.G = Eigen::MatrixXd::Zero(2, 1);
  m.Qc = Eigen::MatrixXd::Zero(1, 1);
  m.initial_variance = Eigen::Vector2d(0.0, ramp * ramp);
  m.state_names = {name, name + "_slope"};
  m.noise_names = {name + "_driving_noise"};
  return m;
}

ContinuousStateModel angle_bias_state(double white_noise, double random_walk,
                                      const std::string& name) {
  require_non_negative(white_noise, "angle_bias_state", "white noise N");
  require_non_negative(random_walk, "angle_bias_state", "random walk K");
  ContinuousStateModel m;
  m.F.resize(2, 2);
  m.F << 0.0, 1.0, 0.0, 0.0;
  m.G = Eigen::Matrix2d::Identity();
  m.Qc = Eigen::Vector2d(white_noise * white_noise, random_walk * random_walk).asDiagonal();
  m.initial_variance = Eigen::Vector2d::Zero();
  m.state_names = {name + "_angle", name + "_bias"};
  m.noise_names = {name + "_angle_white_noise", name + "_bias_driving_noise"};
  return m;
}

ContinuousStateModel block_diagonal(std::span<const ContinuousStateModel> blocks) {
  Eigen::Index n = 0, p = 0;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    check_model(blocks[i], "block_diagonal: block " + std::to_string(i), true);
    n += blocks[i].F.rows();
    p += blocks[i].G.cols();
  }
  ContinuousStateModel out;
  out.F = Eigen::MatrixXd::Zero(n, n);
  out.G = Eigen::MatrixXd::Zero(n, p);
  out.Qc = Eigen::MatrixXd::Zero(p, p);
  out.initial_variance = Eigen::VectorXd::Zero(n);
  Eigen::Index r = 0, c = 0;
  for (const ContinuousStateModel& b : blocks) {
    const auto bn = b.F.rows();
    const auto bp = b.G.cols();
    out.F.block(r, r, bn, bn) = b.F;
    out.G.block(r, c, bn, bp) = b.G;
    out.Qc.block(c, c, bp, bp) = b.Qc;
    out.initial_variance.segment(r, bn) = b.initial_variance;
    out.state_names.insert(out.state_names.end(), b.state_names.begin(), b.state_names.end());
    out.noise_names.insert(out.noise_names.end(), b.noise_names.begin(), b.noise_names.end());
    r += bn;
    c += bp;
  }
  return out;
}

DiscreteStateModel discretize(const ContinuousStateModel& model, double dt_s) {
  require_step(dt_s, "discretize");
  check_model(model, "discretize", false);
  const auto n = model.F.rows();
  DiscreteStateModel out;
  out.state_names = model.state_names;
  out.dt_s = dt_s;
  out.method = "van loan";
  if (n == 0) {
    out.Phi.resize(0, 0);
    out.Qd.resize(0, 0);
    return out;
  }

  // W = GQ_cGᵀ, scaled to ‖W‖₁ = 1 so the exponential never sees its magnitude; Q_d is
  // linear in W, so the scale is put back at the end.
  Eigen::MatrixXd W = model.G * model.Qc * model.G.transpose();
  W = 0.5 * (W + W.transpose()).eval();
  if (!W.allFinite()) {
    throw ContractViolation("discretize: G Qc G^T overflows (max |Qc| " +
                            show(model.Qc.cwiseAbs().maxCoeff()) + ")");
  }
  const double w_scale = W.cwiseAbs().colwise().sum().maxCoeff();
  if (w_scale > 0.0) W /= w_scale;

  // Smallest k with ‖F‖_∞·Δt/2^k ≤ 1: e^{−Fh} then stays below e (theory.md §6.2 caveat:
  // Δt = 3000 s with T_c = 15 s overflows in one step). norm·h may overflow to +inf for
  // extreme inputs; halving still terminates because h shrinks.
  const double f_norm = model.F.cwiseAbs().rowwise().sum().maxCoeff();
  int k = 0;
  double h = dt_s;
  while (f_norm * h > 1.0 && k < kMaxHalvings) {
    h = std::ldexp(dt_s, -(k + 1));
    ++k;
  }

  auto [Phi, Q] = van_loan_step(model.F, W, h);
  // Doubling: over 2h, Φ₂ = Φ² and Q₂ = ΦQΦᵀ + Q (the second half-step's noise plus the first
  // half-step's noise carried through Φ). Each pass is exact up to rounding.
  for (int i = 0; i < k; ++i) {
    Q = (Phi * Q * Phi.transpose() + Q).eval();
    Q = 0.5 * (Q + Q.transpose()).eval();
    Phi = (Phi * Phi).eval();
  }
  out.Phi = std::move(Phi);
  out.Qd = w_scale * 0.5 * (Q + Q.transpose());
  if (k > 0) out.method = "van loan, 2^" + std::to_string(k) + " substeps";
  return out;
}

DiscreteStateModel random_walk_discrete(double random_walk, double dt_s, const std::string& name) {
  require_non_negative(random_walk, "random_walk_discrete", "random walk K");
  require_step(dt_s, "random_walk_discrete");
  return closed_form(Eigen::MatrixXd::Ones(1, 1),
                     Eigen::MatrixXd::Constant(1, 1, random_walk * random_walk * dt_s), {name},
                     dt_s);
}

DiscreteStateModel gauss_markov_discrete(double sigma, double tau_c_s, double dt_s,
                                         const std::string& name) {
  require_non_negative(sigma, "gauss_markov_discrete", "sigma");
  require_positive(tau_c_s, "gauss_markov_discrete", "tau_c");
  require_step(dt_s, "gauss_markov_discrete");
  // 1 − e^{−2Δt/T_c} = −expm1(−2Δt/T_c): no cancellation when Δt ≪ T_c (theory.md §6.2).
  const double qd = -sigma * sigma * std::expm1(-2.0 * dt_s / tau_c_s);
  return closed_form(Eigen::MatrixXd::Constant(1, 1, std::exp(-dt_s / tau_c_s)),
                     Eigen::MatrixXd::Constant(1, 1, qd), {name}, dt_s);
}

DiscreteStateModel angle_bias_discrete(double white_noise, double random_walk, double dt_s,
                                       const std::string& name) {
  require_non_negative(white_noise, "angle_bias_discrete", "white noise N");
  require_non_negative(random_walk, "angle_bias_discrete", "random walk K");
  require_step(dt_s, "angle_bias_discrete");
  const double n2 = white_noise * white_noise;
  const double k2 = random_walk * random_walk;
  Eigen::MatrixXd Phi(2, 2);
  Phi << 1.0, dt_s, 0.0, 1.0;
  // theory.md §6.2 [θ, b] pair: the bias integrates into the angle, hence Δt³/3 and Δt²/2.
  Eigen::MatrixXd Qd(2, 2);
  Qd << n2 * dt_s + k2 * dt_s * dt_s * dt_s / 3.0, k2 * dt_s * dt_s / 2.0, k2 * dt_s * dt_s / 2.0,
      k2 * dt_s;
  return closed_form(std::move(Phi), std::move(Qd), {name + "_angle", name + "_bias"}, dt_s);
}

double white_noise_rate_sigma(double white_noise, double dt_s) {
  require_non_negative(white_noise, "white_noise_rate_sigma", "white noise N");
  require_step(dt_s, "white_noise_rate_sigma");
  // Mean of white rate of two-sided density N² over Δt has variance N²/Δt (theory.md §6.2).
  return white_noise / std::sqrt(dt_s);
}

double white_noise_increment_sigma(double white_noise, double dt_s) {
  require_non_negative(white_noise, "white_noise_increment_sigma", "white noise N");
  require_step(dt_s, "white_noise_increment_sigma");
  // Integral of white rate over Δt has variance N²Δt (theory.md §6.2).
  return white_noise * std::sqrt(dt_s);
}

}  // namespace imunoise::models
