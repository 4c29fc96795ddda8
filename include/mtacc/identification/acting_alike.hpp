#pragma once
// Location errors of a machine that no measurement can tell apart: parameters whose effects on
// the tool are parallel at every pose act alike ("X0X, X0B and X0C act alike (X0X = X0B = -X0C
// in effect)"); what remains after keeping one of each such class goes to the observability
// analysis, for dependencies among several. Evaluated over random poses within travel.
#include <memory>
#include <string>
#include <vector>

#include "mtacc/errors/error_model.hpp"
#include "mtacc/machine/machine.hpp"

namespace mtacc {

// One sentence per finding, over the location errors among `catalogue`.
std::vector<std::string> locationErrorsActingAlike(const std::shared_ptr<const Machine>& machine, const std::vector<Parameter>& catalogue);

}  // namespace mtacc
