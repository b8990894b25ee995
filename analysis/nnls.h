/// @file
/// @brief Non-negative least squares, min ‖A·x − b‖₂ subject to x ≥ 0, by the active-set
/// algorithm of Lawson & Hanson (Solving Least Squares Problems, 1974, ch. 23, algorithm NNLS).
/// The solver of the σ²-domain noise fit (theory.md §4.3), whose unknowns are variances.
#pragma once

#include <Eigen/Dense>

namespace imunoise::analysis {

/// Solves min ‖A·x − b‖₂ subject to x ≥ 0.
///
/// Columns are scaled to unit Euclidean norm before solving and the solution is scaled back:
/// the AVAR basis columns (3/τ², 1/τ, 1, τ/3, τ²/2 over τ = 0.01 … 10⁴ s) differ by ~10¹⁶ in
/// magnitude, which would otherwise make the dual-variable test (w_j > tol) and the pivoted QR
/// of each subproblem depend on the units. Scaling does not change the solution set. Columns of
/// zero norm get x_j = 0. Each least-squares subproblem on the passive set is solved by
/// column-pivoted Householder QR, so collinear passive columns are handled (basic solution).
///
/// @param[in] A              m×n design matrix (any m, n ≥ 1; finite)
/// @param[in] b              right-hand side, m entries (finite)
/// @param[in] max_iterations limit on outer iterations (columns moved into the passive set);
///                           0 = 3·n, Lawson & Hanson's suggestion
/// @return x ≥ 0 (n entries) satisfying the KKT conditions to rounding: w = Aᵀ(b − A·x) ≤ 0
///         where x_j = 0 and w_j ≈ 0 where x_j > 0
/// @throws AnalysisError on non-finite input (numbers the data gave), or no convergence within
///         max_iterations (only possible for degenerate, cycling problems); ContractViolation
///         on mismatched sizes or an empty system.
Eigen::VectorXd nnls(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, int max_iterations = 0);

}  // namespace imunoise::analysis
