#pragma once
// Batches of poses and points: one row per pose. Joint values are in the commanded-axis order
// of Machine::axes, linear axes in mm and rotary axes in rad; points and directions in mm.
#include <Eigen/Core>

namespace mtacc {

using JointMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
// Direction of motion of each axis per pose (+1, -1, 0), for reversal errors; empty for none.
using DirectionMatrix = Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using PointMatrix = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using PoseErrorMatrix = Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor>;

}  // namespace mtacc
