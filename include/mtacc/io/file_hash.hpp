#pragma once
// The SHA-256 of a file, as `sha256sum` prints it: what a record of the data it came from quotes.
#include <string>

namespace mtacc {

// 64 lower-case hex digits; throws InputError naming the path when it cannot be read.
std::string sha256OfFile(const std::string& path);

}  // namespace mtacc
