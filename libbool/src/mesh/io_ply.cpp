// SPDX-License-Identifier: GPL-3.0-or-later
// PLY: ascii, binary_little_endian and binary_big_endian; elements vertex (x, y, z) and face
// (a list vertex_indices or vertex_index), other elements and properties skipped.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <ostream>

#include "mesh/io_text.h"

namespace morphex::detail {

namespace {

struct PlyProperty {
  std::string name, type, list_count_type;
  bool list = false;
};
struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

std::size_t ply_size(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "float" || type == "int32" || type == "uint32" ||
      type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

bool is_ply_float(const std::string& type) {
  return type == "float" || type == "float32" || type == "double" || type == "float64";
}

class PlyBinary {
 public:
  PlyBinary(const std::string& content, std::size_t pos, bool big_endian, const std::string& name)
      : c_(content), pos_(pos), big_(big_endian), name_(name) {}
  double read(const std::string& type) {
    const std::size_t n = ply_size(type);
    if (pos_ + n > c_.size())
      throw InputError(name_, "truncated binary PLY data at byte " + std::to_string(pos_));
    unsigned char b[8];
    std::memcpy(b, c_.data() + pos_, n);
    pos_ += n;
    if (big_) std::reverse(b, b + n);
    if (type == "char" || type == "int8") return double(static_cast<std::int8_t>(b[0]));
    if (type == "uchar" || type == "uint8") return double(b[0]);
    if (type == "short" || type == "int16") {
      std::int16_t v;
      std::memcpy(&v, b, 2);
      return v;
    }
    if (type == "ushort" || type == "uint16") {
      std::uint16_t v;
      std::memcpy(&v, b, 2);
      return v;
    }
    if (type == "int" || type == "int32") {
      std::int32_t v;
      std::memcpy(&v, b, 4);
      return v;
    }
    if (type == "uint" || type == "uint32") {
      std::uint32_t v;
      std::memcpy(&v, b, 4);
      return v;
    }
    if (type == "float" || type == "float32") {
      float v;
      std::memcpy(&v, b, 4);
      return v;
    }
    double v;
    std::memcpy(&v, b, 8);
    return v;
  }
  std::size_t remaining() const { return c_.size() - std::min(pos_, c_.size()); }

 private:
  const std::string& c_;
  std::size_t pos_;
  bool big_;
  const std::string& name_;
};

}  // namespace

Mesh read_ply(const std::string& content, const std::string& name) {
  if (content.empty()) throw InputError(name, "empty file");
  if (content.compare(0, 3, "ply") != 0)
    throw InputError(name, "not a PLY file: missing 'ply' header at line 1");
  const std::size_t end_header = content.find("end_header");
  if (end_header == std::string::npos)
    throw InputError(name, "truncated PLY header: no 'end_header'");
  std::size_t data = content.find('\n', end_header);
  data = data == std::string::npos ? content.size() : data + 1;
  std::string format;
  std::vector<PlyElement> elements;
  {
    const std::string_view header(content.data(), end_header);
    std::size_t number = 0, pos = 0;
    while (pos < header.size()) {
      std::size_t stop = header.find('\n', pos);
      if (stop == std::string_view::npos) stop = header.size();
      const std::string_view text = header.substr(pos, stop - pos);
      pos = stop + 1;
      ++number;
      const auto t = split(text);
      if (t.empty()) continue;
      if (t[0] == "format" && t.size() >= 2)
        format = t[1];
      else if (t[0] == "element" && t.size() >= 3)
        elements.push_back({std::string(t[1]), count(t[2], name, number, "element count"), {}});
      else if (t[0] == "property" && !elements.empty()) {
        PlyProperty p;
        if (t.size() >= 5 && t[1] == "list") {
          p.list = true;
          p.list_count_type = t[2];
          p.type = t[3];
          p.name = t[4];
        } else if (t.size() >= 3) {
          p.type = t[1];
          p.name = t[2];
        } else
          throw InputError(name, "malformed property" + at_line(number));
        if (ply_size(p.type) == 0 || (p.list && ply_size(p.list_count_type) == 0))
          throw InputError(name, "unknown PLY type in property " + shown(text) + at_line(number));
        if (p.list && is_ply_float(p.list_count_type))
          throw InputError(name, "PLY list count must be an integer type in property " +
                                     shown(text) + at_line(number));
        elements.back().properties.push_back(p);
      }
    }
  }
  if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
    throw InputError(name, "unsupported PLY format " + shown(format));
  const bool ascii = format == "ascii";
  // Every element takes at least one byte (or one token), so the counts are bounded by the size;
  // checked one by one so that a sum of huge counts cannot wrap around.
  std::uint64_t declared = 0;
  const std::uint64_t available = content.size() - data + 1;
  for (const auto& e : elements) declared = std::min(available + 1, declared + e.count);
  if (declared > available)
    throw InputError(name, "truncated file: header announces more elements than its " +
                               std::to_string(available - 1) + " data bytes can hold");

  Mesh mesh;
  std::uint64_t vertex_count = 0;
  TextReader lines(content, data);
  PlyBinary binary(content, data, format == "binary_big_endian", name);
  Line line;
  std::size_t token = 0, line_number = 0;
  auto next_value = [&](const std::string& type) -> double {
    if (!ascii) return binary.read(type);
    while (token >= line.tokens.size()) {
      if (!lines.next(line)) throw InputError(name, "truncated PLY data");
      token = 0;
      line_number = line.number;
    }
    const std::string_view value = line.tokens[token++];
    if (const std::optional<double> d = double_literal(value)) return *d;
    return CGAL::to_double(number(value, name, line_number));
  };
  for (const PlyElement& e : elements) {
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    if (is_vertex) vertex_count = e.count;
    std::vector<VertexIndex> polygon;
    for (std::uint64_t i = 0; i < e.count; ++i) {
      double xyz[3] = {0, 0, 0};
      int found = 0;
      for (const PlyProperty& p : e.properties) {
        if (p.list) {
          const double n = next_value(p.list_count_type);
          if (!(n >= 0 && n <= 1e6) || n != std::floor(n))
            throw InputError(name, "invalid list size in " + e.name + " " + std::to_string(i));
          polygon.clear();
          for (int k = 0; k < int(n); ++k) {
            const double v = next_value(p.type);
            if (is_face && (p.name == "vertex_indices" || p.name == "vertex_index")) {
              if (v < 0 || v >= double(vertex_count) || v != std::floor(v))
                throw InputError(name, "face " + std::to_string(i) + " has vertex index " +
                                           std::to_string(v) + " out of range");
              polygon.push_back(VertexIndex(v));
            }
          }
          if (is_face && (p.name == "vertex_indices" || p.name == "vertex_index"))
            add_polygon(mesh, polygon, name, i, line_number);
        } else {
          const double v = next_value(p.type);
          if (is_vertex) {
            const int axis = p.name == "x" ? 0 : p.name == "y" ? 1 : p.name == "z" ? 2 : -1;
            if (axis >= 0) {
              xyz[axis] = finite_coordinate(v, name, "at vertex " + std::to_string(i));
              ++found;
            }
          }
        }
      }
      if (is_vertex) {
        if (found < 3) throw InputError(name, "vertex element lacks x, y or z");
        mesh.points.emplace_back(xyz[0], xyz[1], xyz[2]);
      }
    }
  }
  return mesh;
}

void write_ply(const DoubleMesh& m, std::ostream& out, const std::string& note) {
  out << "ply\nformat binary_little_endian 1.0\ncomment " << note << "\nelement vertex "
      << m.points.size()
      << "\nproperty double x\nproperty double y\nproperty double z\nelement face "
      << m.triangles.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : m.points) out.write(reinterpret_cast<const char*>(p.data()), 24);
  for (const Triangle& t : m.triangles) {
    const unsigned char three = 3;
    out.write(reinterpret_cast<const char*>(&three), 1);
    const std::int32_t v[3] = {std::int32_t(t[0]), std::int32_t(t[1]), std::int32_t(t[2])};
    out.write(reinterpret_cast<const char*>(v), 12);
  }
}

}  // namespace morphex::detail
