#include "mtacc/kinematics/jacobian.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

#include "mtacc/kinematics/forward.hpp"

namespace mtacc {
namespace {

struct ChainFactors {
  std::vector<Factor> factors;
  // Per machine axis: its chain element (or null) and the range of its factors.
  std::vector<const ChainElement*> element;
  std::vector<std::pair<size_t, size_t>> range;
  std::vector<Pose> prefix;  // prefix[i] = F_0 ... F_{i-1}; prefix[n] = total
  std::vector<Pose> suffix;  // suffix[i] = F_{i+1} ... F_n (tail frame included)
  Pose total;
};

// The chain's factors with their prefix and suffix products.
ChainFactors expand(const KinematicModel& m, const std::vector<ChainElement>& chain, const Pose& tail, const double* q,
                    const int* dir) {
  ChainFactors c;
  c.element.assign(m.machine->axes.size(), nullptr);
  c.range.assign(m.machine->axes.size(), {0, 0});
  for (const auto& e : chain) {
    const double qe = e.joint >= 0 ? q[e.joint] : 0.0;
    const int d = (dir && e.joint >= 0) ? dir[e.joint] : 0;
    const size_t begin = c.factors.size();
    elementFactors(m, e, qe, d, c.factors);
    c.element[static_cast<size_t>(e.axis)] = &e;
    c.range[static_cast<size_t>(e.axis)] = {begin, c.factors.size()};
  }
  c.factors.push_back({tail, Hook::None, -1});  // the tool or workpiece frame
  const size_t n = c.factors.size();
  c.prefix.resize(n + 1);
  c.prefix[0] = Pose::Identity();
  for (size_t i = 0; i < n; ++i) c.prefix[i + 1] = c.prefix[i] * c.factors[i].pose;
  c.total = c.prefix[n];
  c.suffix.resize(n);
  Pose acc = Pose::Identity();
  for (size_t i = n; i-- > 0;) {
    c.suffix[i] = acc;
    acc = c.factors[i].pose * acc;
  }
  return c;
}

// dF of a hooked factor of element e with respect to p (the model's own matrix for location
// errors, else computed into `scratch`); null when the factor does not depend on p.
const Mat4* factorDerivative(const KinematicModel& m, const ChainElement& e, Hook hook, const Parameter& p, const double* q,
                             const int* dir, Mat4& scratch) {
  if (e.axis != p.axis) return nullptr;
  const auto axis = static_cast<size_t>(p.axis);
  const double qa = e.joint >= 0 ? q[e.joint] : 0.0;
  const int d = (dir && e.joint >= 0) ? dir[e.joint] : 0;
  const auto& errs = m.errors.axes[axis];
  if (p.kind == ParameterKind::Location && hook == Hook::Location) return &m.locationDerivatives[axis][static_cast<size_t>(p.component)];
  if (p.kind == ParameterKind::Location && hook == Hook::LinearJoint) {
    const int own = m.machine->axes[axis].ownComponent();
    Vec3 dt;
    if (p.component == own)
      dt = e.sign * m.tiltedDirections[axis];
    else if (p.component >= 3)
      dt = e.sign * (qa + errs.location[own]) * m.tiltedDirectionDerivatives[axis][static_cast<size_t>(p.component - 3)];
    else
      return nullptr;
    scratch.setZero();
    scratch.block<3, 1>(0, 3) = dt;
    return &scratch;
  }
  if (p.kind == ParameterKind::Motion && hook == Hook::Motion) {
    Vec6 comps;
    for (int k = 0; k < 6; ++k) comps[k] = errs.motion[static_cast<size_t>(k)].value(qa, d);
    scratch = errorTransformDerivative(comps, p.component) * errs.motion[static_cast<size_t>(p.component)].basis(p.index, qa, d);
    return &scratch;
  }
  return nullptr;
}

// Calls add(i, dF_i) for every factor i of the chain whose matrix depends on the parameter:
// d(chain total)/dp = sum prefix[i] * dF_i * suffix[i].
template <class Add>
void forEachFactorDerivative(const KinematicModel& m, const ChainFactors& c, const Parameter& p, const double* q,
                             const int* dir, Add&& add) {
  const ChainElement* element = c.element[static_cast<size_t>(p.axis)];
  if (!element) return;
  Mat4 scratch;
  for (size_t i = c.range[static_cast<size_t>(p.axis)].first; i < c.range[static_cast<size_t>(p.axis)].second; ++i) {
    if (c.factors[i].hook == Hook::None) continue;
    if (const Mat4* df = factorDerivative(m, *element, c.factors[i].hook, p, q, dir, scratch)) add(i, *df);
  }
}

Mat4 chainDerivative(const KinematicModel& m, const ChainFactors& c, const Parameter& p, const double* q,
                     const int* dir) {
  Mat4 sum = Mat4::Zero();
  forEachFactorDerivative(m, c, p, q, dir,
                          [&](size_t i, const Mat4& df) { sum += c.prefix[i].matrix() * df * c.suffix[i].matrix(); });
  return sum;
}

}  // namespace

ParameterJacobian parameterJacobian(const KinematicModel& m, const std::vector<Parameter>& parameters, const double* q,
                                    const int* dir) {
  if (!m.withErrors) throw std::logic_error("parameterJacobian needs a model compiled with errors");
  const auto tool = expand(m, m.toolChain, m.toolFrame, q, dir);
  const auto wp = expand(m, m.workpieceChain, m.workpieceFrame, q, dir);
  const Mat4 wInv = wp.total.inverse().matrix();
  const Mat4 toolTotal = tool.total.matrix();
  const Mat4 pose = m.alignment.matrix() * wInv * toolTotal;
  const Mat3 r = pose.topLeftCorner<3, 3>();

  const bool aligned = m.machine->alignment == WorkpieceAlignment::Machine;
  ChainFactors ref;
  Mat4 nominalRefInv = Mat4::Identity();
  if (aligned) {
    const auto& qr = m.machine->referencePose;
    ref = expand(m, m.workpieceChain, m.workpieceFrame, qr.data(), nullptr);
    // M_WC = N^-1 * W_act(q_ref)  =>  N^-1 = M_WC * W_act(q_ref)^-1
    nominalRefInv = m.alignment.matrix() * ref.total.inverse().matrix();
  }

  Pose nominalPose = Pose::Identity();
  {
    const KinematicModel nominal = compile(m.machine, m.errors, false);
    nominalPose = toolInWorkpiece(nominal, q);
  }
  const Vec3 rotErr = rotationVector(r * nominalPose.linear().transpose());
  const Mat3 jInv = leftJacobianInverse(rotErr);

  ParameterJacobian jac(6, static_cast<Eigen::Index>(parameters.size()));
  for (size_t k = 0; k < parameters.size(); ++k) {
    const Parameter& p = parameters[k];
    Mat4 d = m.alignment.matrix() * wInv * chainDerivative(m, tool, p, q, dir);
    d -= m.alignment.matrix() * wInv * chainDerivative(m, wp, p, q, dir) * wInv * toolTotal;
    if (aligned) d += nominalRefInv * chainDerivative(m, ref, p, m.machine->referencePose.data(), nullptr) * wInv * toolTotal;
    const Mat3 omegaHat = d.topLeftCorner<3, 3>() * r.transpose();
    const Vec3 omega(omegaHat(2, 1), omegaHat(0, 2), omegaHat(1, 0));
    jac.block<3, 1>(0, static_cast<Eigen::Index>(k)) = d.block<3, 1>(0, 3);
    jac.block<3, 1>(3, static_cast<Eigen::Index>(k)) = jInv * omega;
  }
  return jac;
}

PointJacobianPlan planPointJacobian(const KinematicModel& m, const std::vector<Parameter>& parameters) {
  if (!m.withErrors) throw std::logic_error("pointJacobian needs a model compiled with errors");
  using Term = PointJacobianPlan::Term;
  PointJacobianPlan plan;
  plan.model = &m;
  plan.parameters = parameters;
  const std::vector<double> zero(static_cast<size_t>(m.jointCount), 0.0);
  Mat4 scratch;
  auto addChain = [&](int chain, const std::vector<ChainOp>& program, const std::vector<ChainElement>& elements) {
    int factor = 0;
    for (size_t i = 0; i < program.size(); ++i) {
      const ChainOp& op = program[i];
      if (op.kind != ChainOp::HookMarker) continue;
      ++i;  // markers come in pairs around their factor
      while (program[i].kind != ChainOp::HookMarker) ++i;
      if (factor == PointJacobianPlan::kMaxFactors)
        throw std::invalid_argument("pointJacobian: a chain has more than " +
                                    std::to_string(PointJacobianPlan::kMaxFactors) + " factors with error parameters");
      const auto element = std::find_if(elements.begin(), elements.end(), [&](const ChainElement& e) { return e.axis == op.axis; });
      for (size_t k = 0; k < parameters.size(); ++k) {
        const Parameter& p = parameters[k];
        const Mat4* df = factorDerivative(m, *element, op.hook, p, zero.data(), nullptr, scratch);
        if (!df) continue;
        Term t{static_cast<int>(k), chain, factor, &*element, op.hook, Term::PerPose};
        if (op.hook == Hook::Location) {
          t.kind = Term::Constant;
          t.rotation = df->topLeftCorner<3, 3>();
          t.translation = df->block<3, 1>(0, 3);
          t.rotates = !t.rotation.isZero(0.0);
        } else if (op.hook == Hook::LinearJoint) {
          // factorDerivative is affine in the joint value: sample it at 0 and 1.
          t.kind = Term::JointTranslation;
          t.translation = df->block<3, 1>(0, 3);
          std::vector<double> one = zero;
          one[static_cast<size_t>(element->joint)] = 1.0;
          t.translationPerUnit = factorDerivative(m, *element, op.hook, p, one.data(), nullptr, scratch)->block<3, 1>(0, 3) -
                                 t.translation;
        }
        plan.terms.push_back(t);
      }
      ++factor;
    }
  };
  addChain(0, m.toolHookProgram, m.toolChain);
  addChain(1, m.workpieceHookProgram, m.workpieceChain);
  if (m.machine->alignment == WorkpieceAlignment::Machine) {
    addChain(2, m.workpieceHookProgram, m.workpieceChain);
    plan.referenceFrames.resize(2 * PointJacobianPlan::kMaxFactors);
    plan.reference = runHookProgram(m, m.workpieceHookProgram, m.machine->referencePose.data(), nullptr,
                                    plan.referenceFrames.data());
    plan.referenceToWorkpiece = m.alignment.linear() * plan.reference.linear().transpose();
  }
  return plan;
}

void pointJacobian(const PointJacobianPlan& plan, const double* q, const int* dir, const Vec3& toolPoint, PointJacobian& out) {
  constexpr int kMax = PointJacobianPlan::kMaxFactors;
  const KinematicModel& m = *plan.model;
  std::array<ChainFrame, 2 * kMax> toolFrames, workpieceFrames;
  const Pose tool = runHookProgram(m, m.toolHookProgram, q, dir, toolFrames.data());
  const Pose wpInv = runHookProgram(m, m.workpieceHookProgram, q, dir, workpieceFrames.data()).inverse(Eigen::Isometry);
  const Vec3 inBed = tool * toolPoint;
  const Vec3 beforeAlignment = wpInv * inBed;
  // The map of a direction in the bed frame to the workpiece frame.
  const Mat3 bedToWorkpiece = m.aligned ? Mat3(m.alignment.linear() * wpInv.linear()) : wpInv.linear();
  out.point = m.aligned ? Vec3(m.alignment * beforeAlignment) : beforeAlignment;
  out.toolRotation = bedToWorkpiece * tool.linear();

  // d(W^-1 T x) = W^-1 (dT x - dW (W^-1 T x)): both chains see the same bed point. A hooked
  // factor F between the frames B (before) and A (after) adds B dF A^-1 x.
  const bool aligned = m.machine->alignment == WorkpieceAlignment::Machine;
  const ChainFrame* frames[3] = {toolFrames.data(), workpieceFrames.data(), plan.referenceFrames.data()};
  const Vec3 points[3] = {inBed, inBed, aligned ? Vec3(plan.reference * beforeAlignment) : Vec3::Zero()};
  const Mat3 toWorkpiece[3] = {bedToWorkpiece, -bedToWorkpiece, plan.referenceToWorkpiece};
  // Per hooked factor: the map of a direction before it to the workpiece frame, and the point
  // in the frame after it (computed when a term first asks for them).
  std::array<Mat3, kMax> maps[3];
  std::array<Vec3, kMax> local[3];
  std::array<bool, kMax> ready[3] = {};
  const double* qOf[3] = {q, q, m.machine->referencePose.data()};
  const int* dirOf[3] = {dir, dir, nullptr};
  out.jacobian.setZero(3, static_cast<Eigen::Index>(plan.parameters.size()));
  Mat4 scratch;
  for (const auto& t : plan.terms) {
    const auto c = static_cast<size_t>(t.chain), h = static_cast<size_t>(t.factor);
    if (!ready[c][h]) {
      const ChainFrame& before = frames[c][2 * h];
      const ChainFrame& after = frames[c][2 * h + 1];
      maps[c][h].noalias() = toWorkpiece[c] * before.rotation;
      local[c][h].noalias() = after.rotation.transpose() * (points[c] - after.origin);
      ready[c][h] = true;
    }
    Vec3 d;
    if (t.kind == PointJacobianPlan::Term::Constant) {
      d = t.rotates ? Vec3(t.rotation * local[c][h] + t.translation) : t.translation;
    } else if (t.kind == PointJacobianPlan::Term::JointTranslation) {
      d = t.translation + qOf[c][t.element->joint] * t.translationPerUnit;
    } else {
      const Mat4& df = *factorDerivative(m, *t.element, t.hook, plan.parameters[static_cast<size_t>(t.parameter)], qOf[c],
                                         dirOf[c], scratch);
      d = df.topLeftCorner<3, 3>() * local[c][h] + df.block<3, 1>(0, 3);
    }
    out.jacobian.col(t.parameter).noalias() += maps[c][h] * d;
  }
}

PointJacobian pointJacobian(const KinematicModel& m, const std::vector<Parameter>& parameters, const double* q,
                            const int* dir, const Vec3& toolPoint) {
  PointJacobian out;
  pointJacobian(planPointJacobian(m, parameters), q, dir, toolPoint, out);
  return out;
}

std::vector<Pose> errorFrames(const KinematicModel& m, const double* q) {
  std::vector<Pose> frames(m.machine->axes.size(), Pose::Identity());
  auto walk = [&](const std::vector<ChainElement>& chain) {
    Pose t = Pose::Identity();
    for (const auto& e : chain) {
      const double qe = e.joint >= 0 ? q[e.joint] : 0.0;
      Pose point = Pose::Identity();
      point.translation() = e.location;
      Pose before = Pose::Identity();
      before.translation() = e.offset;
      if (m.withErrors && e.type != AxisType::Linear)
        before = before * point * errorTransform(m.errors.axes[static_cast<size_t>(e.axis)].location) * point.inverse();
      const Pose frame = e.frame == ErrorFrame::Fixed ? before : before * jointPose(m, e, qe);
      frames[static_cast<size_t>(e.axis)] = t * frame * point;
      std::vector<Factor> factors;
      elementFactors(m, e, qe, 0, factors);
      for (const auto& f : factors) t = t * f.pose;
    }
  };
  walk(m.toolChain);
  walk(m.workpieceChain);
  return frames;
}

}  // namespace mtacc
