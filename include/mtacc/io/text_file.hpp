#pragma once
// Files as text. Inputs are read whole (a directory or a missing file is an InputError, not an
// empty text); outputs are written whole or not at all: to a temporary file beside the target,
// then renamed over it.
#include <string>

namespace mtacc {

// Throws InputError naming the path when it is not a readable regular file.
std::string readTextFile(const std::string& path);
// Throws InputError naming the path when the file cannot be written, under `key` (the option
// or argument that named the file).
void writeFileAtomically(const std::string& path, const std::string& content, const std::string& key = "output");

}  // namespace mtacc
