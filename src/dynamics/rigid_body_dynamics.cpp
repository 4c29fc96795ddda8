#include "mtacc/dynamics/rigid_body_dynamics.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"

namespace mtacc {
namespace {

using Mat6 = Eigen::Matrix<double, 6, 6>;

// Displacement of the rigid body (translation of its centre, rotation vector) at point p.
Mat6 pointMotion(const Vec3& r) {
  Mat6 a = Mat6::Identity();
  a.block<3, 3>(0, 3) = -skew(r);
  return a;
}

Vec3 shift(const StructureModel& model, int body, const std::vector<double>& positions) {
  Vec3 s = Vec3::Zero();
  if (body == kGround) return s;
  for (size_t j = 0; j < model.axes.size(); ++j)
    for (int moved : model.axes[j].moves)
      if (moved == body) s += positions[j] * model.axes[j].direction;
  return s;
}

}  // namespace

StructureMatrices assembleStructure(const StructureModel& model, const std::vector<double>& given) {
  std::vector<double> positions = given.empty() ? std::vector<double>(model.axes.size(), 0.0) : given;
  if (positions.size() != model.axes.size())
    throw InputError(InputLocation{model.sourceFile, 0, "positions"},
                     fmt::format("expected {} axis positions, got {}", model.axes.size(), positions.size()));
  for (size_t j = 0; j < positions.size(); ++j) {
    const auto& a = model.axes[j];
    if (a.max > a.min && (positions[j] < a.min - 1e-12 || positions[j] > a.max + 1e-12))
      throw InputError(InputLocation{model.sourceFile, 0, a.name},
                       fmt::format("{} = {:g} mm beyond travel [{:g}, {:g}] mm", a.name, positions[j] * 1e3, a.min * 1e3, a.max * 1e3));
  }
  const int n = model.dofs();
  StructureMatrices m;
  m.mass = Eigen::MatrixXd::Zero(n, n);
  m.stiffness = Eigen::MatrixXd::Zero(n, n);
  m.damping = Eigen::MatrixXd::Zero(n, n);
  std::vector<Vec3> centres;
  for (size_t i = 0; i < model.bodies.size(); ++i) {
    const auto& b = model.bodies[i];
    const int k = 6 * static_cast<int>(i);
    m.mass.block<3, 3>(k, k) = b.mass * Mat3::Identity();
    m.mass.block<3, 3>(k + 3, k + 3) = b.inertia;
    centres.push_back(b.centre + shift(model, static_cast<int>(i), positions));
  }
  for (const auto& c : model.connections) {
    const Vec3 p = c.point + shift(model, c.b, positions);
    Mat6 frame = Mat6::Zero();
    frame.block<3, 3>(0, 0) = c.frame;
    frame.block<3, 3>(3, 3) = c.frame;
    const Mat6 kl = frame * c.stiffness.asDiagonal() * frame.transpose();
    const Mat6 dl = frame * c.damping.asDiagonal() * frame.transpose();
    // Relative motion delta = A_b q_b - A_a q_a.
    const int bodies[2] = {c.a, c.b};
    const double signs[2] = {-1.0, 1.0};
    for (int s = 0; s < 2; ++s) {
      if (bodies[s] == kGround) continue;
      const Mat6 as = pointMotion(p - centres[static_cast<size_t>(bodies[s])]);
      for (int t = 0; t < 2; ++t) {
        if (bodies[t] == kGround) continue;
        const Mat6 at = pointMotion(p - centres[static_cast<size_t>(bodies[t])]);
        const double sign = signs[s] * signs[t];
        m.stiffness.block<6, 6>(6 * bodies[s], 6 * bodies[t]) += sign * as.transpose() * kl * at;
        m.damping.block<6, 6>(6 * bodies[s], 6 * bodies[t]) += sign * as.transpose() * dl * at;
      }
    }
  }
  m.selection = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, n);
  auto select = [&](int body, const Vec3& point, double sign) {
    if (body == kGround) return;
    const Vec3 p = point + shift(model, body, positions);
    m.selection.block<3, 6>(0, 6 * body) += sign * pointMotion(p - centres[static_cast<size_t>(body)]).topRows<3>();
  };
  select(model.tcpBody, model.tcpPoint, 1.0);
  select(model.workpieceBody, model.workpiecePoint, -1.0);
  m.inertialLoads = Eigen::MatrixXd::Zero(n, static_cast<Eigen::Index>(model.axes.size()));
  for (size_t j = 0; j < model.axes.size(); ++j) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(n);
    for (int body : model.axes[j].moves) e.segment<3>(6 * body) = model.axes[j].direction;
    m.inertialLoads.col(static_cast<Eigen::Index>(j)) = -m.mass * e;
  }
  return m;
}

Modes undampedModes(const StructureModel& model, const StructureMatrices& m) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(m.stiffness, m.mass);
  const Eigen::VectorXd w2 = eig.eigenvalues();
  const double largest = std::abs(w2.maxCoeff());
  if (eig.info() != Eigen::Success || !(w2.minCoeff() > 1e-10 * largest)) {
    // The free motion: the body that moves most in the lowest mode, and how.
    const Eigen::VectorXd phi = eig.eigenvectors().col(0);
    Eigen::Index dof = 0;
    phi.cwiseAbs().maxCoeff(&dof);
    const char* names[6] = {"along x", "along y", "along z", "about x", "about y", "about z"};
    throw InputError(InputLocation{model.sourceFile, model.bodies[static_cast<size_t>(dof / 6)].line, "elements"},
                     fmt::format("the stiffness matrix is singular: body '{}' is free to move {} (add a connecting element)",
                                 model.bodies[static_cast<size_t>(dof / 6)].name, names[dof % 6]));
  }
  Modes out;
  out.frequencies = w2.cwiseSqrt() / (2 * kPi);
  out.shapes = eig.eigenvectors();
  return out;
}

std::vector<DampedMode> dampedModes(const StructureMatrices& m) {
  const Eigen::Index n = m.mass.rows();
  const Eigen::MatrixXd minv = m.mass.inverse();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  a.topRightCorner(n, n).setIdentity();
  a.bottomLeftCorner(n, n) = -minv * m.stiffness;
  a.bottomRightCorner(n, n) = -minv * m.damping;
  Eigen::EigenSolver<Eigen::MatrixXd> eig(a, false);
  std::vector<DampedMode> out;
  for (Eigen::Index i = 0; i < 2 * n; ++i) {
    const std::complex<double> l = eig.eigenvalues()[i];
    if (l.imag() <= 0) continue;  // one of each conjugate pair
    out.push_back({std::abs(l) / (2 * kPi), -l.real() / std::abs(l)});
  }
  std::sort(out.begin(), out.end(), [](const DampedMode& x, const DampedMode& y) { return x.frequency < y.frequency; });
  return out;
}

Frf frfDirect(const StructureMatrices& m, const std::vector<double>& frequencies) {
  Frf out;
  const Eigen::MatrixXcd st = m.selection.transpose().cast<std::complex<double>>();
  for (double f : frequencies) {
    const double w = 2 * kPi * f;
    const Eigen::MatrixXcd z = (m.stiffness - w * w * m.mass).cast<std::complex<double>>() +
                               std::complex<double>(0, w) * m.damping.cast<std::complex<double>>();
    const Eigen::MatrixXcd x = z.partialPivLu().solve(st);
    out.push_back(m.selection.cast<std::complex<double>>() * x);
  }
  return out;
}

Frf frfModal(const StructureMatrices& m, const Modes& modes, const std::vector<double>& frequencies) {
  const Eigen::Index r = modes.frequencies.size();
  const Eigen::Matrix<double, 3, Eigen::Dynamic> participation = m.selection * modes.shapes;  // S phi_r
  const Eigen::VectorXd modalDamping = (modes.shapes.transpose() * m.damping * modes.shapes).diagonal();
  const Eigen::VectorXd w2 = (2 * kPi * modes.frequencies).array().square();
  // The six distinct entries of the symmetric H, per mode.
  Eigen::Matrix<double, 6, Eigen::Dynamic> outer(6, r);
  for (Eigen::Index k = 0; k < r; ++k) {
    const Vec3 a = participation.col(k);
    outer.col(k) << a.x() * a.x(), a.y() * a.y(), a.z() * a.z(), a.x() * a.y(), a.x() * a.z(), a.y() * a.z();
  }
  Frf out;
  out.reserve(frequencies.size());
  for (double f : frequencies) {
    const double w = 2 * kPi * f;
    Eigen::Matrix<std::complex<double>, 6, 1> h = Eigen::Matrix<std::complex<double>, 6, 1>::Zero();
    for (Eigen::Index k = 0; k < r; ++k) h += outer.col(k) / std::complex<double>(w2[k] - w * w, w * modalDamping[k]);
    Eigen::Matrix3cd hm;
    hm << h[0], h[3], h[4], h[3], h[1], h[5], h[4], h[5], h[2];
    out.push_back(hm);
  }
  return out;
}

Eigen::Matrix3d staticCompliance(const StructureMatrices& m) {
  return m.selection * m.stiffness.ldlt().solve(m.selection.transpose());
}

Eigen::Matrix<double, 3, Eigen::Dynamic> accelerationResponse(const StructureMatrices& m) {
  return m.selection * m.stiffness.ldlt().solve(m.inertialLoads);
}

}  // namespace mtacc
