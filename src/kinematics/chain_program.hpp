#pragma once
// The compiled chains (private to src/kinematics): each chain as a program of operations,
// constant factors merged, and the one function that evaluates an operation. Forward
// kinematics, point and parameter Jacobians and error frames all run these programs; they
// differ only in how they compose the factors (a frame product, or a point carried through).
#include <array>
#include <cmath>
#include <vector>

#include "mtacc/kinematics/kinematic_model.hpp"

namespace mtacc {

// One machine axis in a chain. Its factors, in order:
// offset -> [location error] -> [motion error, fixed frame] -> joint -> [motion error, moving frame].
struct ChainElement {
  int axis = -1;   // index into Machine::axes
  int joint = -1;  // index into the joint vector q, -1 for the spindle
  AxisType type = AxisType::Linear;
  ErrorFrame frame = ErrorFrame::Moving;
  double sign = 1.0;  // +1 tool side, -1 workpiece side (ISO 841: the axis moves the workpiece)
  Vec3 offset = Vec3::Zero();
  Vec3 direction = Vec3::UnitX();
  Vec3 location = Vec3::Zero();  // rotary: point on the axis line; linear: origin
};

// What a marker stands for: the factor between a pair of Jacobian markers carries the
// location errors (of a rotary axis or the spindle), the motion errors, or the location
// errors of a linear axis (its joint); an ErrorFrame marker records the frame in which an
// axis's component errors act.
enum class Hook { Location, Motion, LinearJoint, ErrorFrame };

// One operation of a program.
struct ChainOp {
  enum Kind { Constant, LinearJoint, RotaryJoint, MotionError, Marker } kind = Constant;
  Hook hook = Hook::Location;        // Marker
  Pose constant = Pose::Identity();  // Constant
  bool translationOnly = false;      // Constant: no rotation (the rotation product is skipped)
  int joint = -1;
  int axis = -1;
  Vec3 vector = Vec3::Zero();  // LinearJoint: translation per unit q; RotaryJoint: unit axis
  Vec3 base = Vec3::Zero();    // LinearJoint: translation at q = 0; RotaryJoint: point on the axis
  double sign = 1.0;           // RotaryJoint
  int principal = -1;          // RotaryJoint: 0, 1, 2 when the axis is +X, +Y, +Z (fast path), else -1
  bool hasBase = false;        // RotaryJoint: the axis does not pass through the frame origin
  // MotionError: table terms grouped by their grid, so that each grid is located once per
  // pose, with their cubic coefficients copied side by side ([interval][power][table], so
  // that the tables of one interval evaluate as one vectorisable loop);
  // harmonic terms grouped by frequency and zero: a cos(w (q - zero) + phase) = a cos(phase)
  // cos(theta) - a sin(phase) sin(theta), with one sine and cosine per pose for a group whose
  // frequency is not an integer multiple of the one before it at the same zero, and the
  // multiple-angle product for one that is (the orders of a harmonic series);
  // polynomial terms summed per power over the components, for each variable they share;
  // piecewise terms with their component; reversal terms summed per component;
  // stiffness changes with their component, the joint of their other axis and their load factor.
  struct TableGroup {
    std::vector<double> positions;
    bool uniform = false;
    double inverseStep = 0.0;
    std::vector<int> components;
    std::vector<double> coefficients;
  };
  struct HarmonicGroup {
    double omega = 0.0;  // rad per unit of q
    double zero = 0.0;
    int multiple = 1;    // > 1: omega is this multiple of the last group with multiple 1
    Vec6 cosine = Vec6::Zero(), sine = Vec6::Zero();  // per component, summed over its terms: a cos(phase), a sin(phase)
  };
  struct PolynomialGroup {  // the polynomials in one variable u = (q - zero) / scale, summed per power
    double zero = 0.0, scale = 1.0;
    std::vector<Vec6> powers;
  };
  struct Piecewise {
    int component = 0;
    CompiledPiecewise term;
  };
  std::vector<TableGroup> tableGroups;
  std::vector<HarmonicGroup> harmonicGroups;
  std::vector<PolynomialGroup> polynomialGroups;
  std::vector<Piecewise> piecewise;
  struct Stiffness {
    int component = 0;
    int otherJoint = -1;
    double loadFactor = 1.0;
    StiffnessError term;
  };
  std::vector<Stiffness> stiffness;
  Vec6 halfReversal = Vec6::Zero();  // per component: half the summed reversal widths
  bool sixTablesOnOneGrid = false;  // exactly one group holding components 0..5 in order, nothing else
};
using ChainProgram = std::vector<ChainOp>;

// How one parameter changes one hooked factor F (between the markers 2 * factor and
// 2 * factor + 1 of a Jacobian program).
struct JacobianTerm {
  enum Chain { Tool, Workpiece, Reference };  // Reference: the workpiece chain at the reference pose (machine alignment)
  // Constant: dF = [rotation translation; 0 0] (location errors of rotary axes and the
  // spindle). JointTranslation: dF = [0, translation + q * translationPerUnit] (location
  // errors of a linear axis, q its joint value). Motion: taken at each pose from the
  // motion-error operation `op` of the program.
  enum Kind { Constant, JointTranslation, Motion };
  int parameter = 0;  // column of the Jacobian
  Chain chain = Tool;
  int factor = 0;
  Kind kind = Constant;
  int op = -1;     // Motion
  int joint = -1;  // JointTranslation
  bool rotates = false;  // Constant with a nonzero rotation part
  Mat3 rotation = Mat3::Zero();
  Vec3 translation = Vec3::Zero();
  Vec3 translationPerUnit = Vec3::Zero();
  Vec3 angular = Vec3::Zero();  // Constant: vee(dF_rot F_rot^T), the factor's rotation rate
};

struct ChainPrograms {
  std::vector<ChainElement> toolChain;       // bed -> tool
  std::vector<ChainElement> workpieceChain;  // bed -> workpiece
  // The programs end with the tool or workpiece frame, Trans(tool / workpiece offset).
  ChainProgram toolProgram, workpieceProgram;
  // With a marker pair around every factor that carries error parameters (models with errors).
  ChainProgram toolHookProgram, workpieceHookProgram;
  // With an ErrorFrame marker where each axis's component errors act.
  ChainProgram toolFrameProgram, workpieceFrameProgram;
  // The TCP, tool frame rotation and tool direction after the tool program's trailing
  // constant (which does not depend on the pose), and how many tool operations remain to
  // apply per pose.
  Vec3 tcpStart = Vec3::Zero();
  Mat3 toolRotationStart = Mat3::Identity();
  Vec3 toolDirectionStart = Vec3::UnitZ();
  size_t toolOpsPerPose = 0;
  // Per axis (with errors): the location error transform and its derivatives with respect to
  // its six components, which do not depend on the pose.
  std::vector<Pose> locationTransforms;
  std::vector<std::array<Mat4, 6>> locationDerivatives;
  // Per linear axis: the direction tilted by its location errors, and its derivatives with
  // respect to the three tilts (A, B, C).
  std::vector<Vec3> tiltedDirections;
  std::vector<std::array<Vec3, 3>> tiltedDirectionDerivatives;

  // The Jacobians' plan (models compiled with parameters): the terms, and per chain the
  // first of its hooked factors in the flat per-factor arrays of KinematicData.
  std::vector<JacobianTerm> terms;
  std::array<int, 4> factorStart{};  // [Tool], [Workpiece], [Reference], total
  // Machine alignment: the workpiece chain at the reference pose, the same for every pose.
  std::vector<ChainFrame> referenceFrames;
  Pose reference = Pose::Identity();
  Mat3 referenceToWorkpiece = Mat3::Zero();  // M_WC's rotation times the reference pose's inverse rotation
};

// Plans the Jacobians of `model` (compiled with its programs) into chains.terms.
void planJacobian(const KinematicModel& model, ChainPrograms& chains);

// The six component errors of a motion-error operation at the joint values.
inline Vec6 motionComponents(const ChainOp& op, const double* q, const int* dir) {
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
  double baseCosine = 1.0, baseSine = 0.0;
  for (const auto& group : op.harmonicGroups) {
    double cosine = baseCosine, sine = baseSine;
    if (group.multiple == 1) {
      const double theta = group.omega * (qa - group.zero);
      fastSinCos(theta, sine, cosine);
      baseCosine = cosine;
      baseSine = sine;
    } else {
      for (int m = 1; m < group.multiple; ++m) {
        const double next = cosine * baseCosine - sine * baseSine;
        sine = sine * baseCosine + cosine * baseSine;
        cosine = next;
      }
    }
    c += group.cosine * cosine - group.sine * sine;
  }
  for (const auto& p : op.polynomialGroups) {
    const double u = (qa - p.zero) / p.scale;
    Vec6 v = p.powers.back();
    for (auto k = p.powers.size() - 1; k-- > 0;) v = v * u + p.powers[k];
    c += v;
  }
  for (const auto& p : op.piecewise) c[p.component] += p.term.value(qa);
  for (const auto& s : op.stiffness) c[s.component] += s.loadFactor * s.term.value(qa, s.otherJoint >= 0 ? q[s.otherJoint] : 0.0);
  if (dir && op.joint >= 0 && dir[op.joint] != 0) c += dir[op.joint] > 0 ? op.halfReversal : Vec6(-op.halfReversal);
  return c;
}

// Evaluates one operation at the joint values and hands its factor to `compose`, which
// applies it (to a frame product, or to a point and a direction, forwards or inverted):
//   compose.translate(t)       a pure translation
//   compose.transform(R, t)    x -> R x + t
//   compose.rotate(op, angle)  a RotaryJoint: rotation by angle about op's axis line
//   compose.mark(op)           a Marker
template <class Compose>
[[gnu::always_inline]] inline void evaluateOp(const ChainOp& op, const double* q, const int* dir, Compose& compose) {
  switch (op.kind) {
    case ChainOp::Constant:
      if (op.translationOnly)
        compose.translate(op.constant.translation());
      else
        compose.transform(op.constant.linear(), op.constant.translation());
      break;
    case ChainOp::LinearJoint:
      compose.translate(op.base + q[op.joint] * op.vector);
      break;
    case ChainOp::RotaryJoint:
      compose.rotate(op, op.sign * q[op.joint]);
      break;
    case ChainOp::MotionError: {
      const Vec6 c = motionComponents(op, q, dir);
      compose.transform(rotationXYZ(c[kA], c[kB], c[kC]), c.head<3>());
      break;
    }
    case ChainOp::Marker:
      compose.mark(op);
      break;
  }
}

// The product of a program's factors; with `markers` (room for one per marker), the frame at
// each marker in program order.
Pose runProgram(const ChainProgram& program, const double* q, const int* dir,
                ChainFrame* markers = nullptr);

}  // namespace mtacc
