// Thermal errors (issue 19): the scale expansion of seed 003 §2.7 against hand calculations, and
// the regression of drift on temperatures with its stepwise sensor choice on a virtual machine
// run through seed 003's load cycle (5000 rpm for 6 h, 8 h at rest, L971-973).
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>

#include "mtacc/core/input_error.hpp"
#include "mtacc/thermal/drift_regression.hpp"
#include "mtacc/thermal/scale_expansion.hpp"
#include "test_helpers.hpp"
#include "thermal_machines.hpp"

namespace mtacc {
namespace {

constexpr double kAlpha = 11.5e-6;  // 1/K

TEST(ScaleExpansion, ALinearProfileGivesTheClosedForm) {
  // T(u) = 21 + 0.01 u on sensors at 0, 300, 600 mm: Delta = alpha [(21 - 20)(p - p_ref) + 0.005 (p^2 - p_ref^2)].
  const ScaleSensors scale{{0, 300, 600}, kAlpha, 150, 20};
  const std::vector<double> t{21, 24, 27};
  for (double p : {0.0, 75.0, 150.0, 299.0, 450.0, 600.0}) {
    const double expected = kAlpha * ((p - 150) + 0.005 * (p * p - 150 * 150));
    EXPECT_NEAR(scaleExpansion(scale, t, p), expected, 1e-12) << p;
  }
}

TEST(ScaleExpansion, AKinkedProfileByHand) {
  // Sensors at 0, 200, 600 mm read 20, 25, 21 degC; T_ref 20, p_ref 100 mm. By hand, K mm:
  // 100..200: int 5u/200 = 375; 200..500: int 5 - (u - 200)/100 = 1500 - 450 = 1050;
  // 500..600: 500 - 350 = 150; beyond 600 the end sensor's 1 K: 100 more to 700; below 0 the
  // first sensor's 0 K: nothing, and 0..100 gives -125.
  const ScaleSensors scale{{0, 200, 600}, kAlpha, 100, 20};
  const std::vector<double> t{20, 25, 21};
  EXPECT_NEAR(scaleExpansion(scale, t, 500), kAlpha * 1425, 1e-12);
  EXPECT_NEAR(scaleExpansion(scale, t, 700), kAlpha * 1675, 1e-12);
  EXPECT_NEAR(scaleExpansion(scale, t, -50), kAlpha * -125, 1e-12);
  EXPECT_NEAR(scaleExpansion(scale, t, 0), kAlpha * -125, 1e-12);
}

TEST(ScaleExpansion, IsZeroAtTheReferencePositionAtAnyTemperatures) {
  for (double reference : {-50.0, 0.0, 123.4, 600.0, 800.0}) {
    const ScaleSensors scale{{0, 250, 600}, kAlpha, reference, 20};
    EXPECT_EQ(scaleExpansion(scale, std::vector<double>{31, 17, 44}, reference), 0.0) << reference;
  }
}

TEST(ScaleExpansion, RefusesAScaleItCannotInterpolate) {
  const auto message = [](const ScaleSensors& s, const std::vector<double>& t) {
    const auto e = test::thrown<InvalidInput>([&] { scaleExpansion(s, t, 10); });
    return e ? std::string(e->what()) : std::string();
  };
  EXPECT_EQ(message({{0}, kAlpha}, {20}), "a scale needs at least two temperature sensors, not 1");
  EXPECT_EQ(message({{0, 100}, kAlpha}, {20}), "1 temperatures for 2 sensors on the scale");
  EXPECT_EQ(message({{0, 100, 100}, kAlpha}, {20, 21, 22}), "scale sensors must be in increasing position (100 mm after 100 mm)");
  EXPECT_EQ(message({{0, 100}, kAlpha}, {20, std::nan("")}), "scale sensor 1: not a finite number");
}

TEST(ThermalDrift, WarmUpAndCoolDownDifferAtTheSameHeadTemperature) {
  // The seed's observation (L992-998): 40 or 52 um of Y drift for the same rise of the head,
  // depending on warm-up or cool-down. Here: the drift when the head passes 15 K of rise.
  const auto r = recordDriftTest(test::maho(1), test::cycle({{6, 8}}), 1.0);
  double warming = NAN, cooling = NAN;
  for (long k = 1; k < r.nodes.rows(); ++k) {
    const double before = r.nodes(k - 1, 0) - 20, now = r.nodes(k, 0) - 20;
    if (before < 15 && now >= 15 && std::isnan(warming)) warming = r.trueDrift[k];
    if (before > 15 && now <= 15) cooling = r.trueDrift[k];
  }
  EXPECT_GT(cooling - warming, 5e-3) << "the column, slower than the head, holds its heat";
  RecordProperty("drift_um_at_15K_warming_cooling", fmt::format("{:.1f} / {:.1f}", warming * 1e3, cooling * 1e3));
}

TEST(ThermalDrift, TheRegressionRecoversTheInjectedCoefficientsWithinTheirUncertainties) {
  const auto r = recordDriftTest(test::maho(2), test::cycle({{6, 8}}), 1.0);
  const auto model = fitDriftModel(r.record, {1, 2});
  const Eigen::VectorXd truth = Eigen::Vector2d(1.5e-3, 2.5e-3), se = model.standardErrors();
  for (long j = 0; j < 2; ++j) {
    EXPECT_LT(std::fabs(model.coefficients[j] - truth[j]), 3 * se[j]) << j;
    EXPECT_LT(se[j], 0.01 * truth[j]) << "the cycle determines each coefficient to 1 %";
  }
  EXPECT_NEAR(model.residualSigma, 0.3e-3, 0.01e-3);
  RecordProperty("coefficients_um_per_K", fmt::format("{:.4f} +- {:.4f}, {:.4f} +- {:.4f}", model.coefficients[0] * 1e3, se[0] * 1e3,
                                                      model.coefficients[1] * 1e3, se[1] * 1e3));
}

TEST(ThermalDrift, StepwiseSelectionFindsTheInjectedSensorsAndRefusesOneSensor) {
  const auto r = recordDriftTest(test::maho(3), test::cycle({{6, 8}}), 1.0);
  const auto selection = selectSensors(r.record);
  auto chosen = selection.model.sensors;
  std::sort(chosen.begin(), chosen.end());
  EXPECT_EQ(chosen, (std::vector<int>{1, 2}));
  // One sensor cannot explain the drift: the best one leaves many times the noise.
  EXPECT_GT(selection.bestSingleSensorRms, 10 * 0.3e-3);
  EXPECT_LT(selection.crossValidatedRms, 1.1 * 0.3e-3);
  RecordProperty("cv_rms_um_best_single_vs_chosen",
                 fmt::format("{:.2f} (sensor {}) vs {:.3f}", selection.bestSingleSensorRms * 1e3, selection.bestSingleSensor, selection.crossValidatedRms * 1e3));
}

TEST(ThermalDrift, TheDriftOfAHeldOutCycleIsPredictedWithinItsStatedUncertainty) {
  const auto fitted = selectSensors(recordDriftTest(test::maho(4), test::cycle({{6, 8}}), 1.0).record).model;
  const auto other = recordDriftTest(test::maho(5), test::cycle({{3, 2}, {3, 6}}), 1.0);  // intermittent spindle use
  double squares = 0.0;
  long within = 0;
  const long n = other.record.drift.size();
  for (long k = 0; k < n; ++k) {
    const Eigen::VectorXd t = other.record.temperatures.row(k).transpose();
    const double z = (other.record.drift[k] - fitted.predict(t)) / fitted.predictionUncertainty(t);
    squares += z * z;
    within += std::fabs(z) <= 2 ? 1 : 0;
  }
  EXPECT_NEAR(std::sqrt(squares / static_cast<double>(n)), 1.0, 0.1);
  EXPECT_GT(static_cast<double>(within) / static_cast<double>(n), 0.94);
}

TEST(ThermalDrift, APositionDependentDriftIsRecoveredAndPredictedWhereItWasNotRead) {
  // The drift read with Z at 0, -200 and -400 mm in turn (10 min each): the head's 1.5 um/K at
  // Z = 0 grows by 5 nm/K per mm downwards (a lead screw's expansion, extraction §10.3's beta(z)).
  auto machine = test::maho(6);
  machine.driftGradient = {-5e-6, 0, 0, 0};
  const auto loads = test::cycle({{6, 8}});
  const auto r = recordDriftTest(machine, loads, 1.0, test::stops(loads.rows(), {0, -200, -400}, 600));
  const auto selection = selectSensors(r.record);
  const auto& model = selection.model;
  auto chosen = model.sensors;
  std::sort(chosen.begin(), chosen.end());
  ASSERT_EQ(chosen, (std::vector<int>{1, 2}));
  ASSERT_TRUE(model.positionDependent);
  const Eigen::VectorXd se = model.standardErrors(), gammaSe = model.positionStandardErrors();
  for (size_t j = 0; j < 2; ++j) {
    const bool head = model.sensors[j] == 1;
    EXPECT_LT(std::fabs(model.coefficients[static_cast<long>(j)] - (head ? 1.5e-3 : 2.5e-3)), 3 * se[static_cast<long>(j)]) << j;
    EXPECT_LT(std::fabs(model.positionCoefficients[static_cast<long>(j)] - (head ? -5e-6 : 0.0)), 3 * gammaSe[static_cast<long>(j)]) << j;
  }
  EXPECT_LT(gammaSe.maxCoeff(), 0.05 * 5e-6) << "the three stops determine the gradient to 5 %";
  EXPECT_LT(selection.crossValidatedRms, 1.1 * 0.3e-3);
  auto placeless = r.record;
  placeless.position.resize(0);
  EXPECT_GT(selectSensors(placeless).crossValidatedRms, 10 * 0.3e-3) << "the same drift without its positions";

  auto other = test::maho(7);
  other.driftGradient = machine.driftGradient;
  const long n = loads.rows();
  const auto heldOut = recordDriftTest(other, loads, 1.0, Eigen::VectorXd::Constant(n, -300.0));
  double squares = 0.0;
  for (long k = 0; k < n; ++k) {
    const Eigen::VectorXd t = heldOut.record.temperatures.row(k).transpose();
    const double z = (heldOut.record.drift[k] - model.predict(t, -300.0)) / model.predictionUncertainty(t, -300.0);
    squares += z * z;
  }
  EXPECT_NEAR(std::sqrt(squares / static_cast<double>(n)), 1.0, 0.1) << "Z = -300 mm, where no drift was read";
  RecordProperty("head_um_per_K_and_nm_per_K_per_mm",
                 fmt::format("{:.4f} +- {:.4f}, {:.3f} +- {:.3f}", model.coefficients[model.sensors[0] == 1 ? 0 : 1] * 1e3,
                             se[model.sensors[0] == 1 ? 0 : 1] * 1e3, model.positionCoefficients[model.sensors[0] == 1 ? 0 : 1] * 1e6,
                             gammaSe[model.sensors[0] == 1 ? 0 : 1] * 1e6));
}

// The cross-validated RMS of the model on `sensors` fitted directly: for each of the selection's
// contiguous folds (five by default), least squares on the other folds' rows of [1, T_S (, p, p T_S)] by QR, and
// the held-out rows' squared residuals summed; what the selection gets from its Gram matrices.
double directCrossValidatedRms(const ThermalRecord& r, const std::vector<int>& sensors) {
  const long n = r.drift.size(), m = static_cast<long>(sensors.size()) + 1;
  const bool positional = r.position.size() > 0;
  Eigen::MatrixXd z(n, positional ? 2 * m : m);
  z.col(0).setOnes();
  for (long j = 1; j < m; ++j) z.col(j) = r.temperatures.col(sensors[static_cast<size_t>(j - 1)]);
  if (positional) z.rightCols(m) = z.leftCols(m).array().colwise() * r.position.array();
  const long folds = SensorSelectionOptions{}.folds;
  double squares = 0.0;
  for (long f = 0; f < folds; ++f) {
    const long begin = n * f / folds, end = n * (f + 1) / folds;
    Eigen::MatrixXd train(n - (end - begin), z.cols());
    Eigen::VectorXd y(train.rows());
    train << z.topRows(begin), z.bottomRows(n - end);
    y << r.drift.head(begin), r.drift.tail(n - end);
    const Eigen::VectorXd beta = train.colPivHouseholderQr().solve(y);
    squares += (r.drift.segment(begin, end - begin) - z.middleRows(begin, end - begin) * beta).squaredNorm();
  }
  return std::sqrt(squares / static_cast<double>(n));
}

TEST(ThermalDrift, TheCrossValidatedRmsIsThatOfDirectFitsOnTheOtherFolds) {
  // 12,503 samples: folds of 2500 and 2501 rows, which the selection sums in chunks of 1024.
  // They agree to about 2e-14; 1e-10 leaves room for the Gram matrices' squared condition number.
  const long n = 12503;
  ThermalRecord r{Eigen::MatrixXd(n, 4), Eigen::VectorXd(n), {}};
  const Eigen::ArrayXd t = Eigen::ArrayXd::LinSpaced(n, 0, 1);
  r.temperatures << 20 + 3 * t, 21 + (6 * t).sin(), 20 + t.square(), 22 + 0.2 * Eigen::ArrayXd::Random(n);
  r.drift = 2e-3 * r.temperatures.col(1) - 1e-3 * r.temperatures.col(2) + 0.3e-3 * Eigen::VectorXd::Random(n);
  for (const bool positional : {false, true}) {
    if (positional) r.position = 100 * (40 * t).sin();
    const auto selection = selectSensors(r);
    ASSERT_GE(selection.steps.size(), 2u) << positional;
    EXPECT_NEAR(selection.steps.front().crossValidatedRms / directCrossValidatedRms(r, {}), 1, 1e-10) << positional;
    EXPECT_NEAR(selection.bestSingleSensorRms / directCrossValidatedRms(r, {selection.bestSingleSensor}), 1, 1e-10) << positional;
    EXPECT_NEAR(selection.crossValidatedRms / directCrossValidatedRms(r, selection.model.sensors), 1, 1e-10) << positional;
  }
}

TEST(ThermalDrift, BadRecordsAreRefused) {
  const auto message = [](const ThermalRecord& r, const std::vector<int>& sensors) {
    const auto e = test::thrown<InvalidInput>([&] { fitDriftModel(r, sensors); });
    return e ? std::string(e->what()) : std::string();
  };
  ThermalRecord r{Eigen::MatrixXd::Random(6, 3), Eigen::VectorXd::Random(6), {}};
  r.temperatures.col(2).setConstant(20);
  EXPECT_EQ(message(r, {0, 1, 0}), "sensor 0 given twice");
  EXPECT_EQ(message(r, {2}), "sensor 2 does not change: no slope to fit");
  EXPECT_EQ(message(r, {3}), "sensor 3 out of range (0 .. 2)");
  EXPECT_EQ(message({r.temperatures.topRows(3), r.drift.head(3), {}}, {0, 1}), "3 samples for 2 sensors: at least 4 needed");
  EXPECT_EQ(message({r.temperatures, r.drift, Eigen::VectorXd::LinSpaced(6, 0, 1)}, {0, 1}), "6 samples for 2 sensors and the position: at least 7 needed");
  EXPECT_EQ(message({r.temperatures, r.drift, Eigen::VectorXd::Constant(6, 5)}, {0}), "the position does not change: no position dependence to fit");
  EXPECT_EQ(message({r.temperatures, r.drift, Eigen::VectorXd::Zero(5)}, {0}), "5 positions for 6 drift samples");
  r.temperatures(4, 1) = std::nan("");
  EXPECT_EQ(message(r, {0}), "sensor 1 sample 4: not a finite number");
  const auto e = test::thrown<InvalidInput>([&] { selectSensors({Eigen::MatrixXd::Random(20, 8), Eigen::VectorXd::Random(20), {}}); });
  ASSERT_TRUE(e);
  EXPECT_STREQ(e->what(), "20 samples in 5 folds: at least 10 per fold needed for up to 8 sensors");
}

}  // namespace
}  // namespace mtacc

namespace mtacc {
namespace {

// Issue 52: the drift's position dependence stated directly. A noise-free record read along an
// axis, drift = b0 + g0 z + sum_i (b_i + g_i z) (T_i - T_i0): the fit returns every coefficient,
// the offset's slope g0 among them, and predicts a sample it was not given by the same formula.
TEST(DriftModelFit, TheOffsetAndEachCoefficientAreLinearInThePosition) {
  const int samples = 40;
  ThermalRecord r{Eigen::MatrixXd(samples, 2), Eigen::VectorXd(samples), Eigen::VectorXd(samples)};
  const double b0 = 2e-3, g0 = -4e-6, b[2] = {1.5e-3, -0.8e-3}, g[2] = {3e-6, 1e-6};
  for (int k = 0; k < samples; ++k) {
    r.temperatures(k, 0) = 20.0 + 0.1 * k + 0.3 * std::sin(0.7 * k);
    r.temperatures(k, 1) = 21.0 + 0.05 * k * k / samples - 0.2 * std::cos(1.3 * k);
    r.position[k] = -400.0 + 200.0 * (k % 3);
  }
  const auto drift = [&](double t0, double t1, double z) {
    return b0 + g0 * z + (b[0] + g[0] * z) * (t0 - r.temperatures(0, 0)) + (b[1] + g[1] * z) * (t1 - r.temperatures(0, 1));
  };
  for (int k = 0; k < samples; ++k) r.drift[k] = drift(r.temperatures(k, 0), r.temperatures(k, 1), r.position[k]);
  const DriftModel m = fitDriftModel(r, {0, 1});
  ASSERT_TRUE(m.positionDependent);
  EXPECT_NEAR(m.offset, b0, 1e-12);
  EXPECT_NEAR(m.offsetSlope, g0, 1e-14);
  for (long i = 0; i < 2; ++i) {
    EXPECT_NEAR(m.coefficients[i], b[i], 1e-12) << i;
    EXPECT_NEAR(m.positionCoefficients[i], g[i], 1e-14) << i;
  }
  const Eigen::Vector2d elsewhere(23.5, 19.2);
  EXPECT_NEAR(m.predict(elsewhere, 150.0), drift(23.5, 19.2, 150.0), 1e-12);
}

}  // namespace
}  // namespace mtacc
