#pragma once
// Thermal drift from temperatures (seed 003 §2.6, extraction §10.3): a least-squares regression
// of one drift component on the sensor temperatures,
//   delta(T) = beta_0 + sum_i beta_i (T_i - T_i0),
// or, where the drift was read at several positions p of an axis, with every coefficient linear
// in the position (the extraction's delta_j(T, z) = beta_j0(z) + sum_i beta_ji(z) (T_i - T_i0)):
//   delta(T, p) = beta_0 + gamma_0 p + sum_i (beta_i + gamma_i p) (T_i - T_i0),
// and the stepwise choice of a minimal sensor set by the cross-validated prediction
// error, the criterion the seed names ("maximum predictive value").
#include <Eigen/Dense>

#include <vector>

namespace mtacc {

// Temperatures of every sensor and one drift component, sampled together.
struct ThermalRecord {
  Eigen::MatrixXd temperatures;  // samples x sensors, degC
  Eigen::VectorXd drift;         // samples, mm
  Eigen::VectorXd position;      // samples, mm: where each drift was read along an axis; empty: at one place
};

struct DriftModel {
  std::vector<int> sensors;                // columns of the record's temperatures
  Eigen::VectorXd referenceTemperatures;   // T_i0 of each sensor: its first sample
  double offset = 0.0;                     // beta_0, mm: the drift at the reference temperatures (and position 0)
  Eigen::VectorXd coefficients;            // beta_i, mm/K (at position 0)
  bool positionDependent = false;          // fitted with positions: gamma_0 and gamma_i below
  double offsetSlope = 0.0;                // gamma_0, mm/mm
  Eigen::VectorXd positionCoefficients;    // gamma_i, mm/K per mm
  Eigen::MatrixXd covariance;              // of (beta_0, beta_i[, gamma_0, gamma_i]), from the residual variance with white residuals
  double residualSigma = 0.0;              // mm: sqrt(SSR / (samples - parameters))
  double residualRms = 0.0;                // mm, on the fitted samples

  // The drift at one sample of every sensor's temperature (the record's columns) and a position, mm.
  double predict(const Eigen::VectorXd& temperatures, double position = 0.0) const;
  // One standard deviation of a new drift reading there: the fit's and the residual's, mm.
  double predictionUncertainty(const Eigen::VectorXd& temperatures, double position = 0.0) const;
  Eigen::VectorXd standardErrors() const;          // of beta_i
  Eigen::VectorXd positionStandardErrors() const;  // of gamma_i; empty when not position-dependent
};

// Throws InvalidInput for fewer samples than parameters + 1, a value that is not finite, a
// sensor index out of range or given twice, a sensor or a given position that does not change
// (no slope to fit), or positions not one per sample.
DriftModel fitDriftModel(const ThermalRecord& record, const std::vector<int>& sensors);

struct SensorSelectionOptions {
  int folds = 5;                      // contiguous blocks of the record, each held out in turn
  int maximumSensors = 8;
  double minimumImprovement = 0.05;   // a sensor joins if it lowers the cross-validated RMS by this fraction or more
};

struct SelectionStep {
  int sensor = -1;                 // the sensor added or removed; -1 for the offset alone
  bool added = true;
  double crossValidatedRms = 0.0;  // mm, of the model after this step
};

struct SensorSelection {
  std::vector<SelectionStep> steps;  // the offset alone, then each sensor that joined or left
  DriftModel model;                  // fitted on the whole record with the chosen sensors
  double crossValidatedRms = 0.0;    // mm, of the chosen model
  int bestSingleSensor = -1;
  double bestSingleSensorRms = 0.0;  // mm: the best one-sensor model's cross-validated RMS
};

// Stepwise selection: from the offset alone, add the sensor that lowers the cross-validated RMS
// most, while it does so by at least minimumImprovement; after each addition, remove a chosen
// sensor whose removal raises it by less than that (the one that costs least), as long as one
// does. Each sensor brings beta_i (and gamma_i with positions). Every fit comes from the blocks'
// Gram matrices, formed once. Throws InvalidInput as fitDriftModel does, for fewer than
// two folds, or fewer samples per fold than the largest model's parameters + 1.
SensorSelection selectSensors(const ThermalRecord& record, const SensorSelectionOptions& options = {});

}  // namespace mtacc
