// Tests of ins/frames.h: skew(a) is the matrix of the cross product (checked against Eigen's
// cross()), skew-symmetric, and annihilates a.
#include "ins/frames.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace imunoise::ins {
namespace {

TEST(Frames, SkewIsTheCrossProductMatrix) {
  const Eigen::Vector3d a(0.3, -1.7, 2.5), b(-4.0, 0.25, 1.5);
  EXPECT_TRUE((skew(a) * b).isApprox(a.cross(b), 1e-15));
  EXPECT_TRUE((skew(a) + skew(a).transpose()).isZero(0.0));
  EXPECT_TRUE((skew(a) * a).isZero(1e-15));
}

}  // namespace
}  // namespace imunoise::ins
