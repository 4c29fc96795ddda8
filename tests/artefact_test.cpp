// Calibrated artefacts (docs/file-formats.md "Artefact measurements"): a certificate plate, a
// step gauge and a ball bar placed obliquely in the volume, simulated on the Maho machine with
// its App. D errors, written, read back and evaluated, against the deviations computed here from
// the forward kinematics and Eigen's own Umeyama fit; the alignments on exact rigid motions; the
// Monte Carlo uncertainty against its closed form; an identification from 3-D-probed placements.
#include <gtest/gtest.h>

#include <boost/math/distributions/chi_squared.hpp>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <fmt/format.h>

#include <fstream>
#include <random>

#include "mtacc/kinematics/forward.hpp"
#include "mtacc/workflows/artefacts.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

MachineSetup maho() { return loadMachineSetup({"maho", "", "", std::nullopt, ""}); }

// The workpiece-frame point the tool reaches at the middle of the linear axes' travel.
Vec3 middleOfTheVolume(const MachineSetup& setup) {
  std::vector<double> q = setup.machine->referencePose;
  for (size_t a = 0; a < q.size(); ++a)
    if (const auto& axis = setup.machine->axes[a]; !axis.isRotary() && axis.travel) q[a] = 0.5 * (axis.travel->min + axis.travel->max);
  return toolInWorkpiece(setup.nominal(), q.data()).translation();
}

std::string layout(const std::string& head, const std::vector<std::pair<std::string, Vec3>>& features, double expandedUm) {
  std::string text = head + "feature,u,v,w,U,x,y,z\n";
  for (const auto& [id, c] : features) text += fmt::format("{},{:.10f},{:.10f},{:.10f},{},,,\n", id, c.x(), c.y(), c.z(), expandedUm);
  return text;
}

// The deviations the machine's errors give at each feature, computed from the forward
// kinematics at the evaluation's poses and aligned by Eigen's Umeyama (least squares, rigid).
Eigen::MatrixXd modelDeviations(const MachineSetup& setup, const ArtefactEvaluation& e) {
  const auto& m = e.measurement;
  const auto nominal = setup.nominal(), actual = setup.actual();
  const Eigen::Matrix3d frame = m.placement.frame();
  const auto n = static_cast<Eigen::Index>(m.artefact.features.size());
  const auto& t = m.temperatures;
  const double grows = 1.0 + t.plateExpansion * (t.plate - t.reference);
  Eigen::Matrix3Xd calibrated(3, n), probed(3, n);
  for (Eigen::Index h = 0; h < n; ++h) {
    const Vec3 c = grows * m.artefact.features[static_cast<size_t>(h)].calibrated;
    const double* q = e.poses.row(h).data();
    const Vec3 truePlace = m.placement.place(c);
    EXPECT_LT((toolInWorkpiece(nominal, q) * m.placement.stylus - truePlace).norm(), 1e-9) << "the pose reaches the feature";
    const Vec3 error = toolInWorkpiece(actual, q) * m.placement.stylus - toolInWorkpiece(nominal, q) * m.placement.stylus;
    calibrated.col(h) = c;
    probed.col(h) = frame.transpose() * (truePlace - error - m.placement.origin);
  }
  const Eigen::Matrix4d fit = Eigen::umeyama(calibrated, probed, false);
  const Eigen::Matrix3Xd aligned = (fit.topLeftCorner<3, 3>() * calibrated).colwise() + fit.topRightCorner<3, 1>();
  return (probed - aligned).transpose();
}

// Simulates the layout on the Maho machine, reads the file written and evaluates it; the
// deviations equal the model's to 1e-9 mm (1e-6 um) in all three directions. Returns the largest.
Vec3 expectTheModelsDeviations(const std::string& text) {
  const test::TestFolder folder("mtacc-artefact");
  const auto setup = maho();
  const std::string layoutFile = (folder.dir() / "layout.csv").string(), measured = (folder.dir() / "measured.csv").string();
  std::ofstream(layoutFile) << text;
  simulateArtefactFile(setup, {layoutFile, measured, "0 um", 1});
  const auto e = evaluateArtefactFile(setup, measured);
  const Eigen::MatrixXd expected = modelDeviations(setup, e);
  EXPECT_EQ(e.measured.deviations.cols(), 3);
  EXPECT_LT((e.measured.deviations - expected).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((e.simulated.deviations - expected).cwiseAbs().maxCoeff(), 1e-9);
  return expected.cwiseAbs().colwise().maxCoeff().transpose();
}

TEST(Artefacts, CertificatePlateTiltedOutOfEveryCoordinatePlane) {
  // A 7 x 7 plate at 50 mm whose certificate puts every feature up to 50 um off the grid (in u,
  // v and w), U = 0.7 um, its normal and both its axes leaning out of every coordinate plane.
  const Vec3 w = Vec3(0.6, 0.5, 0.62).normalized();
  const Vec3 u = (Vec3(1.0, 0.3, -0.7) - Vec3(1.0, 0.3, -0.7).dot(w) * w).normalized(), v = w.cross(u);
  for (const Vec3& axis : {u, v, w}) EXPECT_GT(axis.cwiseAbs().minCoeff(), 0.1);
  const Vec3 origin = middleOfTheVolume(maho()) - 150.0 * (u + v);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> off(-0.05, 0.05);
  std::vector<std::pair<std::string, Vec3>> features;
  for (int r = 0; r < 7; ++r)
    for (int c = 0; c < 7; ++c) features.push_back({fmt::format("R{}C{}", r, c), Vec3(50.0 * c + off(rng), 50.0 * r + off(rng), off(rng))});
  // Measured 0.9 K warm on scales 0.4 K warm.
  const Vec3 largest = expectTheModelsDeviations(layout(
      fmt::format("# artefact: certificate plate\n# dimension: 2\n# temperatures: 20.4, 20.9, 20 C\n# expansion: 11.5e-6, 8e-6\n"
                  "# origin: {}, {}, {} mm\n# axes: {},{},{} / {},{},{}\n", origin.x(),
                  origin.y(), origin.z(), u.x(), u.y(), u.z(), v.x(), v.y(), v.z()),
      features, 0.7));
  // App. D's errors move the features by micrometres in every direction, out of the plane too.
  EXPECT_GT(largest.minCoeff(), 1e-3);
}

TEST(Artefacts, StepGaugeAlongTheSpaceDiagonal) {
  const Vec3 u = Vec3(1.0, 1.0, 1.0).normalized(), v = Vec3(1.0, -1.0, 0.0).normalized();
  const Vec3 origin = middleOfTheVolume(maho()) - 200.0 * u;
  std::vector<std::pair<std::string, Vec3>> features;
  for (int k = 0; k <= 10; ++k) features.push_back({fmt::format("S{}", k), Vec3(40.0 * k, 0.0, 0.0)});
  const Vec3 largest = expectTheModelsDeviations(layout(fmt::format("# artefact: step gauge 400\n# dimension: 1\n# origin: {}, {}, {} mm\n"
                                                                    "# axes: {},{},{} / {},{},{}\n",
                                                                    origin.x(), origin.y(), origin.z(), u.x(), u.y(), u.z(), v.x(), v.y(), v.z()),
                                                        features, 0.5));
  EXPECT_GT(largest.minCoeff(), 1e-4);
}

TEST(Artefacts, BallBarInAVerticalPlane) {
  // Nine balls at 45 mm on a bar rising 30 degrees in the XZ plane.
  const Vec3 u(std::cos(0.5236), 0.0, std::sin(0.5236)), v = Vec3::UnitY();
  const Vec3 origin = middleOfTheVolume(maho()) - 180.0 * u;
  std::vector<std::pair<std::string, Vec3>> features;
  for (int k = 0; k < 9; ++k) features.push_back({fmt::format("B{}", k + 1), Vec3(45.0 * k, 0.0, 0.0)});
  const Vec3 largest = expectTheModelsDeviations(layout(fmt::format("# artefact: ball bar\n# dimension: 1\n# origin: {}, {}, {} mm\n"
                                                                    "# axes: {},{},{} / {},{},{}\n",
                                                                    origin.x(), origin.y(), origin.z(), u.x(), u.y(), u.z(), v.x(), v.y(), v.z()),
                                                        features, 0.5));
  EXPECT_GT(largest.minCoeff(), 1e-4);
}

Eigen::MatrixX3d squarePlate() {
  Eigen::MatrixX3d c(16, 3);
  for (int k = 0; k < 16; ++k) c.row(k) << 100.0 * (k % 4), 100.0 * (k / 4), 0.0;
  return c;
}

TEST(Artefacts, AlignmentsUndoAnExactRigidMotion) {
  // A plate turned by 0.1 rad about a skew axis and shifted 3 mm: far beyond the first order,
  // every alignment returns it to zero deviation; a 100 ppm scale only the scaled fit removes.
  const Eigen::MatrixX3d c = squarePlate();
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.1, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::MatrixX3d moved = (c * r.transpose()).rowwise() + Eigen::RowVector3d(3.0, -1.0, 2.0);
  for (const auto method : {AlignmentMethod::LeastSquares, AlignmentMethod::LeastSquaresScaled, AlignmentMethod::ThreePoint}) {
    const auto a = alignArtefact(c, moved, ProbedDirections::All, 2, {method});
    EXPECT_LT(a.deviations.cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((a.rotation - r).cwiseAbs().maxCoeff(), 1e-14);
  }
  const Eigen::MatrixX3d scaled = 1.0001 * moved;
  const auto withScale = alignArtefact(c, scaled, ProbedDirections::All, 2, {AlignmentMethod::LeastSquaresScaled});
  EXPECT_LT(withScale.deviations.cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_NEAR(withScale.scale, 1.0001, 1e-14);
  EXPECT_GT(alignArtefact(c, scaled, ProbedDirections::All, 2, {}).deviations.cwiseAbs().maxCoeff(), 0.01);
}

TEST(Artefacts, ThreePointAlignmentPutsItsFeaturesOnTheCertificate) {
  // Features 0, 3 and 12 (the corners): the first has no deviation, the second none across the
  // measured line from the first, the third none out of their measured plane; every other
  // feature keeps its own.
  const Eigen::MatrixX3d c = squarePlate();
  std::mt19937 rng(2);
  std::normal_distribution<double> g(0.0, 0.002);
  Eigen::MatrixX3d m = c;
  for (Eigen::Index k = 0; k < m.rows(); ++k) m.row(k) += Eigen::RowVector3d(g(rng), g(rng), g(rng));
  const auto a = alignArtefact(c, m, ProbedDirections::All, 2, {AlignmentMethod::ThreePoint, {0, 3, 12}});
  EXPECT_LT(a.deviations.row(0).norm(), 1e-15);
  const Vec3 line = (m.row(3) - m.row(0)).transpose(), normal = line.cross(Vec3((m.row(12) - m.row(0)).transpose())).normalized();
  EXPECT_LT(Vec3(a.deviations.row(3).transpose()).cross(line.normalized()).norm(), 1e-15);
  EXPECT_LT(std::abs(normal.dot(a.deviations.row(12).transpose())), 1e-15);
  EXPECT_GT(a.deviations.cwiseAbs().maxCoeff(), 1e-3);
  // The default choice is the first feature, the farthest from it and the farthest from their line.
  EXPECT_EQ(alignArtefact(c, m, ProbedDirections::All, 2, {AlignmentMethod::ThreePoint}).features, (std::array<int, 3>{0, 15, 3}));
  EXPECT_THROW(alignArtefact(c, m, ProbedDirections::All, 2, {AlignmentMethod::ThreePoint, {0, 1, 2}}), InvalidInput);
}

TEST(Artefacts, UncertaintyOfAGaugeReadAlongItsAxis) {
  // Read along one direction and aligned by a translation alone, a deviation is its feature's
  // error minus the mean of all: variance (s_cert^2 + s_probe^2)(1 - 1/n). 400 draws estimate
  // the standard deviation within 3.5 % (1 / sqrt(2 x 400)); 15 % is four of those.
  const int n = 6;
  Eigen::MatrixX3d c = Eigen::MatrixX3d::Zero(n, 3);
  for (int k = 0; k < n; ++k) c(k, 0) = 50.0 * k;
  const Eigen::VectorXd certificate = Eigen::VectorXd::Constant(n, 0.3e-3);
  const Vec3 probe(0.4e-3, 0.0, 0.0);
  const auto u = deviationUncertainty(c, c, ProbedDirections::Along, 1, {}, certificate, probe);
  const double expected = 2.0 * std::sqrt((0.3e-3 * 0.3e-3 + 0.4e-3 * 0.4e-3) * (1.0 - 1.0 / n));
  for (int k = 0; k < n; ++k) EXPECT_NEAR(u(k, 0), expected, 0.15 * expected);
}

TEST(Artefacts, IdentificationFromPlatesProbedInSpace) {
  // seed 003 §7.7's 24 placements with the 9 x 9 plate, each now a ball plate probed in u, v
  // and w (probe 2S 1 um, noise 0.5 um), simulated, written, read back and identified with
  // App. D's shapes: every determined parameter within 4.5 standard uncertainties, their
  // chi-square below its 99.9 % quantile, and the weighted residual at the stated noise.
  const test::TestFolder folder("mtacc-artefact");
  const auto setup = maho();
  const auto nominal = setup.nominal();
  const Plate plate;
  ArtefactCampaign campaign;
  for (const auto& placement : cubePlacements(nominal, plate)) {
    const auto poses = platePoses(nominal, plate, placement);
    ArtefactMeasurement m;
    m.artefact = plateArtefact(plate, poses.features);
    m.placement = artefactPlacement(plate, placement);
    m.placement.probed = ProbedDirections::All;
    m.probe = {1e-3, 1e-3, 1e-3};
    m.certificateStated = true;
    const std::string layoutFile = (folder.dir() / (placement.name + "-layout.csv")).string();
    const std::string measured = (folder.dir() / (placement.name + ".csv")).string();
    std::ofstream(layoutFile) << artefactMeasurementCsv(*setup.machine, m);
    simulateArtefactFile(setup, {layoutFile, measured, "0.5 um", campaign.size() + 1});
    campaign.push_back(campaignPlacement(nominal, readArtefactMeasurement(*setup.machine, measured)));
  }
  const ErrorModel truth = setup.errors;
  const ErrorModel shape = plateShape(*setup.machine, truth);
  const auto parameters = plateParameters(*setup.machine, shape);
  const auto r = identifyFromArtefacts(setup.machine, shape, parameters, campaign, 1);
  EXPECT_EQ(r.readings, 24 * 81 * 3);
  EXPECT_NEAR(r.sigma, 1.0, 0.1);
  std::vector<Eigen::Index> determined;
  for (size_t k = 0; k < parameters.size(); ++k)
    if (r.determined[k]) determined.push_back(static_cast<Eigen::Index>(k));
  ASSERT_GT(determined.size(), parameters.size() / 2);
  Eigen::VectorXd error(static_cast<Eigen::Index>(determined.size()));
  Eigen::MatrixXd covariance(error.size(), error.size());
  for (size_t i = 0; i < determined.size(); ++i) {
    const auto k = determined[i];
    error[static_cast<Eigen::Index>(i)] = r.values[k] - parameterValue(shape, parameters[static_cast<size_t>(k)]);
    EXPECT_LT(std::abs(error[static_cast<Eigen::Index>(i)]), 4.5 * r.uncertainty[k]) << r.names[static_cast<size_t>(k)];
    for (size_t j = 0; j < determined.size(); ++j) covariance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = r.covariance(k, determined[j]);
  }
  EXPECT_LT(error.dot(covariance.fullPivLu().solve(error)),
            boost::math::quantile(boost::math::chi_squared(static_cast<double>(error.size())), 0.999));
  // Three translations and three rotations per placement, named by the plate's axes.
  EXPECT_EQ(r.names.size(), parameters.size() + 24 * 6);
  EXPECT_EQ(r.names[parameters.size() + 5], "XY1.rw");
}

}  // namespace
}  // namespace mtacc
