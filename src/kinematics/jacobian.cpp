#include "mtacc/kinematics/jacobian.hpp"

#include <stdexcept>

#include "mtacc/kinematics/forward.hpp"

namespace mtacc {
namespace {

struct ChainFactors {
  std::vector<Factor> factors;
  std::vector<Mat4> prefix;  // prefix[i] = F_0 ... F_{i-1}
  std::vector<Mat4> suffix;  // suffix[i] = F_{i+1} ... F_n (tail frame included)
  Mat4 total;
};

ChainFactors expand(const KinematicModel& m, const std::vector<ChainElement>& chain, const Pose& tail, const double* q,
                    const int* dir) {
  ChainFactors c;
  for (const auto& e : chain) {
    const double qe = e.joint >= 0 ? q[e.joint] : 0.0;
    const int d = (dir && e.joint >= 0) ? dir[e.joint] : 0;
    elementFactors(m, e, qe, d, c.factors);
  }
  c.factors.push_back({tail, Hook::None, -1});  // the tool or workpiece frame
  const size_t n = c.factors.size();
  c.prefix.resize(n);
  c.suffix.resize(n);
  Mat4 acc = Mat4::Identity();
  for (size_t i = 0; i < n; ++i) {
    c.prefix[i] = acc;
    acc = acc * c.factors[i].pose.matrix();
  }
  c.total = acc;
  acc = Mat4::Identity();
  for (size_t i = n; i-- > 0;) {
    c.suffix[i] = acc;
    acc = c.factors[i].pose.matrix() * acc;
  }
  return c;
}

// d(chain total) / d(parameter) for one chain; zero when the parameter is not in it.
Mat4 chainDerivative(const KinematicModel& m, const ChainFactors& c, const std::vector<ChainElement>& chain,
                     const Parameter& p, const double* q, const int* dir) {
  Mat4 sum = Mat4::Zero();
  const ChainElement* element = nullptr;
  for (const auto& e : chain)
    if (e.axis == p.axis) element = &e;
  if (!element) return sum;
  const double qa = element->joint >= 0 ? q[element->joint] : 0.0;
  const int d = (dir && element->joint >= 0) ? dir[element->joint] : 0;
  const auto& errs = m.errors.axes[static_cast<size_t>(p.axis)];
  for (size_t i = 0; i < c.factors.size(); ++i) {
    const Factor& f = c.factors[i];
    if (f.axis != p.axis || f.hook == Hook::None) continue;
    Mat4 df = Mat4::Zero();
    if (p.kind == ParameterKind::Location && f.hook == Hook::Location) {
      df = errorTransformDerivative(errs.location, p.component);
    } else if (p.kind == ParameterKind::Location && f.hook == Hook::LinearJoint) {
      const Vec6& loc = errs.location;
      const int own = m.machine->axes[static_cast<size_t>(p.axis)].ownComponent();
      Vec3 dt;
      if (p.component == own)
        dt = element->sign * (rotationXYZ(loc[kA], loc[kB], loc[kC]) * element->direction);
      else if (p.component >= 3)
        dt = element->sign * (qa + loc[own]) *
             (rotationXYZDerivative(loc[kA], loc[kB], loc[kC], p.component - 3) * element->direction);
      else
        continue;
      df.block<3, 1>(0, 3) = dt;
    } else if (p.kind == ParameterKind::Motion && f.hook == Hook::Motion) {
      Vec6 comps;
      for (int k = 0; k < 6; ++k) comps[k] = errs.motion[static_cast<size_t>(k)].value(qa, d);
      df = errorTransformDerivative(comps, p.component) *
           errs.motion[static_cast<size_t>(p.component)].basis(p.index, qa, d);
    } else {
      continue;
    }
    sum += c.prefix[i] * df * c.suffix[i];
  }
  return sum;
}

}  // namespace

ParameterJacobian parameterJacobian(const KinematicModel& m, const std::vector<Parameter>& parameters, const double* q,
                                    const int* dir) {
  if (!m.withErrors) throw std::logic_error("parameterJacobian needs a model compiled with errors");
  const auto tool = expand(m, m.toolChain, m.toolFrame, q, dir);
  const auto wp = expand(m, m.workpieceChain, m.workpieceFrame, q, dir);
  const Mat4 wInv = wp.total.inverse();
  const Mat4 pose = m.alignment.matrix() * wInv * tool.total;
  const Mat3 r = pose.topLeftCorner<3, 3>();

  const bool aligned = m.machine->alignment == WorkpieceAlignment::Machine;
  ChainFactors ref;
  Mat4 nominalRefInv = Mat4::Identity();
  if (aligned) {
    const auto& qr = m.machine->referencePose;
    ref = expand(m, m.workpieceChain, m.workpieceFrame, qr.data(), nullptr);
    // M_WC = N^-1 * W_act(q_ref)  =>  N^-1 = M_WC * W_act(q_ref)^-1
    nominalRefInv = m.alignment.matrix() * ref.total.inverse();
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
    Mat4 d = m.alignment.matrix() * wInv * chainDerivative(m, tool, m.toolChain, p, q, dir);
    d -= m.alignment.matrix() * wInv * chainDerivative(m, wp, m.workpieceChain, p, q, dir) * wInv * tool.total;
    if (aligned) d += nominalRefInv * chainDerivative(m, ref, m.workpieceChain, p, m.machine->referencePose.data(), nullptr) * wInv * tool.total;
    const Mat3 omegaHat = d.topLeftCorner<3, 3>() * r.transpose();
    const Vec3 omega(omegaHat(2, 1), omegaHat(0, 2), omegaHat(1, 0));
    jac.block<3, 1>(0, static_cast<Eigen::Index>(k)) = d.block<3, 1>(0, 3);
    jac.block<3, 1>(3, static_cast<Eigen::Index>(k)) = jInv * omega;
  }
  return jac;
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
