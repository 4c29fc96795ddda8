#pragma once
// Output files are written whole or not at all: to a temporary file beside the target, then
// renamed over it.
#include <string>

namespace mtacc {

// Throws InputError naming the path when the file cannot be written.
void writeFileAtomically(const std::string& path, const std::string& content);

}  // namespace mtacc
