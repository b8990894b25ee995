/// @file
/// @brief What the two halves of the noise fit share (analysis/noise_fit.cpp: the fit and the
/// model selection; analysis/noise_fit_refits.cpp: the refits of a given structure, the
/// least-squares intervals and the profile bounds). Not a public header.
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "analysis/noise_fit.h"

namespace imunoise::analysis::fit_detail {

/// The used points, as parallel arrays.
struct Data {
  std::vector<double> tau, y, nu;
  std::vector<std::size_t> index;  ///< position in the caller's span
  /// Lower Cholesky factor L of the correlation ρ = LLᵀ of the estimates at the used points
  /// (generalized least squares, refit_fixed_terms); empty: the points taken as independent.
  Eigen::MatrixXd correlation_factor;
  /// With a correlation factor: the model variance the weights come from, held (feasible GLS:
  /// the covariance of the estimates is that of the structure's model, not re-derived from each
  /// solve, which would make the estimator non-linear in the data and, measured on Gaussian
  /// draws, 1.6× less precise in K² than the Gauss–Markov bound).
  Eigen::VectorXd weight_model;
  std::size_t size() const { return tau.size(); }
};

enum class ColumnKind { power_law, gauss_markov, sinusoid };

/// One basis function of the linear model; its coefficient is a variance.
struct Column {
  ColumnKind kind = ColumnKind::power_law;
  NoiseTerm term = NoiseTerm::white_noise;  ///< power_law only
  double tau_c_s = 0.0;                     ///< gauss_markov only
  double frequency_hz = 0.0;                ///< sinusoid only
};

/// Solution of the weighted problem for one column set.
struct Solution {
  Eigen::VectorXd c;      ///< variances per column, ≥ 0
  Eigen::VectorXd model;  ///< model variance at each used τ (including the offset)
  double sse = 0.0;       ///< Σ (ν_k/2)(y_k/m_k − 1)² with m_k the floored model
  double deviance = 0.0;  ///< Σ ν_k (r_k − 1 − ln r_k), r_k = y_k/m_k
  /// The criterion the last solve minimized: the deviance for independent points, the GLS
  /// quadratic form ‖L⁻¹D⁻¹(y − m)‖² (D = diag(m_k·√(2/ν_k)), weights of the last pass) with a
  /// correlation factor.
  double objective = 0.0;
};

/// T_c bracket of a refit: ±1/3 decade (one GM grid step) around the structure's value, in ln T_c.
extern const double kRefitBracket;

/// Column COLUMN's basis function at τ (AVAR, or HVAR when HADAMARD), for unit coefficient.
double basis(const Column& column, double tau_s, bool hadamard);
/// 1 per power-law term and sinusoid, 2 per GM.
int parameter_count(const Column& column);
/// The weighted (GLS with DATA's correlation factor) NNLS of COLUMNS, re-weighted ITERATIONS
/// times (noise_fit.cpp).
Solution solve(const Data& data, const std::vector<Column>& columns, bool hadamard, int iterations,
               const Eigen::VectorXd& offset, const Eigen::VectorXd* initial_model = nullptr);
Eigen::VectorXd zero_offset(const Data& data);
/// MODEL floored at a small fraction of Y for the weights (noise_fit.cpp kModelFloorFraction).
double floored(double model, double y);
/// The 1-D searches of every GM column's T_c within LN_BRACKETS (noise_fit.cpp).
void refine_gauss_markov(const Data& data, std::vector<Column>& columns, bool hadamard,
                         int iterations, const std::vector<std::pair<double, double>>& ln_brackets);
std::vector<std::pair<double, double>> brackets_around(const std::vector<Column>& columns,
                                                       double half_width);
void validate_points(std::span<const FitPoint> points, const char* where);
void validate_options(const FitOptions& options);
double effective_point_count(const Data& data);
FitResult make_result(std::span<const FitPoint> points, const Data& data,
                      const std::vector<Column>& columns, const Solution& s, bool hadamard,
                      double effective_points, std::string note, bool residuals = true);
/// The points FIT used (POINTS[USED]) as fit data; WHERE names the caller in errors.
Data used_data(std::span<const FitPoint> points, std::span<const std::size_t> used,
               const char* where);
/// The columns of a fitted structure: its identified power-law terms, sinusoids and GMs.
std::vector<Column> structure_columns(const FitResult& structure);

}  // namespace imunoise::analysis::fit_detail
