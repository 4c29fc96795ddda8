#include "mtacc/io/surface_files.hpp"

#include <fmt/format.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iterator>
#include <stdexcept>

namespace mtacc {
namespace {

template <class T>
void append(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

struct Vertex {
  float x, y, z;
};

// The exported vertices (every stride-th cell, the last row and column always included).
std::vector<int> strided(int n, int stride) {
  std::vector<int> idx;
  for (int i = 0; i < n; i += stride) idx.push_back(i);
  if (idx.back() != n - 1) idx.push_back(n - 1);
  return idx;
}

std::string base64(const std::string& data) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((data.size() + 2) / 3 * 4);
  for (size_t i = 0; i < data.size(); i += 3) {
    const auto byte = [&](size_t k) { return k < data.size() ? static_cast<unsigned char>(data[k]) : 0u; };
    const unsigned v = byte(i) << 16 | byte(i + 1) << 8 | byte(i + 2);
    out += table[v >> 18 & 63];
    out += table[v >> 12 & 63];
    out += i + 1 < data.size() ? table[v >> 6 & 63] : '=';
    out += i + 2 < data.size() ? table[v & 63] : '=';
  }
  return out;
}

// Blue - white - red, clamped at +-1.
std::array<unsigned char, 3> diverging(double t) {
  t = std::clamp(t, -1.0, 1.0);
  const auto mix = [](double a, double b, double f) { return static_cast<unsigned char>(std::lround(a + (b - a) * f)); };
  if (t < 0) return {mix(255, 33, -t), mix(255, 102, -t), mix(255, 172, -t)};
  return {mix(255, 178, t), mix(255, 24, t), mix(255, 43, t)};
}

void writeToString(png_structp png, png_bytep data, png_size_t length) {
  static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(data), length);
}

}  // namespace

std::string heightMapCsv(const HeightMap& m) {
  const HeightGrid& g = m.grid;
  std::string out = fmt::format("# heights in um relative to z = {:g} mm; row j: y = {:g} + (j + 0.5) * {:g} mm, "
                                "column i: x = {:g} + (i + 0.5) * {:g} mm; {} rows of {} columns\n",
                                m.reference, g.y0, g.spacing, g.x0, g.spacing, g.ny, g.nx);
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      if (i > 0) out += ',';
      fmt::format_to(std::back_inserter(out), "{:.5f}", m.at(i, j) * 1e3);
    }
    out += '\n';
  }
  return out;
}

std::string heightMapNpy(const HeightMap& m) {
  std::string header = fmt::format("{{'descr': '<f4', 'fortran_order': False, 'shape': ({}, {}), }}", m.grid.ny, m.grid.nx);
  const size_t total = 10 + header.size() + 1;
  header.append((64 - total % 64) % 64, ' ');
  header += '\n';
  std::string out("\x93NUMPY\x01\x00", 8);
  append(out, static_cast<std::uint16_t>(header.size()));
  out += header;
  out.append(reinterpret_cast<const char*>(m.height.data()), m.height.size() * sizeof(float));
  return out;
}

int exportStride(const HeightGrid& g, long vertices) {
  int stride = 1;
  while (static_cast<long>(g.nx / stride + 1) * static_cast<long>(g.ny / stride + 1) > vertices) ++stride;
  return stride;
}

std::string heightMapPly(const HeightMap& m, int stride) {
  const auto xs = strided(m.grid.nx, stride), ys = strided(m.grid.ny, stride);
  const size_t nx = xs.size(), ny = ys.size(), faces = 2 * (nx - 1) * (ny - 1);
  std::string out = fmt::format("ply\nformat binary_little_endian 1.0\ncomment mtacc machined surface, mm, workpiece frame\n"
                                "element vertex {}\nproperty float x\nproperty float y\nproperty float z\n"
                                "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
                                nx * ny, faces);
  for (int j : ys)
    for (int i : xs)
      append(out, Vertex{static_cast<float>(m.grid.x(i)), static_cast<float>(m.grid.y(j)), static_cast<float>(m.reference + m.at(i, j))});
  for (size_t j = 0; j + 1 < ny; ++j)
    for (size_t i = 0; i + 1 < nx; ++i) {
      const auto v = static_cast<std::int32_t>(j * nx + i), nxi = static_cast<std::int32_t>(nx);
      for (const auto& t : {std::array{v, v + 1, v + nxi + 1}, std::array{v, v + nxi + 1, v + nxi}}) {
        append(out, static_cast<unsigned char>(3));
        for (auto k : t) append(out, k);
      }
    }
  return out;
}

std::string heightMapStl(const HeightMap& m, int stride) {
  const auto xs = strided(m.grid.nx, stride), ys = strided(m.grid.ny, stride);
  std::string out(80, '\0');
  std::memcpy(out.data(), "mtacc machined surface, mm, workpiece frame", 43);
  append(out, static_cast<std::uint32_t>(2 * (xs.size() - 1) * (ys.size() - 1)));
  const auto vertex = [&](size_t i, size_t j) {
    return Vec3(m.grid.x(xs[i]), m.grid.y(ys[j]), m.reference + m.at(xs[i], ys[j]));
  };
  for (size_t j = 0; j + 1 < ys.size(); ++j)
    for (size_t i = 0; i + 1 < xs.size(); ++i) {
      const Vec3 a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1), d = vertex(i, j + 1);
      for (const auto& t : {std::array{a, b, c}, std::array{a, c, d}}) {
        const Vec3 n = (t[1] - t[0]).cross(t[2] - t[0]).normalized();
        for (int k = 0; k < 3; ++k) append(out, static_cast<float>(n[k]));
        for (const auto& p : t)
          for (int k = 0; k < 3; ++k) append(out, static_cast<float>(p[k]));
        append(out, static_cast<std::uint16_t>(0));
      }
    }
  return out;
}

std::string heightMapPng(const HeightMap& m, const ColourMap& c) {
  const HeightGrid& g = m.grid;
  const int factor = std::max(1, (std::max(g.nx, g.ny) + c.pixels - 1) / c.pixels);
  const int w = (g.nx + factor - 1) / factor, h = (g.ny + factor - 1) / factor;
  std::vector<unsigned char> rgb(static_cast<size_t>(w) * static_cast<size_t>(h) * 3);
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      double sum = 0;
      int n = 0;
      for (int j = py * factor; j < std::min(g.ny, (py + 1) * factor); ++j)
        for (int i = px * factor; i < std::min(g.nx, (px + 1) * factor); ++i, ++n) sum += m.at(i, j);
      const auto colour = diverging(sum / n / c.limit);
      std::copy(colour.begin(), colour.end(), rgb.begin() + 3 * (static_cast<size_t>(h - 1 - py) * static_cast<size_t>(w) + static_cast<size_t>(px)));
    }
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) throw std::runtime_error("cannot start the PNG encoder");
  std::string out;
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("the PNG encoder failed");
  }
  png_set_write_fn(png, &out, writeToString, nullptr);
  png_set_IHDR(png, info, static_cast<png_uint_32>(w), static_cast<png_uint_32>(h), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < h; ++y) png_write_row(png, rgb.data() + 3 * static_cast<size_t>(y) * static_cast<size_t>(w));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return out;
}

std::string zoneMapSvg(const HeightMap& m, const ColourMap& c, const CubicTestSpec& spec, const std::vector<ZonePlane>& zones,
                       const std::string& title) {
  const HeightGrid& g = m.grid;
  const double size = 600, left = 60, top = 50, span = g.nx * g.spacing, scale = size / span;
  const auto px = [&](double x) { return left + (x - g.x0) * scale; };
  const auto py = [&](double y) { return top + size - (y - g.y0) * scale; };
  std::string s = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" font-family=\"sans-serif\" font-size=\"12\">\n"
      "<text x=\"{}\" y=\"25\" font-size=\"14\">{}</text>\n"
      "<image x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" preserveAspectRatio=\"none\" href=\"data:image/png;base64,{}\"/>\n",
      left + size + 120, top + size + 50, left, title, left, top, size, size * g.ny / g.nx, base64(heightMapPng(m, c)));
  for (size_t k = 0; k < spec.zones.size() && k < zones.size(); ++k) {
    const auto& z = spec.zones[k];
    const double h = spec.zoneSize / 2;
    s += fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"none\" stroke=\"#444\"/>\n",
                     px(z.x - h), py(z.y + h), 2 * h * scale, 2 * h * scale);
    s += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{}</text>\n", px(z.x), py(z.y) - 4, z.name);
    s += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{:.2f} µm</text>\n", px(z.x), py(z.y) + 12,
                     zones[k].mean * 1e3);
  }
  for (double t : {g.x0, 0.0, g.x0 + span}) {
    s += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{:g}</text>\n", px(t), top + size + 18, t);
    s += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"end\">{:g}</text>\n", left - 6, py(t) + 4, t);
  }
  s += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">x [mm]</text>\n", left + size / 2, top + size + 38);
  const double bar = left + size + 30;
  for (int i = 0; i < 100; ++i) {
    const auto col = diverging(1 - 2 * (i + 0.5) / 100);
    s += fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"20\" height=\"{:.2f}\" fill=\"rgb({},{},{})\"/>\n", bar,
                     top + i * size / 100, size / 100 + 0.5, col[0], col[1], col[2]);
  }
  for (double f : {1.0, 0.5, 0.0, -0.5, -1.0})
    s += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\">{:g} µm</text>\n", bar + 26, top + (1 - f) / 2 * size + 4, f * c.limit * 1e3);
  return s + "</svg>\n";
}

}  // namespace mtacc
