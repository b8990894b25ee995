/// @file
/// @brief Tests of analysis/nnls.h: against brute-force enumeration of every active set on
/// small random problems, the KKT conditions, and invariance to column scaling.
#include "analysis/nnls.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "common/errors.h"
#include "test_support.h"

namespace imunoise::analysis {
namespace {

/// Independent reference: for every subset S of the columns solve the unconstrained least
/// squares on S; among the solutions that are ≥ 0 keep the one of smallest residual. The
/// NNLS optimum is one of these (the KKT point's passive set), so this finds it exactly.
Eigen::VectorXd brute_force_nnls(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  const int n = static_cast<int>(A.cols());
  Eigen::VectorXd best = Eigen::VectorXd::Zero(n);
  double best_residual = b.norm();
  for (int mask = 1; mask < (1 << n); ++mask) {
    std::vector<int> cols;
    for (int j = 0; j < n; ++j)
      if (mask & (1 << j)) cols.push_back(j);
    Eigen::MatrixXd sub(A.rows(), static_cast<Eigen::Index>(cols.size()));
    for (std::size_t k = 0; k < cols.size(); ++k)
      sub.col(static_cast<Eigen::Index>(k)) = A.col(cols[k]);
    const Eigen::VectorXd z = sub.colPivHouseholderQr().solve(b);
    if ((z.array() < 0.0).any()) continue;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    for (std::size_t k = 0; k < cols.size(); ++k) x(cols[k]) = z(static_cast<Eigen::Index>(k));
    const double residual = (A * x - b).norm();
    if (residual < best_residual) {
      best_residual = residual;
      best = x;
    }
  }
  return best;
}

Eigen::MatrixXd random_matrix(std::mt19937_64& rng, int rows, int cols) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXd A(rows, cols);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) A(i, j) = normal(rng);
  return A;
}

Eigen::VectorXd random_vector(std::mt19937_64& rng, int rows) {
  std::normal_distribution<double> normal;
  Eigen::VectorXd b(rows);
  for (int i = 0; i < rows; ++i) b(i) = normal(rng);
  return b;
}

/// KKT of min ½‖Ax − b‖², x ≥ 0: x ≥ 0, w = Aᵀ(b − Ax) ≤ 0, w_j = 0 where x_j > 0.
void expect_kkt(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const Eigen::VectorXd& x) {
  const Eigen::VectorXd w = A.transpose() * (b - A * x);
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    const double scale = 1e-10 * A.col(j).norm() * b.norm();
    EXPECT_GE(x(j), 0.0) << j;
    if (x(j) > 0.0)
      EXPECT_NEAR(w(j), 0.0, scale) << j;
    else
      EXPECT_LE(w(j), scale) << j;
  }
}

TEST(Nnls, MatchesBruteForceEnumerationOnRandomProblems) {
  std::mt19937_64 rng(20240611);
  int with_zeros = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int cols = 1 + trial % 6;
    const int rows = cols + trial % 5;  // square to over-determined: a unique optimum
    const Eigen::MatrixXd A = random_matrix(rng, rows, cols);
    const Eigen::VectorXd b = random_vector(rng, rows);
    const Eigen::VectorXd x = nnls(A, b);
    const Eigen::VectorXd ref = brute_force_nnls(A, b);
    EXPECT_LE((x - ref).norm(), 1e-9 * (1.0 + ref.norm())) << "trial " << trial;
    expect_kkt(A, b, x);
    if ((x.array() == 0.0).any()) ++with_zeros;
  }
  EXPECT_GT(with_zeros, 100);  // the constraint is active in most problems
}

TEST(Nnls, UnderdeterminedProblemsReachTheBruteForceResidual) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 100; ++trial) {
    const int cols = 3 + trial % 4;
    const int rows = 1 + trial % (cols - 1);  // fewer rows than columns
    const Eigen::MatrixXd A = random_matrix(rng, rows, cols);
    const Eigen::VectorXd b = random_vector(rng, rows);
    const Eigen::VectorXd x = nnls(A, b);
    const double ref_residual = (A * brute_force_nnls(A, b) - b).norm();
    EXPECT_NEAR((A * x - b).norm(), ref_residual, 1e-9 * b.norm()) << "trial " << trial;
    expect_kkt(A, b, x);
  }
}

TEST(Nnls, RecoversAnExactNonNegativeSolution) {
  std::mt19937_64 rng(3);
  const Eigen::MatrixXd A = random_matrix(rng, 20, 5);
  Eigen::VectorXd truth(5);
  truth << 0.5, 0.0, 2.0, 0.0, 1e-3;
  const Eigen::VectorXd x = nnls(A, A * truth);
  EXPECT_LE((x - truth).norm(), 1e-12);
}

TEST(Nnls, ColumnScalingDoesNotChangeTheSolution) {
  // Columns spanning 24 orders of magnitude, like the AVAR bases 3/τ² … τ²/2 (theory.md §4.3).
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::MatrixXd A = random_matrix(rng, 12, 5);
    const Eigen::VectorXd b = random_vector(rng, 12);
    Eigen::VectorXd scale(5);
    scale << 1e-12, 1e-6, 1.0, 1e6, 1e12;
    const Eigen::VectorXd x = nnls(A, b);
    const Eigen::VectorXd xs = nnls(A * scale.asDiagonal(), b);
    EXPECT_LE((xs.cwiseProduct(scale) - x).norm(), 1e-10 * (1.0 + x.norm())) << trial;
  }
}

TEST(Nnls, ZeroAndDuplicateColumns) {
  Eigen::MatrixXd A(4, 3);
  A << 1, 0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4;  // column 1 zero, column 2 = column 0
  Eigen::VectorXd b(4);
  b << 2, 4, 6, 8;
  const Eigen::VectorXd x = nnls(A, b);
  EXPECT_EQ(x(1), 0.0);
  EXPECT_NEAR(x(0) + x(2), 2.0, 1e-12);
  EXPECT_GE(x.minCoeff(), 0.0);
}

TEST(Nnls, AllNegativeCorrelationGivesZero) {
  Eigen::MatrixXd A(3, 2);
  A << 1, 2, 1, 1, 0, 3;
  const Eigen::VectorXd b = -Eigen::VectorXd::Ones(3);
  EXPECT_EQ(nnls(A, b), Eigen::VectorXd::Zero(2));
}

TEST(Nnls, RejectsBadInput) {
  const Eigen::MatrixXd A = Eigen::MatrixXd::Ones(3, 2);
  test::expect_throw_containing<ContractViolation>([&] { nnls(A, Eigen::VectorXd::Ones(4)); },
                                                   "3 rows but b has 4");
  Eigen::VectorXd b = Eigen::VectorXd::Ones(3);
  b(1) = std::numeric_limits<double>::quiet_NaN();
  test::expect_throw_containing<AnalysisError>([&] { nnls(A, b); }, "must be finite");
}

}  // namespace
}  // namespace imunoise::analysis
