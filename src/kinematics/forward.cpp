#include "mtacc/kinematics/forward.hpp"

#include <algorithm>
#include <thread>
#include <vector>

namespace mtacc {
namespace {

Pose runProgram(const KinematicModel& m, const std::vector<ChainOp>& program, const double* q, const int* dir) {
  Pose t = Pose::Identity();
  for (const auto& op : program) {
    switch (op.kind) {
      case ChainOp::Constant:
        t = t * op.constant;
        break;
      case ChainOp::LinearJoint:
        t.translation() += t.linear() * (op.base + q[op.joint] * op.vector);
        break;
      case ChainOp::RotaryJoint: {
        const Mat3 r = rotationAbout(op.vector, op.sign * q[op.joint]);
        t.translation() += t.linear() * (op.base - r * op.base);
        t.linear() = t.linear() * r;
        break;
      }
      case ChainOp::MotionError: {
        const auto& motion = m.errors.axes[static_cast<size_t>(op.axis)].motion;
        const double qa = op.joint >= 0 ? q[op.joint] : 0.0;
        const int d = (dir && op.joint >= 0) ? dir[op.joint] : 0;
        Vec6 c;
        for (int k = 0; k < 6; ++k) c[k] = motion[static_cast<size_t>(k)].value(qa, d);
        t = t * errorTransform(c);
        break;
      }
    }
  }
  return t;
}

}  // namespace

Pose toolChainPose(const KinematicModel& m, const double* q, const int* dir) {
  return runProgram(m, m.toolProgram, q, dir) * m.toolFrame;
}

Pose workpiecePose(const KinematicModel& m, const double* q, const int* dir) {
  return runProgram(m, m.workpieceProgram, q, dir) * m.workpieceFrame;
}

Pose toolInWorkpiece(const KinematicModel& m, const double* q, const int* dir) {
  return m.alignment * workpiecePose(m, q, dir).inverse(Eigen::Isometry) * toolChainPose(m, q, dir);
}

ToolPoint toolPoint(const KinematicModel& m, const double* q, const int* dir) {
  const Pose p = toolInWorkpiece(m, q, dir);
  return {p.translation(), p.linear() * m.toolDirection};
}

Vec6 poseError(const Pose& actual, const Pose& nominal) {
  Vec6 e;
  e.head<3>() = actual.translation() - nominal.translation();
  e.tail<3>() = rotationVector(actual.linear() * nominal.linear().transpose());
  return e;
}

void parallelFor(long n, int threads, const std::function<void(long, long)>& body) {
  int t = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  t = static_cast<int>(std::min<long>(t, std::max(1L, n / 256)));
  if (t <= 1) {
    body(0, n);
    return;
  }
  std::vector<std::thread> pool;
  const long chunk = (n + t - 1) / t;
  for (int i = 0; i < t; ++i) {
    const long begin = i * chunk;
    const long end = std::min(n, begin + chunk);
    if (begin < end) pool.emplace_back(body, begin, end);
  }
  for (auto& th : pool) th.join();
}

void toolPoints(const KinematicModel& m, const JointMatrix& q, const Eigen::MatrixXi& dir, PointMatrix& positions,
                PointMatrix& directions, int threads) {
  const long n = q.rows();
  positions.resize(n, 3);
  directions.resize(n, 3);
  const bool hasDir = dir.size() > 0;
  parallelFor(n, threads, [&](long begin, long end) {
    Eigen::VectorXi d(q.cols());
    for (long i = begin; i < end; ++i) {
      if (hasDir) d = dir.row(i).transpose();
      const ToolPoint tp = toolPoint(m, q.row(i).data(), hasDir ? d.data() : nullptr);
      positions.row(i) = tp.position.transpose();
      directions.row(i) = tp.direction.transpose();
    }
  });
}

Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor> toolErrors(const KinematicModel& actual,
                                                                      const KinematicModel& nominal,
                                                                      const JointMatrix& q,
                                                                      const Eigen::MatrixXi& dir, int threads) {
  Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor> out(q.rows(), 6);
  const bool hasDir = dir.size() > 0;
  parallelFor(q.rows(), threads, [&](long begin, long end) {
    Eigen::VectorXi d(q.cols());
    for (long i = begin; i < end; ++i) {
      if (hasDir) d = dir.row(i).transpose();
      out.row(i) = poseError(toolInWorkpiece(actual, q.row(i).data(), hasDir ? d.data() : nullptr),
                             toolInWorkpiece(nominal, q.row(i).data()))
                       .transpose();
    }
  });
  return out;
}

}  // namespace mtacc
