#pragma once
// mtacc's version (CMake's project version): what `mtacc --version` prints and what the Python
// package reports as mtacc.__version__ (and pip lists).

namespace mtacc {

const char* version();

}  // namespace mtacc
