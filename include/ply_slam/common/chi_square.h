#pragma once

namespace ply_slam {

// The chi-square quantiles the outlier tests use, 95 % (probability of keeping an inlier),
// by degrees of freedom: a pixel residual has 2, a pixel plus a depth residual 3.
constexpr double kChiSquare95TwoDof = 5.991;
constexpr double kChiSquare95ThreeDof = 7.815;
// What the depth residual's degree of freedom adds to a 2-DoF bound (7.815 - 5.991), so that a
// configured 2-DoF bound gives the 3-DoF one. Written out: the subtraction in double would not
// give 1.824 exactly, and the bounds must stay the numbers they were.
constexpr double kChiSquare95DepthDof = 1.824;

// The bound of a residual with a depth term, from the bound of its pixel term alone.
inline double withDepthDof(double two_dof_bound) { return two_dof_bound + kChiSquare95DepthDof; }

}  // namespace ply_slam
