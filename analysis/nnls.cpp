/// @file
/// @brief Lawson–Hanson NNLS (see nnls.h).
#include "analysis/nnls.h"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "common/errors.h"

namespace imunoise::analysis {
namespace {

/// Unconstrained least squares restricted to the columns in PASSIVE; other entries are 0.
Eigen::VectorXd solve_on_passive_set(const Eigen::MatrixXd& A, const Eigen::VectorXd& b,
                                     const std::vector<bool>& passive) {
  std::vector<Eigen::Index> columns;
  for (Eigen::Index j = 0; j < A.cols(); ++j)
    if (passive[static_cast<std::size_t>(j)]) columns.push_back(j);
  Eigen::MatrixXd sub(A.rows(), static_cast<Eigen::Index>(columns.size()));
  for (std::size_t k = 0; k < columns.size(); ++k)
    sub.col(static_cast<Eigen::Index>(k)) = A.col(columns[k]);
  const Eigen::VectorXd z_sub = sub.colPivHouseholderQr().solve(b);
  Eigen::VectorXd z = Eigen::VectorXd::Zero(A.cols());
  for (std::size_t k = 0; k < columns.size(); ++k)
    z(columns[k]) = z_sub(static_cast<Eigen::Index>(k));
  return z;
}

}  // namespace

Eigen::VectorXd nnls(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, int max_iterations) {
  IMUNOISE_EXPECT(A.rows() == b.size(), "nnls: A has " + std::to_string(A.rows()) +
                                            " rows but b has " + std::to_string(b.size()) +
                                            " entries");
  IMUNOISE_EXPECT(A.cols() >= 1 && A.rows() >= 1, "nnls: empty system");
  IMUNOISE_CHECK(A.allFinite() && b.allFinite(), AnalysisError,
                 "nnls: A and b must be finite (found NaN or infinity)");
  const Eigen::Index n = A.cols();
  const int limit = max_iterations > 0 ? max_iterations : static_cast<int>(3 * n);

  // Column scaling (see header): x = D⁻¹·x_scaled with D = diag(‖a_j‖).
  Eigen::VectorXd norms = A.colwise().norm().transpose();
  Eigen::MatrixXd As = A;
  std::vector<bool> usable(static_cast<std::size_t>(n), false);
  for (Eigen::Index j = 0; j < n; ++j) {
    if (norms(j) > 0.0) {
      As.col(j) /= norms(j);
      usable[static_cast<std::size_t>(j)] = true;
    }
  }

  // Optimality tolerance on the dual w_j = a_jᵀ r: with unit columns |w_j| ≤ ‖r‖ ≤ ‖b‖, so
  // this is rounding noise of the residual relative to the data.
  const double eps = std::numeric_limits<double>::epsilon();
  const double tol = 10.0 * eps * static_cast<double>(std::max(A.rows(), n)) * b.norm();

  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  std::vector<bool> passive(static_cast<std::size_t>(n), false);
  // Columns temporarily barred from entering: a column whose first subproblem gives it a
  // non-positive value would re-enter forever (Lawson & Hanson's safeguard, step 6 note).
  std::vector<bool> barred(static_cast<std::size_t>(n), false);
  Eigen::VectorXd w = As.transpose() * (b - As * x);

  for (int iteration = 0;; ++iteration) {
    // Step 2–5: pick the most promising zero (active-constraint) column.
    Eigen::Index t = -1;
    double best = tol;
    for (Eigen::Index j = 0; j < n; ++j) {
      const auto ju = static_cast<std::size_t>(j);
      if (usable[ju] && !passive[ju] && !barred[ju] && w(j) > best) {
        best = w(j);
        t = j;
      }
    }
    if (t < 0) break;  // KKT satisfied: every zero variable has w_j ≤ tol
    IMUNOISE_CHECK(iteration < limit, AnalysisError,
                   "nnls: no convergence within " + std::to_string(limit) +
                       " iterations (degenerate or cycling problem)");
    passive[static_cast<std::size_t>(t)] = true;

    bool first_solve = true;
    for (;;) {  // Steps 6–11: keep the passive-set solution feasible.
      const Eigen::VectorXd z = solve_on_passive_set(As, b, passive);
      if (first_solve && z(t) <= 0.0) {
        // Rounding (or collinearity) makes the new column useless: bar it until x changes.
        passive[static_cast<std::size_t>(t)] = false;
        barred[static_cast<std::size_t>(t)] = true;
        break;
      }
      first_solve = false;
      bool feasible = true;
      double alpha = 1.0;
      Eigen::Index blocking = -1;
      for (Eigen::Index j = 0; j < n; ++j) {
        if (!passive[static_cast<std::size_t>(j)] || z(j) > 0.0) continue;
        feasible = false;
        const double ratio = x(j) / (x(j) - z(j));
        if (blocking < 0 || ratio < alpha) {
          alpha = ratio;
          blocking = j;
        }
      }
      if (feasible) {
        x = z;
        std::fill(barred.begin(), barred.end(), false);
        break;
      }
      // Step back along x → z until the first passive variable hits zero; move it (and any
      // other that reached zero) to the active set.
      x += alpha * (z - x);
      x(blocking) = 0.0;
      for (Eigen::Index j = 0; j < n; ++j) {
        const auto ju = static_cast<std::size_t>(j);
        if (passive[ju] && x(j) <= 0.0) {
          passive[ju] = false;
          x(j) = 0.0;
        }
      }
    }
    w = As.transpose() * (b - As * x);
  }

  for (Eigen::Index j = 0; j < n; ++j)
    x(j) = usable[static_cast<std::size_t>(j)] ? x(j) / norms(j) : 0.0;
  return x;
}

}  // namespace imunoise::analysis
