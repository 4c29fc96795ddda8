#include "mtacc/kinematics/kinematic_model.hpp"

#include "mtacc/kinematics/forward.hpp"

#include <algorithm>

namespace mtacc {
namespace {

Pose translation(const Vec3& t) {
  Pose p = Pose::Identity();
  p.translation() = t;
  return p;
}

bool hasMotionErrors(const KinematicModel& m, int axis) {
  if (!m.withErrors) return false;
  for (const auto& f : m.errors.axes[static_cast<size_t>(axis)].motion)
    if (!f.empty()) return true;
  return false;
}

Vec6 motionComponents(const KinematicModel& m, int axis, double q, int dir) {
  Vec6 c;
  const auto& motion = m.errors.axes[static_cast<size_t>(axis)].motion;
  for (int k = 0; k < 6; ++k) c[k] = motion[static_cast<size_t>(k)].value(q, dir);
  return c;
}

std::vector<ChainElement> buildChain(const Machine& machine, const std::vector<int>& indices, double sign) {
  std::vector<ChainElement> chain;
  for (int i : indices) {
    const Axis& a = machine.axes[static_cast<size_t>(i)];
    ChainElement e;
    e.axis = i;
    e.joint = a.commanded() ? i : -1;  // commanded axes come first in Machine::axes
    e.type = a.type;
    e.frame = a.errorFrame;
    e.sign = sign;
    e.offset = a.offset;
    e.direction = a.direction;
    e.location = a.type == AxisType::Linear ? Vec3::Zero() : a.location;
    chain.push_back(e);
  }
  return chain;
}

// Merges runs of constant factors; joint and motion-error factors become operations. With
// markHooks, every factor carrying error parameters stands alone between two hook markers.
std::vector<ChainOp> buildProgram(const KinematicModel& m, const std::vector<ChainElement>& chain, const Pose& tail,
                                  bool markHooks) {
  std::vector<ChainOp> ops;
  auto pushConstant = [&](const Pose& p) {
    if (p.isApprox(Pose::Identity(), 0.0)) return;
    if (!ops.empty() && ops.back().kind == ChainOp::Constant) {
      ops.back().constant = ops.back().constant * p;
      return;
    }
    ChainOp op;
    op.constant = p;
    ops.push_back(op);
  };
  for (const auto& e : chain) {
    const bool motion = hasMotionErrors(m, e.axis);
    auto pushMarker = [&](Hook hook) {
      if (!markHooks) return;
      ChainOp op;
      op.kind = ChainOp::HookMarker;
      op.axis = e.axis;
      op.hook = hook;
      ops.push_back(op);
    };
    auto pushMotion = [&]() {
      pushConstant(translation(e.location));
      pushMarker(Hook::Motion);
      ChainOp op;
      op.kind = ChainOp::MotionError;
      op.joint = e.joint;
      op.axis = e.axis;
      const auto& motion = m.errors.axes[static_cast<size_t>(e.axis)].motion;
      std::vector<std::vector<const TableTerm*>> tables;
      for (int k = 0; k < 6; ++k) {
        for (const auto& term : motion[static_cast<size_t>(k)].terms()) {
          const auto* table = std::get_if<TableTerm>(&term);
          if (!table) {
            op.residualMask |= 1u << k;
            continue;
          }
          auto same = std::find_if(op.tableGroups.begin(), op.tableGroups.end(),
                                   [&](const auto& g) { return g.positions == table->positions; });
          if (same == op.tableGroups.end()) {
            same = op.tableGroups.emplace(op.tableGroups.end());
            same->positions = table->positions;
            same->uniform = table->uniform;
            same->inverseStep = table->inverseStep;
            tables.emplace_back();
          }
          same->components.push_back(k);
          tables[static_cast<size_t>(same - op.tableGroups.begin())].push_back(table);
        }
      }
      for (size_t g = 0; g < op.tableGroups.size(); ++g) {
        auto& group = op.tableGroups[g];
        for (size_t i = 0; i + 1 < group.positions.size(); ++i)
          for (int power = 0; power < 4; ++power)
            for (const TableTerm* t : tables[g]) group.coefficients.push_back(t->cubic[i][static_cast<size_t>(power)]);
      }
      op.sixTablesOnOneGrid = op.residualMask == 0 && op.tableGroups.size() == 1 &&
                              op.tableGroups[0].components == std::vector<int>{0, 1, 2, 3, 4, 5};
      ops.push_back(op);
      pushMarker(Hook::Motion);
      pushConstant(translation(-e.location));
    };
    pushConstant(translation(e.offset));
    if (m.withErrors && e.type != AxisType::Linear) {
      const Pose& error = m.locationTransforms[static_cast<size_t>(e.axis)];
      if (markHooks) {
        pushConstant(translation(e.location));
        pushMarker(Hook::Location);
        ops.push_back(ChainOp{});  // the error factor alone, even when it is the identity
        ops.back().constant = error;
        pushMarker(Hook::Location);
        pushConstant(translation(-e.location));
      } else {
        pushConstant(translation(e.location) * error * translation(-e.location));
      }
    }
    if (motion && e.frame == ErrorFrame::Fixed) pushMotion();
    if (e.type == AxisType::Linear) {
      ChainOp op;
      op.kind = ChainOp::LinearJoint;
      op.joint = e.joint;
      op.base = linearJointTranslation(m, e, 0.0);
      op.vector = linearJointTranslation(m, e, 1.0) - op.base;
      pushMarker(Hook::LinearJoint);
      ops.push_back(op);
      pushMarker(Hook::LinearJoint);
    } else if (e.type == AxisType::Rotary) {
      ChainOp op;
      op.kind = ChainOp::RotaryJoint;
      op.joint = e.joint;
      op.vector = e.direction;
      op.base = e.location;
      op.sign = e.sign;
      op.hasBase = !e.location.isZero(0.0);
      for (int k = 0; k < 3; ++k)
        if (e.direction[k] == 1.0) op.principal = k;
      ops.push_back(op);
    }
    if (motion && e.frame == ErrorFrame::Moving) pushMotion();
  }
  pushConstant(tail);
  for (auto& op : ops)
    if (op.kind == ChainOp::Constant) op.translationOnly = op.constant.linear().isIdentity(0.0);
  return ops;
}

}  // namespace

Vec3 linearJointTranslation(const KinematicModel& m, const ChainElement& e, double q) {
  if (!m.withErrors) return e.sign * q * e.direction;
  const Vec6& loc = m.errors.axes[static_cast<size_t>(e.axis)].location;
  const double zero = loc[m.machine->axes[static_cast<size_t>(e.axis)].ownComponent()];
  return e.sign * (q + zero) * m.tiltedDirections[static_cast<size_t>(e.axis)];
}

Pose jointPose(const KinematicModel& m, const ChainElement& e, double q) {
  Pose j = Pose::Identity();
  if (e.type == AxisType::Linear) {
    j.translation() = linearJointTranslation(m, e, q);
  } else if (e.type == AxisType::Rotary) {
    j.linear() = rotationAbout(e.direction, e.sign * q);
    j.translation() = e.location - j.linear() * e.location;
  }
  return j;
}

void elementFactors(const KinematicModel& m, const ChainElement& e, double q, int dir, std::vector<Factor>& out) {
  const bool motion = hasMotionErrors(m, e.axis);
  // Constant translations by zero are left out.
  auto pushTranslation = [&](const Vec3& t) {
    if (!t.isZero(0.0)) out.push_back({translation(t), Hook::None, e.axis});
  };
  auto pushMotion = [&]() {
    pushTranslation(e.location);
    out.push_back({errorTransform(motionComponents(m, e.axis, q, dir)), Hook::Motion, e.axis});
    pushTranslation(-e.location);
  };
  pushTranslation(e.offset);
  if (m.withErrors && e.type != AxisType::Linear) {
    pushTranslation(e.location);
    out.push_back({m.locationTransforms[static_cast<size_t>(e.axis)], Hook::Location, e.axis});
    pushTranslation(-e.location);
  }
  if (motion && e.frame == ErrorFrame::Fixed) pushMotion();
  if (e.type != AxisType::Spindle)
    out.push_back({jointPose(m, e, q), e.type == AxisType::Linear ? Hook::LinearJoint : Hook::None, e.axis});
  if (motion && e.frame == ErrorFrame::Moving) pushMotion();
}

KinematicModel compile(std::shared_ptr<const Machine> machine, const ErrorModel& errors, bool withErrors) {
  KinematicModel m;
  m.machine = machine;
  m.errors = errors;
  m.withErrors = withErrors;
  m.jointCount = machine->commandedCount();
  if (withErrors)
    for (size_t a = 0; a < errors.axes.size(); ++a) {
      const Vec6& loc = errors.axes[a].location;
      m.locationTransforms.push_back(errorTransform(loc));
      std::array<Mat4, 6> d;
      for (int k = 0; k < 6; ++k) d[static_cast<size_t>(k)] = errorTransformDerivative(loc, k);
      m.locationDerivatives.push_back(d);
      const Vec3& dir = machine->axes[a].direction;
      m.tiltedDirections.push_back(rotationXYZ(loc[kA], loc[kB], loc[kC]) * dir);
      std::array<Vec3, 3> t;
      for (int k = 0; k < 3; ++k) t[static_cast<size_t>(k)] = rotationXYZDerivative(loc[kA], loc[kB], loc[kC], k) * dir;
      m.tiltedDirectionDerivatives.push_back(t);
    }
  m.toolChain = buildChain(*machine, machine->toolChain, +1.0);
  m.workpieceChain = buildChain(*machine, machine->workpieceChain, -1.0);
  m.toolFrame = translation(machine->toolOffset);
  m.workpieceFrame = translation(machine->workpieceOffset);
  m.toolProgram = buildProgram(m, m.toolChain, m.toolFrame, false);
  m.workpieceProgram = buildProgram(m, m.workpieceChain, m.workpieceFrame, false);
  if (withErrors) {
    m.toolHookProgram = buildProgram(m, m.toolChain, m.toolFrame, true);
    m.workpieceHookProgram = buildProgram(m, m.workpieceChain, m.workpieceFrame, true);
  }
  m.toolDirection = machine->toolDirection;
  m.tcpStart = Vec3::Zero();
  m.toolDirectionStart = m.toolDirection;
  m.toolOpsPerPose = m.toolProgram.size();
  if (!m.toolProgram.empty() && m.toolProgram.back().kind == ChainOp::Constant) {
    const Pose& c = m.toolProgram.back().constant;
    m.tcpStart = c.translation();
    m.toolDirectionStart = c.linear() * m.toolDirection;
    --m.toolOpsPerPose;
  }
  if (withErrors && machine->alignment == WorkpieceAlignment::Machine) {
    // Seed 001 eqs. 10-12: the workpiece is set up aligned with the machine at the reference
    // pose, so M_WC = W_nominal(q_ref)^-1 * W_actual(q_ref).
    const KinematicModel nominal = compile(machine, errors, false);
    const auto& q = machine->referencePose;
    m.alignment = workpiecePose(nominal, q.data(), nullptr).inverse() * workpiecePose(m, q.data(), nullptr);
    m.aligned = true;
  }
  return m;
}

KinematicModel compileNominal(std::shared_ptr<const Machine> machine) {
  return compile(machine, ErrorModel::zero(*machine), false);
}

}  // namespace mtacc
