#pragma once
// An identification's result as an errors file (docs/file-formats.md "Identified errors"): the
// model that `check`, `compensate`, `decompose`, `report` and a second identification read
// without an edit, with what produced it.
#include <string>

#include "mtacc/workflows/identification.hpp"

namespace mtacc {

// The estimates merged onto the errors held, every component term in the form whose parameter
// names identify uses, and under `identification:` the record: mtacc's version, the date, the
// machine, the command, the plan, each data file with its SHA-256, the estimates (set-up errors too) with
// their standard uncertainties, the covariance, the errors held at their values, chi-square,
// degrees of freedom and p-value.
std::string identifiedErrorsYaml(const IdentificationOutcome& outcome);
// The same written to `path` whole or not at all; an error names `key` (the option or argument).
void writeIdentifiedErrors(const std::string& path, const IdentificationOutcome& outcome, const std::string& key);

}  // namespace mtacc
