#include "mtacc/dynamics/rigid_body_dynamics.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/units.hpp"
#include "mtacc/core/parallel.hpp"
#include "mtacc/core/symmetric_eigen.hpp"

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

// The segment of a beam under point p (a beam moved as a whole keeps its shape).
int segmentAt(const StructureModel& model, int beam, const Vec3& p, const std::vector<double>& positions) {
  const auto& b = model.beams[static_cast<size_t>(beam)];
  return b.segmentAt((p - b.from - shift(model, b.first, positions)).dot(b.axis) / b.length);
}

}  // namespace

std::string travelViolation(const StructureModel& model, const std::vector<double>& positions) {
  for (size_t j = 0; j < positions.size() && j < model.axes.size(); ++j) {
    const auto& a = model.axes[j];
    if (!std::isfinite(positions[j]) || (a.max > a.min && (positions[j] < a.min - 1e-12 || positions[j] > a.max + 1e-12)))
      return fmt::format("{} = {:g} mm beyond travel [{:g}, {:g}] mm", a.name, positions[j] * 1e3, a.min * 1e3, a.max * 1e3);
  }
  return {};
}

StructureMatrices assembleStructure(const StructureModel& model, const std::vector<double>& given) {
  std::vector<double> positions = given.empty() ? std::vector<double>(model.axes.size(), 0.0) : given;
  if (positions.size() != model.axes.size())
    throw InputError(InputLocation{"", 0, "positions"},
                     fmt::format("expected {} axis positions, got {}", model.axes.size(), positions.size()));
  if (const auto violation = travelViolation(model, positions); !violation.empty())
    throw InputError(InputLocation{"", 0, "positions"}, violation);
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
    const Vec3 p = c.point + shift(model, c.followsA ? c.a : c.b, positions);
    const int bodies[2] = {c.beamA >= 0 ? segmentAt(model, c.beamA, p, positions) : c.a,
                           c.beamB >= 0 ? segmentAt(model, c.beamB, p, positions) : c.b};
    Mat6 frame = Mat6::Zero();
    frame.block<3, 3>(0, 0) = c.frame;
    frame.block<3, 3>(3, 3) = c.frame;
    const Mat6 kl = frame * c.stiffness.asDiagonal() * frame.transpose();
    const Mat6 dl = frame * c.damping.asDiagonal() * frame.transpose();
    // Relative motion delta = A_b q_b - A_a q_a.
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

namespace {

// K phi = w^2 M phi with M block diagonal (one 6 x 6 block per body): with M = L L^T per
// block, the standard problem L^-1 K L^-T z = w^2 z, phi = L^-T z.
struct StandardForm {
  std::vector<Mat6> inverseFactors;  // L^-1 per body
  Eigen::MatrixXd stiffness;          // L^-1 K L^-T, lower triangle
};

// False when a body's mass block is not positive definite.
bool standardForm(const StructureMatrices& m, StandardForm& s) {
  const int n = static_cast<int>(m.mass.rows()), bodies = n / 6;
  s.inverseFactors.resize(static_cast<size_t>(bodies));
  for (int b = 0; b < bodies; ++b) {
    Eigen::LLT<Mat6> llt(m.mass.block<6, 6>(6 * b, 6 * b));
    if (llt.info() != Eigen::Success) return false;
    s.inverseFactors[static_cast<size_t>(b)] = llt.matrixL().solve(Mat6::Identity());
  }
  s.stiffness.resize(n, n);
  for (int i = 0; i < bodies; ++i)
    for (int j = 0; j <= i; ++j) {
      const auto k = m.stiffness.block<6, 6>(6 * i, 6 * j);
      if (k.isZero(0.0))
        s.stiffness.block<6, 6>(6 * i, 6 * j).setZero();  // bodies not joined by an element
      else
        s.stiffness.block<6, 6>(6 * i, 6 * j) =
            s.inverseFactors[static_cast<size_t>(i)] * k * s.inverseFactors[static_cast<size_t>(j)].transpose();
    }
  return true;
}

// The body that moves most in the lowest generalised mode, and how: the InputError of a
// stiffness matrix that leaves a body free.
InputError freeMotion(const StructureModel& model, const StructureMatrices& m) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(m.stiffness, m.mass);
  const Eigen::VectorXd lowest = eig.eigenvectors().col(0);
  Eigen::Index dof = 0;
  lowest.cwiseAbs().maxCoeff(&dof);
  const char* names[6] = {"along x", "along y", "along z", "about x", "about y", "about z"};
  return InputError(InputLocation{model.sourceFile, model.bodies[static_cast<size_t>(dof / 6)].line, "elements"},
                    fmt::format("the stiffness matrix is singular: body '{}' is free to move {} (add a connecting element)",
                                model.bodies[static_cast<size_t>(dof / 6)].name, names[dof % 6]));
}

}  // namespace

std::vector<Modes> undampedModes(const StructureModel& model, std::span<const StructureMatrices> matrices) {
  const size_t count = matrices.size();
  std::vector<StandardForm> forms(count);
  std::vector<Eigen::MatrixXd> problems(count);
  std::vector<bool> massDefinite(count);
  for (size_t i = 0; i < count; ++i) {
    massDefinite[i] = standardForm(matrices[i], forms[i]);
    if (massDefinite[i]) problems[i].swap(forms[i].stiffness);
  }
  std::vector<SymmetricEigen> eig(count);
  symmetricEigen(problems, eig);
  std::vector<Modes> out(count);
  for (size_t i = 0; i < count; ++i) {
    const Eigen::VectorXd& w2 = eig[i].values;
    const bool solved = massDefinite[i] && eig[i].converged;
    const double largest = solved ? std::abs(w2.maxCoeff()) : 0.0;
    if (!solved || !(w2.minCoeff() > 1e-10 * largest)) throw freeMotion(model, matrices[i]);
    const auto& linv = forms[i].inverseFactors;
    out[i].frequencies = w2.cwiseSqrt() / (2 * kPi);
    out[i].shapes.resize(w2.size(), w2.size());
    for (size_t b = 0; b < linv.size(); ++b)
      out[i].shapes.middleRows<6>(6 * static_cast<Eigen::Index>(b)) =
          linv[b].transpose() * eig[i].vectors.middleRows<6>(6 * static_cast<Eigen::Index>(b));
  }
  return out;
}

Modes undampedModes(const StructureModel& model, const StructureMatrices& m) {
  return std::move(undampedModes(model, std::span(&m, 1)).front());
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

Eigen::VectorXd modalDampingCoefficients(const StructureMatrices& m, const Modes& modes) {
  // D phi block by block: D couples only bodies joined by an element.
  const Eigen::Index bodies = m.damping.rows() / 6, r = modes.shapes.cols();
  Eigen::MatrixXd dampedShapes = Eigen::MatrixXd::Zero(m.damping.rows(), r);
  for (Eigen::Index i = 0; i < bodies; ++i)
    for (Eigen::Index j = 0; j < bodies; ++j) {
      const auto block = m.damping.block<6, 6>(6 * i, 6 * j);
      if (!block.isZero(0.0)) dampedShapes.middleRows<6>(6 * i).noalias() += block * modes.shapes.middleRows<6>(6 * j);
    }
  return modes.shapes.cwiseProduct(dampedShapes).colwise().sum().transpose();
}

double modalDampingCoupling(const StructureMatrices& m, const Modes& modes) {
  const Eigen::MatrixXd modal = modes.shapes.transpose() * m.damping * modes.shapes;
  double coupling = 0;
  for (Eigen::Index i = 0; i < modal.rows(); ++i)
    for (Eigen::Index k = 0; k < i; ++k) {
      const double scale = std::sqrt(std::abs(modal(i, i) * modal(k, k)));
      if (modal(i, k) != 0) coupling = std::max(coupling, scale > 0 ? std::abs(modal(i, k)) / scale : 1.0);
    }
  return coupling;
}

namespace {

// The six distinct entries of the symmetric H at every frequency, by modal superposition:
// re[e][f] + j im[e][f] = sum_r outer(e, r) / (w_r^2 - w_f^2 + j w_f c_r).
struct ModalSums {
  std::array<std::vector<double>, 6> re, im;
};
ModalSums modalSums(const StructureMatrices& m, const Modes& modes, const std::vector<double>& frequencies) {
  const Eigen::Index r = modes.frequencies.size();
  const Eigen::Matrix<double, 3, Eigen::Dynamic> participation = m.selection * modes.shapes;  // S phi_r
  const Eigen::VectorXd modalDamping = modalDampingCoefficients(m, modes);
  // One vector register of frequencies.
  constexpr size_t kLanes = Eigen::internal::packet_traits<double>::size;
  using Lanes = Eigen::Array<double, kLanes, 1>;
  // Per mode, contiguous and already in every lane: w_r^2, c_r and the six products of its
  // participations.
  std::vector<std::array<Lanes, 8>> mode(static_cast<size_t>(r));
  for (Eigen::Index k = 0; k < r; ++k) {
    const Vec3 a = participation.col(k);
    const double values[8] = {std::pow(2 * kPi * modes.frequencies[k], 2), modalDamping[k], a.x() * a.x(), a.y() * a.y(),
                              a.z() * a.z(), a.x() * a.y(), a.x() * a.z(), a.y() * a.z()};
    for (size_t v = 0; v < 8; ++v) mode[static_cast<size_t>(k)][v] = Lanes::Constant(values[v]);
  }
  ModalSums out;
  const size_t nf = frequencies.size();
  for (size_t e = 0; e < 6; ++e) out.re[e].resize(nf), out.im[e].resize(nf);
  // kLanes frequencies at a time (the last repeated to fill the lanes), the twelve sums kept
  // in registers over all modes.
  for (size_t i = 0; i < nf; i += kLanes) {
    Lanes w;
    for (size_t l = 0; l < kLanes; ++l) w[static_cast<Eigen::Index>(l)] = 2 * kPi * frequencies[std::min(i + l, nf - 1)];
    const Lanes w2 = w * w;
    Lanes re[6], im[6];
    for (int e = 0; e < 6; ++e) re[e].setZero(), im[e].setZero();
    for (const auto& md : mode) {  // 1 / (a + j b) = (a - j b) / (a^2 + b^2)
      const Lanes a = md[0] - w2, b = w * md[1], d = (a * a + b * b).inverse(), dr = a * d, di = b * d;
      for (int e = 0; e < 6; ++e) re[e] += md[static_cast<size_t>(2 + e)] * dr, im[e] -= md[static_cast<size_t>(2 + e)] * di;
    }
    for (size_t e = 0; e < 6; ++e)
      for (size_t l = 0; l < kLanes && i + l < nf; ++l)
        out.re[e][i + l] = re[e][static_cast<Eigen::Index>(l)], out.im[e][i + l] = im[e][static_cast<Eigen::Index>(l)];
  }
  return out;
}

// The structure's matrices at positions 0..count-1 (positionAt(k): the axis positions of the
// k-th), as many at a time as symmetricEigen solves together, on `threads` threads:
// body(first, matrices) for positions first.. first + matrices.size() - 1.
template <class PositionAt, class Body>
void inGroupsOfPositions(const StructureModel& model, long count, int threads, PositionAt positionAt, Body body) {
  constexpr long kGroup = static_cast<long>(kInterleavedEigenproblems);
  parallelFor((count + kGroup - 1) / kGroup, threads, [&](long begin, long end) {
    std::vector<StructureMatrices> group;
    for (long g = begin; g < end; ++g) {
      group.clear();
      for (long k = g * kGroup; k < std::min(count, (g + 1) * kGroup); ++k) group.push_back(assembleStructure(model, positionAt(k)));
      body(g * kGroup, std::span<const StructureMatrices>(group));
    }
  }, 1);
}

}  // namespace

Frf frfModal(const StructureMatrices& m, const Modes& modes, const std::vector<double>& frequencies) {
  const auto s = modalSums(m, modes, frequencies);
  Frf out;
  out.reserve(frequencies.size());
  for (size_t i = 0; i < frequencies.size(); ++i) {
    std::complex<double> h[6];
    for (size_t e = 0; e < 6; ++e) h[e] = {s.re[e][i], s.im[e][i]};
    Eigen::Matrix3cd hm;
    hm << h[0], h[3], h[4], h[3], h[1], h[5], h[4], h[5], h[2];
    out.push_back(hm);
  }
  return out;
}

std::vector<Eigen::Matrix3d> frfPeaks(const StructureModel& model, const std::vector<std::vector<double>>& positions,
                                      const std::vector<double>& frequencies, int threads) {
  std::vector<Eigen::Matrix3d> out(positions.size());
  inGroupsOfPositions(model, static_cast<long>(positions.size()), threads, [&](long k) { return positions[static_cast<size_t>(k)]; },
                      [&](long first, std::span<const StructureMatrices> group) {
    const auto modes = undampedModes(model, group);
    for (size_t i = 0; i < group.size(); ++i) {
      const auto s = modalSums(group[i], modes[i], frequencies);
      double peak[6] = {0, 0, 0, 0, 0, 0};
      for (size_t e = 0; e < 6; ++e)
        for (size_t f = 0; f < frequencies.size(); ++f) peak[e] = std::max(peak[e], s.re[e][f] * s.re[e][f] + s.im[e][f] * s.im[e][f]);
      Eigen::Matrix3d& h = out[static_cast<size_t>(first) + i];
      h << peak[0], peak[3], peak[4], peak[3], peak[1], peak[5], peak[4], peak[5], peak[2];
      h = h.cwiseSqrt();
    }
  });
  return out;
}

Eigen::Matrix3d staticCompliance(const StructureMatrices& m) {
  return m.selection * m.stiffness.ldlt().solve(m.selection.transpose());
}

Eigen::Matrix<double, 3, Eigen::Dynamic> accelerationResponse(const StructureMatrices& m) {
  return m.selection * m.stiffness.ldlt().solve(m.inertialLoads);
}

}  // namespace mtacc

namespace mtacc {

DynamicsQuantity dynamicsQuantity(const StructureModel& model, const std::string& name) {
  auto fail = [&]() -> DynamicsQuantity {
    throw InputError(InputLocation{"", 0, "quantity"},
                     "unknown quantity '" + name + "' (H<x|y|z>/<axis> in um/g, C<x|y|z><x|y|z> in um/N, f<n> in Hz)");
  };
  auto component = [](char c) { return c == 'x' ? 0 : c == 'y' ? 1 : c == 'z' ? 2 : -1; };
  // A quantity of each position's matrices alone.
  auto each = [](auto f) {
    return [f](const StructureModel&, std::span<const StructureMatrices> matrices) {
      std::vector<double> out;
      for (const auto& m : matrices) out.push_back(f(m));
      return out;
    };
  };
  if (name.size() >= 4 && name[0] == 'H' && name[2] == '/') {
    const int i = component(name[1]);
    const int j = model.axisIndex(name.substr(3));
    if (i < 0 || j < 0) return fail();
    return {name, "um/g", each([i, j](const StructureMatrices& m) { return std::abs(accelerationResponse(m)(i, j)) * kStandardGravity * 1e6; })};
  }
  if (name.size() == 3 && name[0] == 'C') {
    const int i = component(name[1]), j = component(name[2]);
    if (i < 0 || j < 0) return fail();
    return {name, "um/N", each([i, j](const StructureMatrices& m) { return staticCompliance(m)(i, j) * 1e6; })};
  }
  if (name.size() >= 2 && name[0] == 'f') {
    int k = 0;
    try {
      k = std::stoi(name.substr(1));
    } catch (const std::exception&) {
      return fail();
    }
    if (k < 1 || k > model.dofs()) return fail();
    return {name, "Hz", [k](const StructureModel& s, std::span<const StructureMatrices> m) {
              std::vector<double> out;
              for (const auto& modes : undampedModes(s, m)) out.push_back(modes.frequencies[k - 1]);
              return out;
            }};
  }
  return fail();
}

DynamicsMap dynamicsMap(const StructureModel& model, const MapGrid& grid, const DynamicsQuantity& quantity, int threads) {
  const std::string &axisA = grid.axisA, &axisB = grid.axisB;
  const int countA = grid.countA, countB = grid.countB;
  const int ja = model.axisIndex(axisA), jb = model.axisIndex(axisB);
  if (ja < 0 || jb < 0 || ja == jb)
    throw InputError(InputLocation{"", 0, "axes"}, "a map needs two different axes of the model");
  if (countA < 2 || countB < 2) throw InputError(InputLocation{"", 0, "grid"}, "a map needs at least 2 x 2 positions");
  DynamicsMap out;
  out.axisA = axisA, out.axisB = axisB;
  auto spread = [](const StructureAxis& a, int n) {
    std::vector<double> v;
    for (int k = 0; k < n; ++k) v.push_back(a.min + (a.max - a.min) * k / (n - 1));
    return v;
  };
  out.a = spread(model.axes[static_cast<size_t>(ja)], countA);
  out.b = spread(model.axes[static_cast<size_t>(jb)], countB);
  out.values.resize(countA, countB);
  std::vector<double> base = grid.fixed.empty() ? std::vector<double>(model.axes.size(), 0.0) : grid.fixed;
  inGroupsOfPositions(model, static_cast<long>(countA) * countB, threads,
                      [&](long k) {
                        auto q = base;
                        q[static_cast<size_t>(ja)] = out.a[static_cast<size_t>(k / countB)];
                        q[static_cast<size_t>(jb)] = out.b[static_cast<size_t>(k % countB)];
                        return q;
                      },
                      [&](long first, std::span<const StructureMatrices> group) {
                        const auto values = quantity.evaluate(model, group);
                        for (size_t i = 0; i < values.size(); ++i) {
                          const long k = first + static_cast<long>(i);
                          out.values(k / countB, k % countB) = values[i];
                        }
                      });
  out.statistics = boxStatistics(std::vector<double>(out.values.data(), out.values.data() + out.values.size()));
  return out;
}

}  // namespace mtacc
