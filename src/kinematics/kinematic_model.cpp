#include "mtacc/kinematics/kinematic_model.hpp"

#include <algorithm>
#include <cmath>

#include "chain_program.hpp"

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
  return std::any_of(m.errors.stiffness.begin(), m.errors.stiffness.end(), [&](const auto& s) { return s.axis == axis; });
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

// Translation of a linear joint with its location errors (tilt of the direction, zero offset).
Vec3 linearJointTranslation(const KinematicModel& m, const ChainPrograms& c, const ChainElement& e, double q) {
  if (!m.withErrors) return e.sign * q * e.direction;
  const Vec6& loc = m.errors.axes[static_cast<size_t>(e.axis)].location;
  const double zero = loc[m.machine->axes[static_cast<size_t>(e.axis)].ownComponent()];
  return e.sign * (q + zero) * c.tiltedDirections[static_cast<size_t>(e.axis)];
}

// Sorted by zero and frequency; a group whose frequency is an integer multiple (up to 16) of
// the last base group at the same zero is evaluated from it (ChainOp::HarmonicGroup).
void orderHarmonicGroups(std::vector<ChainOp::HarmonicGroup>& groups) {
  std::sort(groups.begin(), groups.end(),
            [](const auto& a, const auto& b) { return a.zero != b.zero ? a.zero < b.zero : a.omega < b.omega; });
  const ChainOp::HarmonicGroup* base = nullptr;
  for (auto& g : groups) {
    const double ratio = base && base->zero == g.zero ? g.omega / base->omega : 0.0;
    const double multiple = std::round(ratio);
    if (multiple >= 2 && multiple <= 16 && std::abs(ratio - multiple) <= 1e-12 * multiple) {
      g.multiple = static_cast<int>(multiple);
    } else {
      g.multiple = 1;
      base = &g;
    }
  }
}

ChainOp motionErrorOp(const Machine& machine, const ErrorModel& errors, const ChainElement& e) {
  ChainOp op;
  op.kind = ChainOp::MotionError;
  op.joint = e.joint;
  op.axis = e.axis;
  const auto& motion = errors.axes[static_cast<size_t>(e.axis)].motion;
  std::vector<std::vector<const TableTerm*>> tables;
  for (int k = 0; k < 6; ++k) {
    for (const auto& term : motion[static_cast<size_t>(k)].terms()) {
      if (const auto* h = std::get_if<HarmonicTerm>(&term)) {
        const double omega = 2.0 * kPi * h->order / h->period;
        auto same = std::find_if(op.harmonicGroups.begin(), op.harmonicGroups.end(),
                                 [&](const auto& g) { return g.omega == omega && g.zero == h->zero; });
        if (same == op.harmonicGroups.end()) same = op.harmonicGroups.insert(op.harmonicGroups.end(), {omega, h->zero, 1});
        same->cosine[k] += h->amplitude * std::cos(h->phase);
        same->sine[k] += h->amplitude * std::sin(h->phase);
        continue;
      }
      if (const auto* p = std::get_if<PolynomialTerm>(&term)) {
        if (p->coefficients.empty()) continue;
        auto same = std::find_if(op.polynomialGroups.begin(), op.polynomialGroups.end(),
                                 [&](const auto& g) { return g.zero == p->zero && g.scale == p->scale; });
        if (same == op.polynomialGroups.end()) same = op.polynomialGroups.insert(op.polynomialGroups.end(), {p->zero, p->scale, {}});
        if (same->powers.size() < p->coefficients.size()) same->powers.resize(p->coefficients.size(), Vec6::Zero());
        for (size_t power = 0; power < p->coefficients.size(); ++power) same->powers[power][k] += p->coefficients[power];
        continue;
      }
      if (const auto* p = std::get_if<PiecewiseTerm>(&term)) {
        op.piecewise.push_back({k, CompiledPiecewise(*p)});
        continue;
      }
      if (const auto* r = std::get_if<ReversalTerm>(&term)) {
        op.halfReversal[k] += 0.5 * r->width;
        continue;
      }
      const auto* table = std::get_if<TableTerm>(&term);
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
  for (const auto& s : errors.stiffness) {
    if (s.axis != e.axis) continue;
    const int otherJoint = s.otherAxis >= 0 && machine.axes[static_cast<size_t>(s.otherAxis)].commanded() ? s.otherAxis : -1;
    op.stiffness.push_back({s.component, otherJoint, s.loadFactor(errors.workpieceLoad), s});
  }
  orderHarmonicGroups(op.harmonicGroups);
  op.sixTablesOnOneGrid = op.harmonicGroups.empty() && op.polynomialGroups.empty() && op.piecewise.empty() && op.stiffness.empty() &&
                          op.halfReversal.isZero(0.0) &&
                          op.tableGroups.size() == 1 &&
                          op.tableGroups[0].components == std::vector<int>{0, 1, 2, 3, 4, 5};
  return op;
}

enum class Markers { None, Hooks, ErrorFrames };

// The one place that writes the factor order of a chain (see ChainElement). Runs of constant
// factors are merged; joint and motion-error factors become operations. With Hooks, every
// factor carrying error parameters stands alone between two markers; with ErrorFrames, a
// marker records where each axis's component errors act.
ChainProgram buildProgram(const KinematicModel& m, const ChainPrograms& c, const std::vector<ChainElement>& chain,
                          const Pose& tail, Markers markers) {
  ChainProgram ops;
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
  auto pushMarker = [&](Markers when, Hook hook, int axis) {
    if (markers != when) return;
    ChainOp op;
    op.kind = ChainOp::Marker;
    op.axis = axis;
    op.hook = hook;
    ops.push_back(op);
  };
  for (const auto& e : chain) {
    const bool motion = hasMotionErrors(m, e.axis);
    auto pushErrorFrame = [&]() {  // with the motion errors when the axis has them
      if (!motion && markers != Markers::ErrorFrames) return;
      pushConstant(translation(e.location));
      pushMarker(Markers::ErrorFrames, Hook::ErrorFrame, e.axis);
      if (motion) {
        pushMarker(Markers::Hooks, Hook::Motion, e.axis);
        ops.push_back(motionErrorOp(*m.machine, m.errors, e));
        pushMarker(Markers::Hooks, Hook::Motion, e.axis);
      }
      pushConstant(translation(-e.location));
    };
    pushConstant(translation(e.offset));
    if (m.withErrors && e.type != AxisType::Linear) {
      const Pose& error = c.locationTransforms[static_cast<size_t>(e.axis)];
      if (markers == Markers::Hooks) {
        pushConstant(translation(e.location));
        pushMarker(Markers::Hooks, Hook::Location, e.axis);
        ops.push_back(ChainOp{});  // the error factor alone, even when it is the identity
        ops.back().constant = error;
        pushMarker(Markers::Hooks, Hook::Location, e.axis);
        pushConstant(translation(-e.location));
      } else {
        pushConstant(translation(e.location) * error * translation(-e.location));
      }
    }
    if (e.frame == ErrorFrame::Fixed) pushErrorFrame();
    if (e.type == AxisType::Linear) {
      ChainOp op;
      op.kind = ChainOp::LinearJoint;
      op.joint = e.joint;
      op.axis = e.axis;
      op.base = linearJointTranslation(m, c, e, 0.0);
      op.vector = linearJointTranslation(m, c, e, 1.0) - op.base;
      pushMarker(Markers::Hooks, Hook::LinearJoint, e.axis);
      ops.push_back(op);
      pushMarker(Markers::Hooks, Hook::LinearJoint, e.axis);
    } else if (e.type == AxisType::Rotary) {
      ChainOp op;
      op.kind = ChainOp::RotaryJoint;
      op.joint = e.joint;
      op.axis = e.axis;
      op.vector = e.direction;
      op.base = e.location;
      op.sign = e.sign;
      op.hasBase = !e.location.isZero(0.0);
      for (int k = 0; k < 3; ++k)
        if (e.direction[k] == 1.0) op.principal = k;
      ops.push_back(op);
    }
    if (e.frame == ErrorFrame::Moving) pushErrorFrame();
  }
  pushConstant(tail);
  for (auto& op : ops)
    if (op.kind == ChainOp::Constant) op.translationOnly = op.constant.linear().isIdentity(0.0);
  return ops;
}

KinematicModel compileModel(std::shared_ptr<const Machine> machine, const ErrorModel& errors, bool withErrors,
                            const std::vector<Parameter>& jacobianParameters) {
  KinematicModel m;
  m.machine = machine;
  m.errors = errors;
  m.withErrors = withErrors;
  m.jointCount = machine->commandedCount();
  auto c = std::make_shared<ChainPrograms>();
  if (withErrors)
    for (size_t a = 0; a < errors.axes.size(); ++a) {
      const Vec6& loc = errors.axes[a].location;
      c->locationTransforms.push_back(errorTransform(loc));
      std::array<Mat4, 6> d;
      for (int k = 0; k < 6; ++k) d[static_cast<size_t>(k)] = errorTransformDerivative(loc, k);
      c->locationDerivatives.push_back(d);
      const Vec3& dir = machine->axes[a].direction;
      c->tiltedDirections.push_back(rotationXYZ(loc[kA], loc[kB], loc[kC]) * dir);
      std::array<Vec3, 3> t;
      for (int k = 0; k < 3; ++k) t[static_cast<size_t>(k)] = rotationXYZDerivative(loc[kA], loc[kB], loc[kC], k) * dir;
      c->tiltedDirectionDerivatives.push_back(t);
    }
  c->toolChain = buildChain(*machine, machine->toolChain, +1.0);
  c->workpieceChain = buildChain(*machine, machine->workpieceChain, -1.0);
  const Pose toolFrame = translation(machine->toolOffset);
  const Pose workpieceFrame = translation(machine->workpieceOffset);
  c->toolProgram = buildProgram(m, *c, c->toolChain, toolFrame, Markers::None);
  c->workpieceProgram = buildProgram(m, *c, c->workpieceChain, workpieceFrame, Markers::None);
  if (withErrors) {
    c->toolHookProgram = buildProgram(m, *c, c->toolChain, toolFrame, Markers::Hooks);
    c->workpieceHookProgram = buildProgram(m, *c, c->workpieceChain, workpieceFrame, Markers::Hooks);
  }
  c->toolFrameProgram = buildProgram(m, *c, c->toolChain, toolFrame, Markers::ErrorFrames);
  c->workpieceFrameProgram = buildProgram(m, *c, c->workpieceChain, workpieceFrame, Markers::ErrorFrames);
  c->tcpStart = Vec3::Zero();
  c->toolRotationStart = Mat3::Identity();
  c->toolDirectionStart = machine->toolDirection;
  c->toolOpsPerPose = c->toolProgram.size();
  if (!c->toolProgram.empty() && c->toolProgram.back().kind == ChainOp::Constant) {
    const Pose& last = c->toolProgram.back().constant;
    c->tcpStart = last.translation();
    c->toolRotationStart = last.linear();
    c->toolDirectionStart = last.linear() * machine->toolDirection;
    --c->toolOpsPerPose;
  }
  if (withErrors && machine->alignment == WorkpieceAlignment::Machine) {
    // Seed 001 eqs. 10-12: the workpiece is set up aligned with the machine at the reference
    // pose, so M_WC = W_nominal(q_ref)^-1 * W_actual(q_ref).
    const KinematicModel nominal = compileModel(machine, errors, false, {});
    const double* q = machine->referencePose.data();
    m.alignment = runProgram(nominal.chains->workpieceProgram, q, nullptr).inverse() *
                  runProgram(c->workpieceProgram, q, nullptr);
    m.aligned = true;
  }
  m.parameters = jacobianParameters;
  if (withErrors) planJacobian(m, *c);
  m.chains = std::move(c);
  return m;
}

}  // namespace

KinematicModel compile(std::shared_ptr<const Machine> machine, const ErrorModel& errors,
                       const std::vector<Parameter>& jacobianParameters) {
  return compileModel(std::move(machine), errors, true, jacobianParameters);
}

KinematicModel compileNominal(std::shared_ptr<const Machine> machine) {
  const ErrorModel zero = ErrorModel::zero(*machine);
  return compileModel(std::move(machine), zero, false, {});
}

}  // namespace mtacc
