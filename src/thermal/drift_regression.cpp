#include "mtacc/thermal/drift_regression.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "mtacc/core/decompositions.hpp"
#include "mtacc/core/input_error.hpp"

namespace mtacc {
namespace {

void checkRecord(const ThermalRecord& record) {
  if (record.temperatures.rows() != record.drift.size())
    throw InvalidInput(fmt::format("{} temperature samples for {} drift samples", record.temperatures.rows(), record.drift.size()));
  if (record.position.size() && record.position.size() != record.drift.size())
    throw InvalidInput(fmt::format("{} positions for {} drift samples", record.position.size(), record.drift.size()));
  const bool allFinite = record.drift.allFinite() && record.position.allFinite() && record.temperatures.allFinite();
  if (!allFinite)  // then the sample-by-sample search that names the first bad number (it strides across the columns)
    for (long k = 0; k < record.temperatures.rows(); ++k) {
      if (!std::isfinite(record.drift[k])) throw InvalidInput(fmt::format("drift sample {}: not a finite number", k));
      if (record.position.size() && !std::isfinite(record.position[k]))
        throw InvalidInput(fmt::format("position sample {}: not a finite number", k));
      for (long i = 0; i < record.temperatures.cols(); ++i)
        if (!std::isfinite(record.temperatures(k, i))) throw InvalidInput(fmt::format("sensor {} sample {}: not a finite number", i, k));
    }
  if (record.position.size() && record.position.maxCoeff() == record.position.minCoeff())
    throw InvalidInput("the position does not change: no position dependence to fit");
}

// Parameters per sensor (and for the offset): beta, and gamma with positions.
long perSensor(const ThermalRecord& record) { return record.position.size() ? 2 : 1; }

// The design row [1, dT_S, p, p dT_S] (the last two with positions) of the chosen sensors' temperature rises dT_S.
template <class Row>
void fillDesignRow(Row&& row, const Eigen::VectorXd& rises, bool positional, double position) {
  const long p = rises.size();
  row[0] = 1.0;
  for (long j = 0; j < p; ++j) row[j + 1] = rises[j];
  if (!positional) return;
  row[p + 1] = position;
  for (long j = 0; j < p; ++j) row[p + 2 + j] = position * rises[j];
}

Eigen::MatrixXd design(const ThermalRecord& record, const std::vector<int>& sensors, const Eigen::VectorXd& reference) {
  const long n = record.temperatures.rows(), p = static_cast<long>(sensors.size());
  const bool positional = record.position.size() > 0;
  Eigen::MatrixXd z(n, (p + 1) * perSensor(record));
  Eigen::VectorXd rises(p);
  for (long k = 0; k < n; ++k) {
    for (long j = 0; j < p; ++j) rises[j] = record.temperatures(k, sensors[static_cast<size_t>(j)]) - reference[j];
    fillDesignRow(z.row(k), rises, positional, positional ? record.position[k] : 0.0);
  }
  return z;
}

Eigen::VectorXd designRow(const DriftModel& model, const Eigen::VectorXd& temperatures, double position) {
  const long p = static_cast<long>(model.sensors.size());
  Eigen::VectorXd rises(p);
  for (long j = 0; j < p; ++j) rises[j] = temperatures[model.sensors[static_cast<size_t>(j)]] - model.referenceTemperatures[j];
  Eigen::VectorXd z((p + 1) * (model.positionDependent ? 2 : 1));
  fillDesignRow(z, rises, model.positionDependent, position);
  return z;
}

// Per fold, the Gram matrix of [1, Tc] (with positions [1, Tc, pc, pc Tc]; Tc and pc centred on
// their means, which spans what the model's columns span) and its products with the centred drift.
struct FoldGrams {
  std::vector<Eigen::MatrixXd> zz;
  std::vector<Eigen::VectorXd> zy;
  std::vector<double> yy;
  Eigen::MatrixXd totalZz;
  Eigen::VectorXd totalZy;
};

// The design's rows are formed a chunk at a time into a buffer that stays in the cache and
// summed into the fold's Gram matrix (its lower triangle, then mirrored): the whole design of a
// day at 1 Hz with 64 sensors would be 45 MB written once and read once, its fresh pages half of
// the selection's time.
FoldGrams foldGrams(const ThermalRecord& record, int folds) {
  constexpr long kChunkRows = 1024;
  const long n = record.temperatures.rows(), p = record.temperatures.cols(), width = (p + 1) * perSensor(record);
  const bool positional = record.position.size() > 0;
  const Eigen::RowVectorXd meanTemperature = record.temperatures.colwise().mean();
  const double meanPosition = positional ? record.position.mean() : 0.0, meanDrift = record.drift.mean();
  Eigen::MatrixXd chunk(std::min(kChunkRows, n), width);
  Eigen::VectorXd driftChunk(chunk.rows());
  FoldGrams g;
  g.totalZz = Eigen::MatrixXd::Zero(width, width);
  g.totalZy = Eigen::VectorXd::Zero(width);
  for (int f = 0; f < folds; ++f) {
    const long end = n * (f + 1) / folds;
    Eigen::MatrixXd zz = Eigen::MatrixXd::Zero(width, width);
    Eigen::VectorXd zy = Eigen::VectorXd::Zero(width);
    double yy = 0.0;
    for (long begin = n * f / folds; begin < end; begin += kChunkRows) {
      const long rows = std::min(kChunkRows, end - begin);
      auto z = chunk.topRows(rows);
      auto y = driftChunk.head(rows);
      z.col(0).setOnes();
      z.middleCols(1, p) = record.temperatures.middleRows(begin, rows).rowwise() - meanTemperature;
      if (positional) {
        z.col(p + 1) = record.position.segment(begin, rows).array() - meanPosition;
        z.rightCols(p) = z.middleCols(1, p).array().colwise() * z.col(p + 1).array();
      }
      y = record.drift.segment(begin, rows).array() - meanDrift;
      zz.selfadjointView<Eigen::Lower>().rankUpdate(z.transpose());
      zy.noalias() += z.transpose() * y;
      yy += y.squaredNorm();
    }
    zz.triangularView<Eigen::StrictlyUpper>() = zz.transpose();
    g.totalZz += zz;
    g.totalZy += zy;
    g.zz.push_back(std::move(zz));
    g.zy.push_back(std::move(zy));
    g.yy.push_back(yy);
  }
  return g;
}

// The Gram columns of the offset (0) and sensors (i + 1) in `chosen`.
std::vector<int> gramColumns(const std::vector<int>& chosen, long sensors, bool positional) {
  std::vector<int> columns = chosen;
  if (positional)
    for (const int c : chosen) columns.push_back(c + static_cast<int>(sensors) + 1);
  return columns;
}

// The cross-validated RMS of the model on the Gram columns `columns`, or infinity when a
// training fit is singular.
double crossValidatedRms(const FoldGrams& g, const std::vector<int>& columns, long samples) {
  const long m = static_cast<long>(columns.size());
  Eigen::MatrixXd a(m, m), held(m, m);
  Eigen::VectorXd b(m), heldZy(m);
  double squares = 0.0;
  for (size_t f = 0; f < g.zz.size(); ++f) {
    for (long r = 0; r < m; ++r) {
      b[r] = g.totalZy[columns[r]] - g.zy[f][columns[r]];
      heldZy[r] = g.zy[f][columns[r]];
      for (long c = 0; c < m; ++c) {
        held(r, c) = g.zz[f](columns[r], columns[c]);
        a(r, c) = g.totalZz(columns[r], columns[c]) - held(r, c);
      }
    }
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(a);
    if (ldlt.info() != Eigen::Success || ldlt.rcond() < 1e-13) return std::numeric_limits<double>::infinity();
    const Eigen::VectorXd beta = ldlt.solve(b);
    squares += std::max(0.0, g.yy[f] - 2.0 * beta.dot(heldZy) + beta.dot(held * beta));
  }
  return std::sqrt(squares / static_cast<double>(samples));
}

}  // namespace

double DriftModel::predict(const Eigen::VectorXd& temperatures, double position) const {
  const Eigen::VectorXd z = designRow(*this, temperatures, position);
  const long p = coefficients.size();
  double drift = offset + z.segment(1, p).dot(coefficients);
  if (positionDependent) drift += z[p + 1] * offsetSlope + z.tail(p).dot(positionCoefficients);
  return drift;
}

double DriftModel::predictionUncertainty(const Eigen::VectorXd& temperatures, double position) const {
  const Eigen::VectorXd z = designRow(*this, temperatures, position);
  return std::sqrt(residualSigma * residualSigma + z.dot(covariance * z));
}

Eigen::VectorXd DriftModel::standardErrors() const { return covariance.diagonal().cwiseSqrt().segment(1, coefficients.size()); }

Eigen::VectorXd DriftModel::positionStandardErrors() const {
  return covariance.diagonal().cwiseSqrt().tail(positionCoefficients.size());
}

DriftModel fitDriftModel(const ThermalRecord& record, const std::vector<int>& sensors) {
  checkRecord(record);
  const long n = record.temperatures.rows(), p = static_cast<long>(sensors.size()), parameters = (p + 1) * perSensor(record);
  if (n < parameters + 1)
    throw InvalidInput(fmt::format("{} samples for {} sensors{}: at least {} needed", n, p, record.position.size() ? " and the position" : "",
                                            parameters + 1));
  for (size_t j = 0; j < sensors.size(); ++j) {
    if (sensors[j] < 0 || sensors[j] >= record.temperatures.cols())
      throw InvalidInput(fmt::format("sensor {} out of range (0 .. {})", sensors[j], record.temperatures.cols() - 1));
    if (std::count(sensors.begin(), sensors.end(), sensors[j]) > 1) throw InvalidInput(fmt::format("sensor {} given twice", sensors[j]));
    const auto column = record.temperatures.col(sensors[j]);
    if (column.maxCoeff() == column.minCoeff()) throw InvalidInput(fmt::format("sensor {} does not change: no slope to fit", sensors[j]));
  }
  DriftModel model;
  model.sensors = sensors;
  model.referenceTemperatures.resize(p);
  for (long j = 0; j < p; ++j) model.referenceTemperatures[j] = record.temperatures(0, sensors[static_cast<size_t>(j)]);
  const Eigen::MatrixXd z = design(record, sensors, model.referenceTemperatures);
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(z);
  if (qr.rank() < parameters) throw InvalidInput("the chosen sensors' temperatures are linearly dependent: no unique fit");
  const Eigen::VectorXd beta = qr.solve(record.drift);
  const Eigen::VectorXd residual = record.drift - z * beta;
  model.offset = beta[0];
  model.coefficients = beta.segment(1, p);
  if (record.position.size()) {
    model.positionDependent = true;
    model.offsetSlope = beta[p + 1];
    model.positionCoefficients = beta.tail(p);
  }
  model.residualRms = std::sqrt(residual.squaredNorm() / static_cast<double>(n));
  model.residualSigma = std::sqrt(residual.squaredNorm() / static_cast<double>(n - parameters));
  model.covariance = model.residualSigma * model.residualSigma * (z.transpose() * z).inverse();
  return model;
}

SensorSelection selectSensors(const ThermalRecord& record, const SensorSelectionOptions& options) {
  checkRecord(record);
  const long n = record.temperatures.rows(), p = record.temperatures.cols();
  if (options.folds < 2) throw InvalidInput(fmt::format("{} folds: cross-validation needs at least 2", options.folds));
  const long perFold = n / options.folds, largest = std::min<long>(options.maximumSensors, p), needed = (largest + 1) * perSensor(record) + 1;
  if (perFold < needed)
    throw InvalidInput(fmt::format("{} samples in {} folds: at least {} per fold needed for up to {} sensors{}", n, options.folds,
                                            needed, largest, record.position.size() ? " and the position" : ""));
  const bool positional = record.position.size() > 0;
  const FoldGrams grams = foldGrams(record, options.folds);
  SensorSelection out;
  std::vector<int> columns{0};
  out.steps.push_back({-1, true, crossValidatedRms(grams, gramColumns(columns, p, positional), n)});
  const double keep = 1.0 - options.minimumImprovement;
  for (long round = 0; round < 4 * p && static_cast<long>(columns.size()) - 1 < largest; ++round) {
    int best = -1;
    double bestRms = std::numeric_limits<double>::infinity();
    for (long i = 1; i <= p; ++i) {
      if (std::find(columns.begin(), columns.end(), i) != columns.end()) continue;
      auto candidate = columns;
      candidate.push_back(static_cast<int>(i));
      const double rms = crossValidatedRms(grams, gramColumns(candidate, p, positional), n);
      if (rms < bestRms) {
        bestRms = rms;
        best = static_cast<int>(i);
      }
    }
    if (columns.size() == 1 && best > 0) {
      out.bestSingleSensor = best - 1;
      out.bestSingleSensorRms = bestRms;
    }
    if (best < 0 || !(bestRms <= keep * out.steps.back().crossValidatedRms)) break;
    columns.push_back(best);
    out.steps.push_back({best - 1, true, bestRms});
    while (columns.size() > 2) {
      size_t cheapest = 0;
      double withoutRms = std::numeric_limits<double>::infinity();
      for (size_t j = 1; j + 1 < columns.size(); ++j) {
        auto candidate = columns;
        candidate.erase(candidate.begin() + static_cast<long>(j));
        const double rms = crossValidatedRms(grams, gramColumns(candidate, p, positional), n);
        if (rms < withoutRms) {
          withoutRms = rms;
          cheapest = j;
        }
      }
      if (cheapest == 0 || !(keep * withoutRms <= out.steps.back().crossValidatedRms)) break;
      out.steps.push_back({columns[cheapest] - 1, false, withoutRms});
      columns.erase(columns.begin() + static_cast<long>(cheapest));
    }
  }
  std::vector<int> sensors;
  for (size_t j = 1; j < columns.size(); ++j) sensors.push_back(columns[j] - 1);
  out.model = fitDriftModel(record, sensors);
  out.crossValidatedRms = out.steps.back().crossValidatedRms;
  return out;
}

}  // namespace mtacc
