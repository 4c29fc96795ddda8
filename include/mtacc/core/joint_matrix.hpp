#pragma once
// Batches of poses and points: one row per pose. Joint values are in the commanded-axis order
// of Machine::axes, linear axes in mm and rotary axes in rad; points and directions in mm.
#include <Eigen/Core>

#include <vector>

#include "mtacc/core/large_vector.hpp"

namespace mtacc {

using JointMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
// Direction of motion of each axis per pose (+1, -1, 0), for reversal errors; empty for none.
using DirectionMatrix = Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using PointMatrix = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using PoseErrorMatrix = Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor>;

// A long batch (a pose per instrument sample) in a LargeVector, seen as a JointMatrix.
struct LargeJointMatrix {
  LargeVector<double> values;  // row by row
  Eigen::Index rows = 0, cols = 0;

  LargeJointMatrix() = default;
  LargeJointMatrix(Eigen::Index r, Eigen::Index c) : values(static_cast<size_t>(r * c)), rows(r), cols(c) {}
  Eigen::Map<JointMatrix> matrix() { return {values.data(), rows, cols}; }
  Eigen::Map<const JointMatrix> matrix() const { return {values.data(), rows, cols}; }
};

// Poses from one series per axis (all of one length): row k holds every axis's sample k.
inline JointMatrix posesFromChannels(const std::vector<std::vector<double>>& channels) {
  JointMatrix q(channels.empty() ? 0 : static_cast<Eigen::Index>(channels.front().size()), static_cast<Eigen::Index>(channels.size()));
  for (size_t a = 0; a < channels.size(); ++a)
    for (size_t k = 0; k < channels[a].size(); ++k) q(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(a)) = channels[a][k];
  return q;
}

}  // namespace mtacc
