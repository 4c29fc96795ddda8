#pragma once
// Reading error descriptions: the `errors:` mapping of a machine file or of a separate file
// (schema in docs/file-formats.md, "Errors"). Names are ISO 230-1 or an alias from aliases.hpp; every
// value states its unit.
#include <string>
#include <vector>

#include "mtacc/errors/error_model.hpp"

namespace mtacc {

// The errors of the machine file itself (zero when it has no `errors:` key).
ErrorModel loadMachineErrors(const Machine& machine);
// The `errors:` mapping of an errors file (required there); throws InputError naming file,
// line and key.
ErrorModel loadErrors(const Machine& machine, const std::string& path);
enum class ErrorsKey { Optional, Required };
ErrorModel parseErrors(const Machine& machine, const std::string& yamlText, const std::string& sourceName,
                       ErrorsKey errorsKey = ErrorsKey::Optional);

// One component's entry of an `errors:` mapping with its piecewise terms, as the machine YAML
// loads it back: values in arcsec (rotations) or mm (translations), positions in mm or deg.
// `valueDimension` is the component's, `positionDimension` its axis's.
std::string piecewiseErrorYaml(const std::string& name, const std::vector<PiecewiseTerm>& terms, Dimension valueDimension,
                               Dimension positionDimension);
// One piecewise term as a flow mapping {unit, per, breaks, [period, zero,] intervals}.
std::string piecewiseBlockYaml(const PiecewiseTerm& term, Dimension valueDimension, Dimension positionDimension);

// The errors as an errors file that parseErrors reads back to the same model: every non-zero
// location error, every component function term by term (a list of blocks, so that its
// parameters keep their names and meaning), the stiffness changes and the workpiece load
// they need; values to 15 significant digits in um, urad, mm and deg.
std::string errorsYaml(const Machine& machine, const ErrorModel& errors);

}  // namespace mtacc
