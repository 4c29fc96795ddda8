#include "mtacc/kinematics/forward.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace mtacc {
namespace {

// Right-multiplies the rotation by a rotation of angle about principal axis k.
void rotatePrincipal(Mat3& r, int k, double angle) {
  double s, c;
  ::sincos(angle, &s, &c);
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const Vec3 ci = r.col(i), cj = r.col(j);
  r.col(i) = c * ci + s * cj;
  r.col(j) = c * cj - s * ci;
}

// The six component errors of a motion-error operation at the current joint values.
Vec6 motionComponents(const KinematicModel& m, const ChainOp& op, const double* q, const int* dir) {
  const double qa = op.joint >= 0 ? q[op.joint] : 0.0;
  Vec6 c;
  if (op.sixTablesOnOneGrid) {  // the common measured case: one table per component, one grid
    const auto& g = op.tableGroups.front();
    const auto at = locateInGrid(g.positions, g.uniform, g.inverseStep, qa);
    const double* k0 = g.coefficients.data() + at.interval * 24;
    for (int t = 0; t < 6; ++t) c[t] = k0[t] + at.s * (k0[t + 6] + at.s * (k0[t + 12] + at.s * k0[t + 18]));
    return c;
  }
  c.setZero();
  for (const auto& group : op.tableGroups) {
    const auto at = locateInGrid(group.positions, group.uniform, group.inverseStep, qa);
    const size_t n = group.components.size();
    const double* k0 = group.coefficients.data() + at.interval * n * 4;
    const double *k1 = k0 + n, *k2 = k1 + n, *k3 = k2 + n;
    for (size_t t = 0; t < n; ++t) c[group.components[t]] += k0[t] + at.s * (k1[t] + at.s * (k2[t] + at.s * k3[t]));
  }
  if (op.residualMask) {
    const auto& motion = m.errors.axes[static_cast<size_t>(op.axis)].motion;
    const int d = (dir && op.joint >= 0) ? dir[op.joint] : 0;
    for (int k = 0; k < 6; ++k)
      if (op.residualMask & (1u << k)) c[k] += motion[static_cast<size_t>(k)].valueWithoutTables(qa, d);
  }
  return c;
}

// A point and a direction carried through the chain one factor at a time: cheaper than
// composing frames when only the TCP and the tool direction are wanted.
struct PointDirection {
  Vec3 p;
  Vec3 d;
};

// 3x3 products written out: the hot loop applies a few of them per operation.
inline Vec3 times(const Mat3& r, const Vec3& v) {
  return {r(0, 0) * v[0] + r(0, 1) * v[1] + r(0, 2) * v[2], r(1, 0) * v[0] + r(1, 1) * v[1] + r(1, 2) * v[2],
          r(2, 0) * v[0] + r(2, 1) * v[1] + r(2, 2) * v[2]};
}
inline Vec3 transposeTimes(const Mat3& r, const Vec3& v) {
  return {r(0, 0) * v[0] + r(1, 0) * v[1] + r(2, 0) * v[2], r(0, 1) * v[0] + r(1, 1) * v[1] + r(2, 1) * v[2],
          r(0, 2) * v[0] + r(1, 2) * v[1] + r(2, 2) * v[2]};
}

// v <- rotation of v by (s, c) in the plane (i, j) of principal axis k.
inline void rotatePlane(Vec3& v, int i, int j, double s, double c) {
  const double vi = v[i], vj = v[j];
  v[i] = c * vi - s * vj;
  v[j] = s * vi + c * vj;
}

constexpr int kNext[3] = {1, 2, 0};
constexpr int kAfterNext[3] = {2, 0, 1};

// x <- (R, t) x, or its inverse.
template <bool Inverse>
inline void transformBy(const Mat3& r, const Vec3& t, PointDirection& x) {
  if constexpr (Inverse) {
    x.p = transposeTimes(r, x.p - t);
    x.d = transposeTimes(r, x.d);
  } else {
    x.p = times(r, x.p) + t;
    x.d = times(r, x.d);
  }
}

// x <- F x (Inverse = false) or x <- F^-1 x for one operation.
template <bool Inverse>
inline void applyOp(const KinematicModel& m, const ChainOp& op, const double* q, const int* dir, PointDirection& x) {
  switch (op.kind) {
    case ChainOp::Constant:
      transformBy<Inverse>(op.constant.linear(), op.constant.translation(), x);
      break;
    case ChainOp::LinearJoint:
      if constexpr (Inverse)
        x.p -= op.base + q[op.joint] * op.vector;
      else
        x.p += op.base + q[op.joint] * op.vector;
      break;
    case ChainOp::RotaryJoint: {
      const double angle = (Inverse ? -op.sign : op.sign) * q[op.joint];
      if (op.principal >= 0) {
        double s, c;
        ::sincos(angle, &s, &c);
        const int i = kNext[op.principal], j = kAfterNext[op.principal];
        if (op.hasBase) x.p -= op.base;
        rotatePlane(x.p, i, j, s, c);
        rotatePlane(x.d, i, j, s, c);
        if (op.hasBase) x.p += op.base;
      } else {
        const Mat3 r = rotationAbout(op.vector, angle);
        x.p = op.base + r * (x.p - op.base);
        x.d = r * x.d;
      }
      break;
    }
    case ChainOp::MotionError: {
      const Vec6 c = motionComponents(m, op, q, dir);
      transformBy<Inverse>(rotationXYZ(c[kA], c[kB], c[kC]), c.head<3>(), x);
      break;
    }
    case ChainOp::HookMarker: break;
  }
}

// Fixed-size frame for the hot loop: rotation and translation kept apart, products written
// out so that the compiler inlines and unrolls them.
struct Frame {
  Mat3 r = Mat3::Identity();
  Vec3 p = Vec3::Zero();
  void apply(const Mat3& rc, const Vec3& pc) {
    p.noalias() += r * pc;
    const Mat3 old = r;
    r.noalias() = old * rc;
  }
};

Pose runProgram(const KinematicModel& m, const std::vector<ChainOp>& program, const double* q, const int* dir,
                ChainFrame* hooks = nullptr) {
  Frame t;
  for (const auto& op : program) {
    switch (op.kind) {
      case ChainOp::Constant:
        if (op.translationOnly)
          t.p.noalias() += t.r * op.constant.translation();
        else
          t.apply(op.constant.linear(), op.constant.translation());
        break;
      case ChainOp::LinearJoint:
        t.p.noalias() += t.r * (op.base + q[op.joint] * op.vector);
        break;
      case ChainOp::RotaryJoint: {
        const double angle = op.sign * q[op.joint];
        if (op.principal >= 0 && !op.hasBase) {
          rotatePrincipal(t.r, op.principal, angle);
          break;
        }
        const Mat3 r = rotationAbout(op.vector, angle);
        t.apply(r, op.base - r * op.base);
        break;
      }
      case ChainOp::MotionError: {
        const Vec6 c = motionComponents(m, op, q, dir);
        t.apply(rotationXYZ(c[kA], c[kB], c[kC]), c.head<3>());
        break;
      }
      case ChainOp::HookMarker:
        hooks->rotation = t.r;
        hooks->origin = t.p;
        ++hooks;
        break;
    }
  }
  Pose out = Pose::Identity();
  out.linear() = t.r;
  out.translation() = t.p;
  return out;
}

}  // namespace

Pose toolChainPose(const KinematicModel& m, const double* q, const int* dir) {
  return runProgram(m, m.toolProgram, q, dir);
}

Pose workpiecePose(const KinematicModel& m, const double* q, const int* dir) {
  return runProgram(m, m.workpieceProgram, q, dir);
}

Pose runHookProgram(const KinematicModel& m, const std::vector<ChainOp>& program, const double* q, const int* dir,
                    ChainFrame* hooks) {
  return runProgram(m, program, q, dir, hooks);
}

Pose toolInWorkpiece(const KinematicModel& m, const double* q, const int* dir) {
  const Pose p = workpiecePose(m, q, dir).inverse(Eigen::Isometry) * toolChainPose(m, q, dir);
  return m.aligned ? m.alignment * p : p;
}

ToolPoint toolPoint(const KinematicModel& m, const double* q, const int* dir) {
  // W^-1 T applied to the TCP (origin of the tool frame) and the tool direction, factor by
  // factor: the tool chain from its end, then the inverted workpiece chain from the bed.
  PointDirection x{m.tcpStart, m.toolDirectionStart};
  for (size_t i = m.toolOpsPerPose; i-- > 0;) applyOp<false>(m, m.toolProgram[i], q, dir, x);
  for (const auto& op : m.workpieceProgram) applyOp<true>(m, op, q, dir, x);
  if (m.aligned) return {m.alignment * x.p, m.alignment.linear() * x.d};
  return {x.p, x.d};
}

Vec6 poseError(const Pose& actual, const Pose& nominal) {
  Vec6 e;
  e.head<3>() = actual.translation() - nominal.translation();
  e.tail<3>() = rotationVector(actual.linear() * nominal.linear().transpose());
  return e;
}

void toolPoints(const KinematicModel& m, const JointMatrix& q, const DirectionMatrix& dir, PointMatrix& positions,
                PointMatrix& directions, int threads) {
  const long n = q.rows();
  positions.resize(n, 3);
  directions.resize(n, 3);
  const bool hasDir = dir.size() > 0;
  parallelFor(n, threads, [&](long begin, long end) {
    for (long i = begin; i < end; ++i) {
      const ToolPoint tp = toolPoint(m, q.row(i).data(), hasDir ? dir.row(i).data() : nullptr);
      positions.row(i) = tp.position.transpose();
      directions.row(i) = tp.direction.transpose();
    }
  });
}

PoseErrorMatrix toolErrors(const KinematicModel& actual, const KinematicModel& nominal, const JointMatrix& q,
                           const DirectionMatrix& dir, int threads) {
  PoseErrorMatrix out(q.rows(), 6);
  const bool hasDir = dir.size() > 0;
  parallelFor(q.rows(), threads, [&](long begin, long end) {
    for (long i = begin; i < end; ++i) {
      out.row(i) = poseError(toolInWorkpiece(actual, q.row(i).data(), hasDir ? dir.row(i).data() : nullptr),
                             toolInWorkpiece(nominal, q.row(i).data()))
                       .transpose();
    }
  });
  return out;
}

}  // namespace mtacc
