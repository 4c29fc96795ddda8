#include "mtacc/kinematics/jacobian.hpp"

#include <stdexcept>

#include "chain_program.hpp"

namespace mtacc {
namespace {

Vec3 vee(const Mat3& skewSymmetric) { return {skewSymmetric(2, 1), skewSymmetric(0, 2), skewSymmetric(1, 0)}; }

// The point Jacobian into data.point, and with withRotation the tool frame's rate of turn
// into data.rotation. d(W^-1 T x) = W^-1 (dT x - dW (W^-1 T x)): both chains see the same bed
// point. A hooked factor F between the frames B (before) and A (after) adds B dF A^-1 x to the
// point and B.rot vee(dF_rot F_rot^T) to the rate of turn.
void evaluateJacobian(const KinematicModel& m, const double* q, const int* dir, const Vec3& toolPoint,
                      bool withRotation, KinematicData& data) {
  if (!m.withErrors) throw std::logic_error("Jacobians need a model compiled with errors");
  const ChainPrograms& c = *m.chains;
  data.toolFrames.resize(c.toolHookProgram.size());
  data.workpieceFrames.resize(c.workpieceHookProgram.size());
  const auto factors = static_cast<size_t>(c.factorStart[3]);
  data.maps.resize(factors);
  data.local.resize(factors);
  data.motion.resize(factors);
  data.ready.assign(factors, 0);

  const Pose tool = runProgram(c.toolHookProgram, q, dir, data.toolFrames.data());
  const Pose wpInv =
      runProgram(c.workpieceHookProgram, q, dir, data.workpieceFrames.data()).inverse(Eigen::Isometry);
  const Vec3 inBed = tool * toolPoint;
  const Vec3 beforeAlignment = wpInv * inBed;
  // The map of a direction in the bed frame to the workpiece frame.
  const Mat3 bedToWorkpiece = m.aligned ? Mat3(m.alignment.linear() * wpInv.linear()) : wpInv.linear();
  PointJacobian& out = data.point;
  out.point = m.aligned ? Vec3(m.alignment * beforeAlignment) : beforeAlignment;
  out.toolRotation = bedToWorkpiece * tool.linear();

  const bool reference = !c.referenceFrames.empty();
  const ChainFrame* frames[3] = {data.toolFrames.data(), data.workpieceFrames.data(), c.referenceFrames.data()};
  const ChainProgram* programs[3] = {&c.toolHookProgram, &c.workpieceHookProgram, &c.workpieceHookProgram};
  const Vec3 points[3] = {inBed, inBed, reference ? Vec3(c.reference * beforeAlignment) : Vec3::Zero()};
  const Mat3 toWorkpiece[3] = {bedToWorkpiece, -bedToWorkpiece, c.referenceToWorkpiece};
  const double* qOf[3] = {q, q, m.machine->referencePose.data()};
  const int* dirOf[3] = {dir, dir, nullptr};
  const auto columns = static_cast<Eigen::Index>(m.parameters.size());
  out.jacobian.setZero(3, columns);
  if (withRotation) data.rotation.setZero(3, columns);
  for (const auto& t : c.terms) {
    const auto chain = static_cast<size_t>(t.chain);
    const auto f = static_cast<size_t>(c.factorStart[chain] + t.factor);
    if (!data.ready[f]) {
      const ChainFrame& before = frames[chain][2 * t.factor];
      const ChainFrame& after = frames[chain][2 * t.factor + 1];
      data.maps[f].noalias() = toWorkpiece[chain] * before.rotation;
      data.local[f].noalias() = after.rotation.transpose() * (points[chain] - after.origin);
      if (t.kind == JacobianTerm::Motion)
        data.motion[f] = motionComponents((*programs[chain])[static_cast<size_t>(t.op)], qOf[chain], dirOf[chain]);
      data.ready[f] = 1;
    }
    Vec3 d = Vec3::Zero(), turn = Vec3::Zero();
    switch (t.kind) {
      case JacobianTerm::Constant:
        d = t.rotates ? Vec3(t.rotation * data.local[f] + t.translation) : t.translation;
        turn = t.angular;
        break;
      case JacobianTerm::JointTranslation:
        d = t.translation + qOf[chain][t.joint] * t.translationPerUnit;
        break;
      case JacobianTerm::Motion: {
        const Parameter& p = m.parameters[static_cast<size_t>(t.parameter)];
        const ChainOp& op = (*programs[chain])[static_cast<size_t>(t.op)];
        const double qa = op.joint >= 0 ? qOf[chain][op.joint] : 0.0;
        const int sense = (dirOf[chain] && op.joint >= 0) ? dirOf[chain][op.joint] : 0;
        const Vec6& e = data.motion[f];
        const double basis =
            m.errors.axes[static_cast<size_t>(p.axis)].motion[static_cast<size_t>(p.component)].basis(p.index, qa, sense);
        const Mat4 df = errorTransformDerivative(e, p.component) * basis;
        d = df.topLeftCorner<3, 3>() * data.local[f] + df.block<3, 1>(0, 3);
        if (withRotation && p.component >= 3)
          turn = vee(df.topLeftCorner<3, 3>() * rotationXYZ(e[kA], e[kB], e[kC]).transpose());
        break;
      }
    }
    out.jacobian.col(t.parameter).noalias() += data.maps[f] * d;
    if (withRotation) data.rotation.col(t.parameter).noalias() += data.maps[f] * turn;
  }
}

}  // namespace

void planJacobian(const KinematicModel& m, ChainPrograms& c) {
  c.terms.clear();
  int start = 0;
  auto addChain = [&](JacobianTerm::Chain chain, const ChainProgram& program) {
    c.factorStart[chain] = start;
    int factor = 0;
    // Markers come in pairs around their factor, one operation.
    for (size_t i = 0; i < program.size(); ++i) {
      const ChainOp& marker = program[i];
      if (marker.kind != ChainOp::Marker) continue;
      const size_t opIndex = i + 1;
      i += 2;
      for (size_t k = 0; k < m.parameters.size(); ++k) {
        const Parameter& p = m.parameters[k];
        if (p.axis != marker.axis) continue;
        const auto axis = static_cast<size_t>(p.axis);
        JacobianTerm t;
        t.parameter = static_cast<int>(k);
        t.chain = chain;
        t.factor = factor;
        if (marker.hook == Hook::Location && p.kind != ParameterKind::Motion) {
          const auto& derivatives = c.locationDerivatives[axis];
          const Mat4 d = p.kind == ParameterKind::Location
                             ? derivatives[static_cast<size_t>(p.component)]
                             : Mat4(p.turn[0] * derivatives[kA] + p.turn[1] * derivatives[kB] + p.turn[2] * derivatives[kC]);
          t.kind = JacobianTerm::Constant;
          t.rotation = d.topLeftCorner<3, 3>();
          t.translation = d.block<3, 1>(0, 3);
          t.rotates = !t.rotation.isZero(0.0);
          t.angular = vee(t.rotation * c.locationTransforms[axis].linear().transpose());
        } else if (marker.hook == Hook::LinearJoint && p.kind == ParameterKind::Location) {
          // The joint's translation sign (q + own error) tilted direction is affine in q.
          const int own = m.machine->axes[axis].ownComponent();
          const double sign = chain == JacobianTerm::Tool ? 1.0 : -1.0;
          t.kind = JacobianTerm::JointTranslation;
          t.joint = program[opIndex].joint;
          if (p.component == own) {
            t.translation = sign * c.tiltedDirections[axis];
          } else if (p.component >= 3) {
            const Vec3& tilt = c.tiltedDirectionDerivatives[axis][static_cast<size_t>(p.component - 3)];
            t.translation = sign * m.errors.axes[axis].location[own] * tilt;
            t.translationPerUnit = sign * tilt;
          } else {
            continue;
          }
        } else if (marker.hook == Hook::Motion && p.kind == ParameterKind::Motion) {
          t.kind = JacobianTerm::Motion;
          t.op = static_cast<int>(opIndex);
        } else {
          continue;
        }
        c.terms.push_back(t);
      }
      ++factor;
    }
    start += factor;
  };
  addChain(JacobianTerm::Tool, c.toolHookProgram);
  addChain(JacobianTerm::Workpiece, c.workpieceHookProgram);
  c.factorStart[JacobianTerm::Reference] = start;
  if (!m.parameters.empty() && m.machine->alignment == WorkpieceAlignment::Machine) {
    addChain(JacobianTerm::Reference, c.workpieceHookProgram);
    c.referenceFrames.resize(c.workpieceHookProgram.size());
    c.reference = runProgram(c.workpieceHookProgram, m.machine->referencePose.data(), nullptr,
                             c.referenceFrames.data());
    c.referenceToWorkpiece = m.alignment.linear() * c.reference.linear().transpose();
  }
  c.factorStart[3] = start;
}

const PointJacobian& pointJacobian(const KinematicModel& model, const double* q, const int* dir, const Vec3& toolPoint,
                                   KinematicData& data) {
  evaluateJacobian(model, q, dir, toolPoint, false, data);
  return data.point;
}

ParameterJacobian parameterJacobian(const KinematicModel& model, const KinematicModel& nominal, const double* q,
                                    const int* dir) {
  KinematicData data;
  evaluateJacobian(model, q, dir, Vec3::Zero(), true, data);
  const Mat3 nominalRotation = toolInWorkpiece(nominal, q).linear();
  const Mat3 jInv = leftJacobianInverse(rotationVector(data.point.toolRotation * nominalRotation.transpose()));
  ParameterJacobian jac(6, data.point.jacobian.cols());
  jac.topRows<3>() = data.point.jacobian;
  jac.bottomRows<3>().noalias() = jInv * data.rotation;
  return jac;
}

}  // namespace mtacc
