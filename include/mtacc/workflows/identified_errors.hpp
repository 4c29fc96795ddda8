#pragma once
// An identification's result as an errors file (docs/file-formats.md "Identified errors"): the
// model that `check`, `compensate`, `decompose`, `report` and a second identification read
// without an edit, with what produced it.
#include <string>
#include <utility>
#include <vector>

#include "mtacc/io/identification_record.hpp"
#include "mtacc/workflows/component_fit.hpp"
#include "mtacc/workflows/identification.hpp"
#include "mtacc/workflows/plates.hpp"

namespace mtacc {

// What produced an identified model, as its file keeps it under `identification:`.
struct IdentificationRecord {
  std::string command;                 // "identify", "cubic-identify", "plate-identify", "fit"
  std::string plan;                    // the test plan or test piece; empty: none
  std::vector<std::string> dataFiles;  // each recorded with its SHA-256
  // The fit's statistics, each a key and its YAML value with its unit ("sigma", "0.31 um").
  std::vector<std::pair<std::string, std::string>> fit;
  std::string heldAt;                  // where the errors not identified were held
  std::vector<std::string> held;       // their names (values read from the model)
  // The estimates (machine parameters, then set-up unknowns), mm or rad; an uncertainty that is
  // NaN marks an estimate the data did not determine.
  std::vector<std::string> names;
  std::vector<EstimateUnit> units;
  Eigen::VectorXd values, uncertainty;
  Eigen::MatrixXd covariance;
};
IdentificationRecord identificationRecord(const IdentificationStudy& outcome);
IdentificationRecord identificationRecord(const PlateIdentificationStudy& study);
// A fitted component function: its coefficients (the terms 1, u, u^2 and (u - t_i)^2 at the
// interior breaks, then the periodic term's), named like identify's (`EXX.k2c2`).
IdentificationRecord identificationRecord(const ComponentFitStudy& study);

// `errors` as an errors file (every component term in the form whose parameter names identify
// uses), and under `identification:` the record with mtacc's version and the date.
std::string identifiedErrorsYaml(const Machine& machine, const ErrorModel& errors, const IdentificationRecord& record);
// The same written to `path` whole or not at all; an error names `key` (the option or argument).
void writeIdentifiedErrors(const std::string& path, const Machine& machine, const ErrorModel& errors,
                           const IdentificationRecord& record, const std::string& key);
void writeIdentifiedErrors(const std::string& path, const IdentificationStudy& outcome, const std::string& key);

}  // namespace mtacc
