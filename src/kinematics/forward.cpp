#include "mtacc/kinematics/forward.hpp"

#include "chain_program.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#include <vector>

namespace mtacc {
namespace {

// Calls f(i, j) with the plane (i, j) of principal axis k as compile-time constants: with
// constant indices the vectors and matrices stay in registers instead of going through memory.
template <class F>
inline void inPrincipalPlane(int k, F&& f) {
  using std::integral_constant;
  switch (k) {
    case 0: f(integral_constant<int, 1>{}, integral_constant<int, 2>{}); break;
    case 1: f(integral_constant<int, 2>{}, integral_constant<int, 0>{}); break;
    default: f(integral_constant<int, 0>{}, integral_constant<int, 1>{}); break;
  }
}

// Right-multiplies the rotation by a rotation of angle about principal axis k.
void rotatePrincipal(Mat3& r, int k, double angle) {
  double s, c;
  fastSinCos(angle, s, c);
  inPrincipalPlane(k, [&](auto i, auto j) {
    const Vec3 ci = r.col(i), cj = r.col(j);
    r.col(i) = c * ci + s * cj;
    r.col(j) = c * cj - s * ci;
  });
}

// A point and N directions carried through the chain one factor at a time: cheaper than
// composing frames and inverting one. N = 0: the TCP; N = 1: the TCP and the tool direction;
// N = 3: the tool frame (its origin and the columns of its rotation).
template <int N>
struct PointDirections {
  Vec3 p;
  std::array<Vec3, N> d;
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

// v <- rotation of v by (s, c) in the plane (i, j) of a principal axis.
template <class I, class J>
inline void rotatePlane(Vec3& v, I i, J j, double s, double c) {
  const double vi = v[i], vj = v[j];
  v[i] = c * vi - s * vj;
  v[j] = s * vi + c * vj;
}

// x <- F x for each factor F handed over, or x <- F^-1 x (Inverse): a point and N
// directions carried through a chain.
template <bool Inverse, int N>
struct PointTransport {
  PointDirections<N>& x;
  void translate(const Vec3& t) {
    if constexpr (Inverse)
      x.p -= t;
    else
      x.p += t;
  }
  void transform(const Mat3& r, const Vec3& t) {
    if constexpr (Inverse) {
      x.p = transposeTimes(r, x.p - t);
      for (auto& d : x.d) d = transposeTimes(r, d);
    } else {
      x.p = times(r, x.p) + t;
      for (auto& d : x.d) d = times(r, d);
    }
  }
  void rotate(const ChainOp& op, double angle) {
    if constexpr (Inverse) angle = -angle;
    if (op.principal >= 0) {
      double s, c;
      fastSinCos(angle, s, c);
      if (op.hasBase) x.p -= op.base;
      inPrincipalPlane(op.principal, [&](auto i, auto j) {
        rotatePlane(x.p, i, j, s, c);
        for (auto& d : x.d) rotatePlane(d, i, j, s, c);
      });
      if (op.hasBase) x.p += op.base;
    } else {
      const Mat3 r = rotationAbout(op.vector, angle);
      x.p = op.base + r * (x.p - op.base);
      for (auto& d : x.d) d = r * d;
    }
  }
  void mark(const ChainOp&) {}
};

// T applied to the tool chain's start (after its trailing constant), factor by factor from the
// chain's end: into the bed frame.
template <int N>
void transportToBed(const KinematicModel& m, PointDirections<N>& x, const double* q, const int* dir) {
  const ChainPrograms& c = *m.chains;
  PointTransport<false, N> forward{x};
  for (size_t i = c.toolOpsPerPose; i-- > 0;) evaluateOp(c.toolProgram[i], q, dir, forward);
}

// W^-1 applied to a point and directions in the bed frame: the inverted workpiece chain from the bed.
template <int N>
void transportBedToWorkpiece(const KinematicModel& m, PointDirections<N>& x, const double* q, const int* dir) {
  PointTransport<true, N> inverse{x};
  for (const auto& op : m.chains->workpieceProgram) evaluateOp(op, q, dir, inverse);
}

// W^-1 T applied to the tool chain's start.
template <int N>
PointDirections<N> transportToWorkpiece(const KinematicModel& m, const PointDirections<N>& start, const double* q,
                                        const int* dir) {
  PointDirections<N> x = start;
  transportToBed(m, x, q, dir);
  transportBedToWorkpiece(m, x, q, dir);
  return x;
}

// T <- T F for each factor F handed over: the frame product along a chain, with rotation
// and translation kept apart so that the compiler inlines and unrolls the products; the
// frame at each marker into `markers`.
struct FrameProduct {
  Mat3 r = Mat3::Identity();
  Vec3 p = Vec3::Zero();
  ChainFrame* markers = nullptr;
  void translate(const Vec3& t) { p.noalias() += r * t; }
  void transform(const Mat3& rc, const Vec3& t) {
    p.noalias() += r * t;
    const Mat3 old = r;
    r.noalias() = old * rc;
  }
  void rotate(const ChainOp& op, double angle) {
    if (op.principal >= 0 && !op.hasBase) {
      rotatePrincipal(r, op.principal, angle);
      return;
    }
    const Mat3 rc = rotationAbout(op.vector, angle);
    transform(rc, op.base - rc * op.base);
  }
  void mark(const ChainOp&) {
    markers->rotation = r;
    markers->origin = p;
    ++markers;
  }
};

}  // namespace

Pose runProgram(const ChainProgram& program, const double* q, const int* dir,
                ChainFrame* markers) {
  FrameProduct t;
  t.markers = markers;
  for (const auto& op : program) evaluateOp(op, q, dir, t);
  Pose out = Pose::Identity();
  out.linear() = t.r;
  out.translation() = t.p;
  return out;
}

Pose toolChainPose(const KinematicModel& m, const double* q, const int* dir) {
  return runProgram(m.chains->toolProgram, q, dir);
}

Pose workpiecePose(const KinematicModel& m, const double* q, const int* dir) {
  return runProgram(m.chains->workpieceProgram, q, dir);
}

Pose toolInWorkpiece(const KinematicModel& m, const double* q, const int* dir) {
  const ChainPrograms& c = *m.chains;
  const Mat3& r = c.toolRotationStart;
  const auto x = transportToWorkpiece<3>(m, {c.tcpStart, {Vec3(r.col(0)), Vec3(r.col(1)), Vec3(r.col(2))}}, q, dir);
  Pose out = Pose::Identity();
  out.linear() << x.d[0], x.d[1], x.d[2];
  out.translation() = x.p;
  return m.aligned ? m.alignment * out : out;
}

ToolPoint toolPoint(const KinematicModel& m, const double* q, const int* dir) {
  const ChainPrograms& c = *m.chains;
  const auto x = transportToWorkpiece<1>(m, {c.tcpStart, {c.toolDirectionStart}}, q, dir);
  if (m.aligned) return {m.alignment * x.p, m.alignment.linear() * x.d[0]};
  return {x.p, x.d[0]};
}

Vec3 toolPosition(const KinematicModel& m, const double* q, const int* dir) {
  const auto x = transportToWorkpiece<0>(m, {m.chains->tcpStart, {}}, q, dir);
  return m.aligned ? Vec3(m.alignment * x.p) : x.p;
}

ToolPositionAndWorkpieceRotation toolPositionAndWorkpieceRotation(const KinematicModel& m, const double* q, const int* dir) {
  PointDirections<0> tool{m.chains->tcpStart, {}};
  transportToBed(m, tool, q, dir);
  // The bed's axes carried along from the bed: W^-1 maps e_k to row k of W's rotation.
  PointDirections<3> x{tool.p, {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()}};
  transportBedToWorkpiece(m, x, q, dir);
  ToolPositionAndWorkpieceRotation out{m.aligned ? Vec3(m.alignment * x.p) : x.p, Mat3()};
  out.workpieceRotation << x.d[0].transpose(), x.d[1].transpose(), x.d[2].transpose();
  return out;
}

std::vector<Pose> errorFrames(const KinematicModel& m, const double* q) {
  std::vector<Pose> frames(m.machine->axes.size(), Pose::Identity());
  for (const ChainProgram* program : {&m.chains->toolFrameProgram, &m.chains->workpieceFrameProgram}) {
    std::vector<ChainFrame> marked(program->size());
    runProgram(*program, q, nullptr, marked.data());
    size_t k = 0;
    for (const auto& op : *program) {
      if (op.kind != ChainOp::Marker) continue;
      Pose& f = frames[static_cast<size_t>(op.axis)];
      f.linear() = marked[k].rotation;
      f.translation() = marked[k].origin;
      ++k;
    }
  }
  return frames;
}

Vec6 poseError(const Pose& actual, const Pose& nominal) {
  Vec6 e;
  e.head<3>() = actual.translation() - nominal.translation();
  e.tail<3>() = rotationVector(actual.linear() * nominal.linear().transpose());
  return e;
}

void toolPoints(const KinematicModel& m, const PoseBatch& poses, ToolPointBatch& out, int threads) {
  const long n = poses.q.rows();
  out.positions.resize(n, 3);
  out.directions.resize(n, 3);
  const bool hasDir = poses.direction.size() > 0;
  parallelFor(n, threads, [&](long begin, long end) {
    for (long i = begin; i < end; ++i) {
      const ToolPoint tp = toolPoint(m, poses.q.row(i).data(), hasDir ? poses.direction.row(i).data() : nullptr);
      out.positions.row(i) = tp.position.transpose();
      out.directions.row(i) = tp.direction.transpose();
    }
  });
}

PointMatrix toolPositions(const KinematicModel& model, const JointMatrix& q, int threads) {
  PointMatrix out(q.rows(), 3);
  parallelFor(q.rows(), threads, [&](long begin, long end) {
    for (long i = begin; i < end; ++i) out.row(i) = toolPosition(model, q.row(i).data()).transpose();
  });
  return out;
}

PoseErrorMatrix toolErrors(const KinematicModel& actual, const KinematicModel& nominal, const PoseBatch& poses,
                           int threads) {
  PoseErrorMatrix out(poses.q.rows(), 6);
  const bool hasDir = poses.direction.size() > 0;
  parallelFor(poses.q.rows(), threads, [&](long begin, long end) {
    for (long i = begin; i < end; ++i) {
      const double* q = poses.q.row(i).data();
      out.row(i) = poseError(toolInWorkpiece(actual, q, hasDir ? poses.direction.row(i).data() : nullptr),
                             toolInWorkpiece(nominal, q))
                       .transpose();
    }
  });
  return out;
}

}  // namespace mtacc
