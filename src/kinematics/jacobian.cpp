#include "mtacc/kinematics/jacobian.hpp"

#include <stdexcept>

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

// dF of a hooked factor of element e with respect to p; false when it does not depend on p.
bool factorDerivative(const KinematicModel& m, const ChainElement& e, Hook hook, const Parameter& p, const double* q,
                      const int* dir, Mat4& df) {
  if (e.axis != p.axis) return false;
  const auto axis = static_cast<size_t>(p.axis);
  const double qa = e.joint >= 0 ? q[e.joint] : 0.0;
  const int d = (dir && e.joint >= 0) ? dir[e.joint] : 0;
  const auto& errs = m.errors.axes[axis];
  if (p.kind == ParameterKind::Location && hook == Hook::Location) {
    df = m.locationDerivatives[axis][static_cast<size_t>(p.component)];
    return true;
  }
  if (p.kind == ParameterKind::Location && hook == Hook::LinearJoint) {
    const int own = m.machine->axes[axis].ownComponent();
    Vec3 dt;
    if (p.component == own)
      dt = e.sign * m.tiltedDirections[axis];
    else if (p.component >= 3)
      dt = e.sign * (qa + errs.location[own]) * m.tiltedDirectionDerivatives[axis][static_cast<size_t>(p.component - 3)];
    else
      return false;
    df.setZero();
    df.block<3, 1>(0, 3) = dt;
    return true;
  }
  if (p.kind == ParameterKind::Motion && hook == Hook::Motion) {
    Vec6 comps;
    for (int k = 0; k < 6; ++k) comps[k] = errs.motion[static_cast<size_t>(k)].value(qa, d);
    df = errorTransformDerivative(comps, p.component) * errs.motion[static_cast<size_t>(p.component)].basis(p.index, qa, d);
    return true;
  }
  return false;
}

// Calls add(i, dF_i) for every factor i of the chain whose matrix depends on the parameter:
// d(chain total)/dp = sum prefix[i] * dF_i * suffix[i].
template <class Add>
void forEachFactorDerivative(const KinematicModel& m, const ChainFactors& c, const Parameter& p, const double* q,
                             const int* dir, Add&& add) {
  const ChainElement* element = c.element[static_cast<size_t>(p.axis)];
  if (!element) return;
  Mat4 df;
  for (size_t i = c.range[static_cast<size_t>(p.axis)].first; i < c.range[static_cast<size_t>(p.axis)].second; ++i)
    if (c.factors[i].hook != Hook::None && factorDerivative(m, *element, c.factors[i].hook, p, q, dir, df)) add(i, df);
}

// The frames around every hooked factor of a chain (what the point Jacobian needs, without
// the products of the whole chain at every factor).
struct HookFrame {
  const ChainElement* element;
  Hook hook;
  Pose before, after;
};
struct HookWalk {
  std::vector<HookFrame> hooks;
  std::vector<std::pair<size_t, size_t>> byAxis;  // hooks of each machine axis
  std::vector<Factor> buffer;
  Pose total;
};

void walkHooks(const KinematicModel& m, const std::vector<ChainElement>& chain, const Pose& tail, const double* q,
               const int* dir, HookWalk& w) {
  w.hooks.clear();
  w.byAxis.assign(m.machine->axes.size(), {0, 0});
  Pose acc = Pose::Identity();
  for (const auto& e : chain) {
    w.buffer.clear();
    elementFactors(m, e, e.joint >= 0 ? q[e.joint] : 0.0, (dir && e.joint >= 0) ? dir[e.joint] : 0, w.buffer);
    const size_t begin = w.hooks.size();
    for (const auto& f : w.buffer) {
      if (f.hook == Hook::None) {
        acc = acc * f.pose;
        continue;
      }
      w.hooks.push_back({&e, f.hook, acc, acc * f.pose});
      acc = w.hooks.back().after;
    }
    w.byAxis[static_cast<size_t>(e.axis)] = {begin, w.hooks.size()};
  }
  w.total = acc * tail;
}

// d(chain total)/dp applied to the point whose image under the chain is `point`: each hooked
// factor adds before * dF * (after^-1 point), a direction (dF's last row is 0).
Vec3 hookDerivativeAt(const KinematicModel& m, const HookWalk& w, const Parameter& p, const double* q, const int* dir,
                      const Vec3& point) {
  Vec3 sum = Vec3::Zero();
  Mat4 df;
  const auto [begin, end] = w.byAxis[static_cast<size_t>(p.axis)];
  for (size_t h = begin; h < end; ++h) {
    const HookFrame& f = w.hooks[h];
    if (!factorDerivative(m, *f.element, f.hook, p, q, dir, df)) continue;
    const Vec3 u = f.after.linear().transpose() * (point - f.after.translation());
    sum += f.before.linear() * (df.topLeftCorner<3, 3>() * u + df.block<3, 1>(0, 3));
  }
  return sum;
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

PointJacobian pointJacobian(const KinematicModel& m, const std::vector<Parameter>& parameters, const double* q,
                            const int* dir, const Vec3& toolPoint) {
  if (!m.withErrors) throw std::logic_error("pointJacobian needs a model compiled with errors");
  // Per-thread scratch: this runs once per reading in identifications.
  thread_local HookWalk tool, wp, ref;
  walkHooks(m, m.toolChain, m.toolFrame, q, dir, tool);
  walkHooks(m, m.workpieceChain, m.workpieceFrame, q, dir, wp);
  const Pose wInv = wp.total.inverse();
  const Vec3 inBed = tool.total * toolPoint;
  const Vec3 beforeAlignment = wInv * inBed;
  PointJacobian out;
  out.point = m.alignment * beforeAlignment;
  out.toolRotation = m.alignment.linear() * wInv.linear() * tool.total.linear();
  out.jacobian.resize(3, static_cast<Eigen::Index>(parameters.size()));

  // d(W^-1 T x) = W^-1 (dT x - dW (W^-1 T x)): both chains see the same bed point.
  const bool aligned = m.machine->alignment == WorkpieceAlignment::Machine;
  Mat3 refToWorkpiece = Mat3::Identity();
  Vec3 refPoint = Vec3::Zero();
  if (aligned) {
    walkHooks(m, m.workpieceChain, m.workpieceFrame, m.machine->referencePose.data(), nullptr, ref);
    refToWorkpiece = m.alignment.linear() * ref.total.linear().transpose();
    refPoint = ref.total * beforeAlignment;
  }
  const Mat3 bedToWorkpiece = m.alignment.linear() * wInv.linear();
  for (size_t k = 0; k < parameters.size(); ++k) {
    const Parameter& p = parameters[k];
    Vec3 d = bedToWorkpiece * (hookDerivativeAt(m, tool, p, q, dir, inBed) - hookDerivativeAt(m, wp, p, q, dir, inBed));
    if (aligned) d += refToWorkpiece * hookDerivativeAt(m, ref, p, m.machine->referencePose.data(), nullptr, refPoint);
    out.jacobian.col(static_cast<Eigen::Index>(k)) = d;
  }
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
