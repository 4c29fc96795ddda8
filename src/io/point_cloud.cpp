#include "mtacc/io/point_cloud.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <set>
#include <sstream>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/text_file.hpp"
#include "measured_point_limits.hpp"

namespace mtacc {
namespace {

constexpr size_t kMostPoints = 50'000'000;

struct CloudReader {
  const std::string& source;
  std::vector<Vec3> points;

  [[noreturn]] void fail(int line, const std::string& key, const std::string& what) const {
    throw InputError(InputLocation{source, line, key}, what);
  }
  void add(const Vec3& p, int line, const std::string& where) {
    for (int k = 0; k < 3; ++k)
      if (!(std::abs(p[k]) <= kLargestMeasuredCoordinate))
        fail(line, std::string(1, "xyz"[k]), fmt::format("{}: {} is not a finite coordinate within +-{} mm", where, p[k], kLargestMeasuredCoordinate));
    if (points.size() >= kMostPoints) fail(line, "points", fmt::format("more than {} points", kMostPoints));
    points.push_back(p);
  }
};

std::vector<Vec3> csv(const std::string& text, const std::string& source) {
  CloudReader r{source, {}};
  int n = 0;
  bool header = false;
  readCommentedLines(
      text, n, [](const std::string&, const std::string&) {},
      [&](const std::string& line) {
        const auto fields = splitFields(line);
        if (!header) {
          if (fields != std::vector<std::string>{"x", "y", "z"}) r.fail(n, "header", "expected the header 'x,y,z'");
          header = true;
          return;
        }
        if (fields.size() != 3) r.fail(n, "row", fmt::format("expected 3 fields, found {}", fields.size()));
        Vec3 p;
        for (int k = 0; k < 3; ++k) {
          const std::string key(1, "xyz"[k]);
          try {
            p[k] = parseNumber(fields[static_cast<size_t>(k)], key);
          } catch (const InputError& e) {
            r.fail(n, key, e.reason());
          }
        }
        r.add(p, n, "point");
      });
  if (!header) r.fail(0, "header", "no header row 'x,y,z'");
  return r.points;
}

template <class T>
T readBinary(const std::string& bytes, size_t& at, const CloudReader& r, const std::string& what) {
  if (at + sizeof(T) > bytes.size()) r.fail(0, "points", "the file ends inside " + what);
  T v;
  std::memcpy(&v, bytes.data() + at, sizeof(T));
  at += sizeof(T);
  return v;
}

size_t plyScalarSize(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "float" || type == "int32" || type == "uint32" || type == "float32") return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

std::vector<Vec3> ply(const std::string& bytes, const std::string& source) {
  CloudReader r{source, {}};
  const auto end = bytes.find("end_header");
  if (bytes.rfind("ply", 0) != 0 || end == std::string::npos) r.fail(1, "header", "not a PLY file ('ply' ... 'end_header')");
  std::istringstream header(bytes.substr(0, end));
  std::string line, format;
  int n = 0;
  long vertices = -1;
  bool inVertex = false, beforeVertex = true;
  struct Property {
    std::string name, type;
  };
  std::vector<Property> properties;
  while (std::getline(header, line)) {
    ++n;
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "format") {
      words >> format;
      if (format != "ascii" && format != "binary_little_endian") r.fail(n, "format", "ascii or binary_little_endian, not " + format);
    } else if (word == "element") {
      std::string name;
      long count = -1;
      words >> name >> count;
      inVertex = name == "vertex";
      if (inVertex) {
        if (!(count >= 0 && count <= static_cast<long>(kMostPoints))) r.fail(n, "element", "a vertex count from 0 to 50 million");
        vertices = count;
        beforeVertex = false;
      } else if (beforeVertex) {
        r.fail(n, "element", "the vertices must be the first element");
      }
    } else if (word == "property" && inVertex) {
      Property p;
      words >> p.type >> p.name;
      if (p.type == "list") r.fail(n, "property", "a vertex property that is a list");
      if (plyScalarSize(p.type) == 0) r.fail(n, "property", "unknown type " + p.type);
      properties.push_back(p);
    }
  }
  if (vertices < 0) r.fail(n, "element", "no 'element vertex'");
  int index[3] = {-1, -1, -1};
  for (size_t k = 0; k < properties.size(); ++k)
    for (int c = 0; c < 3; ++c)
      if (properties[k].name == std::string(1, "xyz"[c])) {
        if (properties[k].type != "float" && properties[k].type != "double" && properties[k].type != "float32" && properties[k].type != "float64")
          r.fail(n, "property", std::string("vertex ") + "xyz"[c] + " must be float or double");
        index[c] = static_cast<int>(k);
      }
  if (index[0] < 0 || index[1] < 0 || index[2] < 0) r.fail(n, "property", "the vertices need x, y and z");
  size_t at = bytes.find('\n', end);
  at = at == std::string::npos ? bytes.size() : at + 1;
  if (format == "ascii") {
    std::istringstream body(bytes.substr(at));
    int lineNumber = n + 1;
    for (long v = 0; v < vertices; ++v) {
      if (!std::getline(body, line)) r.fail(lineNumber, "points", fmt::format("{} vertices announced, {} found", vertices, v));
      ++lineNumber;
      const auto words = splitList(trim(line), ' ');
      if (words.size() < properties.size()) r.fail(lineNumber, "points", fmt::format("vertex {}: {} values for {} properties", v, words.size(), properties.size()));
      Vec3 p;
      for (int c = 0; c < 3; ++c) {
        try {
          p[c] = parseNumber(words[static_cast<size_t>(index[c])], std::string(1, "xyz"[c]));
        } catch (const InputError& e) {
          r.fail(lineNumber, std::string(1, "xyz"[c]), e.reason());
        }
      }
      r.add(p, lineNumber, fmt::format("vertex {}", v));
    }
    return r.points;
  }
  for (long v = 0; v < vertices; ++v) {
    Vec3 p = Vec3::Zero();
    const std::string what = fmt::format("vertex {}", v);
    for (size_t k = 0; k < properties.size(); ++k) {
      const auto& type = properties[k].type;
      const int c = static_cast<int>(std::find(std::begin(index), std::end(index), static_cast<int>(k)) - std::begin(index));
      if (c < 3) p[c] = plyScalarSize(type) == 8 ? readBinary<double>(bytes, at, r, what) : readBinary<float>(bytes, at, r, what);
      else if (at + plyScalarSize(type) > bytes.size()) r.fail(0, "points", "the file ends inside " + what);
      else at += plyScalarSize(type);
    }
    r.add(p, 0, what);
  }
  return r.points;
}

std::vector<Vec3> stl(const std::string& bytes, const std::string& source) {
  CloudReader r{source, {}};
  // Each corner once: a surface's triangles share them.
  std::set<std::array<double, 3>> seen;
  const auto corner = [&](const Vec3& p, int line, const std::string& where) {
    if (seen.insert({p.x(), p.y(), p.z()}).second) r.add(p, line, where);
  };
  const bool binary = bytes.size() >= 84 && [&] {
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    return bytes.size() == 84 + 50 * static_cast<size_t>(count);
  }();
  if (binary) {
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    for (size_t t = 0; t < count; ++t) {
      size_t at = 84 + 50 * t + 12;
      for (int c = 0; c < 3; ++c) {
        const std::string what = fmt::format("triangle {}", t);
        const float x = readBinary<float>(bytes, at, r, what), y = readBinary<float>(bytes, at, r, what), z = readBinary<float>(bytes, at, r, what);
        corner(Vec3(x, y, z), 0, what);
      }
    }
    return r.points;
  }
  if (bytes.rfind("solid", 0) != 0) r.fail(1, "header", "neither a binary STL (84 + 50 bytes per triangle) nor an ASCII one ('solid')");
  int n = 0;
  for (const auto& line : contentLines(bytes)) {
    n = line.number;
    if (line.text.rfind("vertex", 0) != 0) continue;
    const auto words = splitList(line.text.substr(6), ' ');
    if (words.size() != 3) r.fail(n, "vertex", "expected 'vertex x y z'");
    Vec3 p;
    for (int c = 0; c < 3; ++c) {
      try {
        p[c] = parseNumber(words[static_cast<size_t>(c)], std::string(1, "xyz"[c]));
      } catch (const InputError& e) {
        r.fail(n, std::string(1, "xyz"[c]), e.reason());
      }
    }
    corner(p, n, "vertex");
  }
  return r.points;
}

}  // namespace

std::vector<Vec3> parsePointCloud(const std::string& bytes, const std::string& extension, const std::string& source) {
  if (extension == "csv") return csv(bytes, source);
  if (extension == "ply") return ply(bytes, source);
  if (extension == "stl") return stl(bytes, source);
  throw InputError(InputLocation{source, 0, "format"}, "a point cloud is a .csv, .ply or .stl file");
}

std::vector<Vec3> readPointCloud(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (!extension.empty()) extension.erase(0, 1);
  return parsePointCloud(readTextFile(path), extension, path);
}

}  // namespace mtacc
