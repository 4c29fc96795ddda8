#pragma once
// NumPy's .npy format (format versions 1.0-3.0) for a one-dimensional structured array of named
// float64 fields, as np.save writes np.rec.fromarrays([t, x, ...], names="time_s,X,...").
#include <string>
#include <vector>

namespace mtacc {

struct NpyRecords {
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;  // one per field, in the file's order
};

// Throws InputError naming the source and the header key for a file that is not .npy, a header
// that is not NumPy's dictionary, a field that is not little-endian float64 ('<f8'), an array
// that is not one-dimensional or structured, repeated field names, or data of the wrong size.
NpyRecords parseNpyRecords(const std::string& bytes, const std::string& sourceName);

// The bytes of a version 1.0 file, header padded to 64 bytes; columns of equal length.
std::string npyRecords(const NpyRecords& records);

}  // namespace mtacc
