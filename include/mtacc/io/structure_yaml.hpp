#pragma once
// Reading structure models (YAML; docs/file-formats.md, "Structure models").
#include <string>

#include "mtacc/dynamics/structure.hpp"

namespace mtacc {

// By path, or by the name of a bundled model (data/structures/). Throws InputError naming file,
// line and key: unknown body, element joining a body to itself, body without mass, ...
StructureModel loadStructure(const std::string& pathOrName);
StructureModel parseStructure(const std::string& yamlText, const std::string& sourceName);

}  // namespace mtacc
