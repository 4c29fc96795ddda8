#pragma once
// Loading a machine description (YAML; schema in docs/file-formats.md, "Machine description").
#include <string>

#include "mtacc/machine/machine.hpp"

namespace mtacc {

// Reads a machine file. A bare name such as "tilting-table" that is not a file is looked up
// among the bundled machines (data/machines/<name>.yaml). Throws InputError.
Machine loadMachine(const std::string& pathOrName);
Machine parseMachine(const std::string& yamlText, const std::string& sourceName);

}  // namespace mtacc
