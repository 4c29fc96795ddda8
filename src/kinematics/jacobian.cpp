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

// Calls add(i, dF_i) for every factor i of the chain whose matrix depends on the parameter:
// d(chain total)/dp = sum prefix[i] * dF_i * suffix[i].
template <class Add>
void forEachFactorDerivative(const KinematicModel& m, const ChainFactors& c, const std::vector<ChainElement>& chain,
                             const Parameter& p, const double* q, const int* dir, Add&& add) {
  const ChainElement* element = nullptr;
  for (const auto& e : chain)
    if (e.axis == p.axis) element = &e;
  if (!element) return;
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
    add(i, df);
  }
}

Mat4 chainDerivative(const KinematicModel& m, const ChainFactors& c, const std::vector<ChainElement>& chain,
                     const Parameter& p, const double* q, const int* dir) {
  Mat4 sum = Mat4::Zero();
  forEachFactorDerivative(m, c, chain, p, q, dir,
                          [&](size_t i, const Mat4& df) { sum += c.prefix[i] * df * c.suffix[i]; });
  return sum;
}

// d(chain total)/dp applied to the point v, with suffixV[i] = suffix[i] * v precomputed.
Vec4 chainDerivativeAt(const KinematicModel& m, const ChainFactors& c, const std::vector<ChainElement>& chain,
                       const Parameter& p, const double* q, const int* dir, const std::vector<Vec4>& suffixV) {
  Vec4 sum = Vec4::Zero();
  forEachFactorDerivative(m, c, chain, p, q, dir,
                          [&](size_t i, const Mat4& df) { sum += c.prefix[i] * (df * suffixV[i]); });
  return sum;
}

std::vector<Vec4> suffixApplied(const ChainFactors& c, const Vec4& v) {
  std::vector<Vec4> out(c.factors.size());
  Vec4 acc = v;
  for (size_t i = c.factors.size(); i-- > 0;) {
    out[i] = acc;
    acc = c.factors[i].pose.matrix() * acc;
  }
  return out;
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

PointJacobian pointJacobian(const KinematicModel& m, const std::vector<Parameter>& parameters, const double* q,
                            const int* dir, const Vec3& toolPoint) {
  if (!m.withErrors) throw std::logic_error("pointJacobian needs a model compiled with errors");
  const auto tool = expand(m, m.toolChain, m.toolFrame, q, dir);
  const auto wp = expand(m, m.workpieceChain, m.workpieceFrame, q, dir);
  const Mat4 wInv = wp.total.inverse();
  const Mat4 align = m.alignment.matrix();
  const Vec4 local = toolPoint.homogeneous();
  const Vec4 inBed = tool.total * local;
  const Vec4 beforeAlignment = wInv * inBed;
  PointJacobian out;
  out.point = (align * beforeAlignment).head<3>();
  out.jacobian.resize(3, static_cast<Eigen::Index>(parameters.size()));

  const auto toolV = suffixApplied(tool, local);
  const auto wpV = suffixApplied(wp, beforeAlignment);
  const bool aligned = m.machine->alignment == WorkpieceAlignment::Machine;
  ChainFactors ref;
  Mat4 nominalRefInv = Mat4::Identity();
  std::vector<Vec4> refV;
  if (aligned) {
    ref = expand(m, m.workpieceChain, m.workpieceFrame, m.machine->referencePose.data(), nullptr);
    nominalRefInv = align * ref.total.inverse();
    refV = suffixApplied(ref, beforeAlignment);
  }
  const Mat4 alignWInv = align * wInv;
  for (size_t k = 0; k < parameters.size(); ++k) {
    const Parameter& p = parameters[k];
    Vec4 d = alignWInv * (chainDerivativeAt(m, tool, m.toolChain, p, q, dir, toolV) -
                          chainDerivativeAt(m, wp, m.workpieceChain, p, q, dir, wpV));
    if (aligned)
      d += nominalRefInv *
           chainDerivativeAt(m, ref, m.workpieceChain, p, m.machine->referencePose.data(), nullptr, refV);
    out.jacobian.col(static_cast<Eigen::Index>(k)) = d.head<3>();
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
