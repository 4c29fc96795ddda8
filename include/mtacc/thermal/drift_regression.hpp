#pragma once
// Thermal drift from temperatures (seed 003 §2.6, extraction §10.3): a least-squares regression
// of one drift component on the sensor temperatures,
//   delta(T) = beta_0 + sum_i beta_i (T_i - T_i0),
// and the stepwise choice of a minimal sensor set by the cross-validated prediction
// error, the criterion the seed names ("maximum predictive value").
#include <Eigen/Dense>

#include <vector>

namespace mtacc {

// Temperatures of every sensor and one drift component, sampled together.
struct ThermalRecord {
  Eigen::MatrixXd temperatures;  // samples x sensors, degC
  Eigen::VectorXd drift;         // samples, mm
};

struct DriftModel {
  std::vector<int> sensors;                // columns of the record's temperatures
  Eigen::VectorXd referenceTemperatures;   // T_i0 of each sensor: its first sample
  double offset = 0.0;                     // beta_0, mm: the drift at the reference temperatures
  Eigen::VectorXd coefficients;            // beta_i, mm/K
  Eigen::MatrixXd covariance;              // of (beta_0, beta_i), from the residual variance with white residuals
  double residualSigma = 0.0;              // mm: sqrt(SSR / (n - 1 - sensors))
  double residualRms = 0.0;                // mm, on the fitted samples

  // The drift at one sample of every sensor's temperature (the record's columns), mm.
  double predict(const Eigen::VectorXd& temperatures) const;
  // One standard deviation of a new drift reading at these temperatures: the fit's and the residual's, mm.
  double predictionUncertainty(const Eigen::VectorXd& temperatures) const;
  Eigen::VectorXd standardErrors() const { return covariance.diagonal().cwiseSqrt().tail(coefficients.size()); }
};

// Throws std::invalid_argument for fewer samples than sensors + 2, a value that is not finite, a
// sensor index out of range or given twice, or a sensor that does not change (no slope to fit).
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
// does. Every fit comes from the blocks' Gram matrices, formed once. Throws std::invalid_argument for fewer than two folds, fewer
// samples per fold than sensors + 2, or a value that is not finite.
SensorSelection selectSensors(const ThermalRecord& record, const SensorSelectionOptions& options = {});

}  // namespace mtacc
