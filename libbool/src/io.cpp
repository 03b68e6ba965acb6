// SPDX-License-Identifier: GPL-3.0-or-later
#include "morphex/io.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

namespace morphex {

namespace fs = std::filesystem;

MeshFormat format_from_path(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext == ".off") return MeshFormat::Off;
  if (ext == ".obj") return MeshFormat::Obj;
  if (ext == ".stl") return MeshFormat::Stl;
  if (ext == ".ply") return MeshFormat::Ply;
  throw InputError(path, "unknown mesh format '" + ext + "' (expected .off, .obj, .stl or .ply)");
}

// ---------------------------------------------------------------------------------------------
// Polygon triangulation

void triangulate_polygon(const std::vector<Point>& points, const std::vector<VertexIndex>& polygon,
                         std::vector<Triangle>& out) {
  const std::size_t n = polygon.size();
  if (n < 3) throw std::invalid_argument("polygon with fewer than 3 vertices");
  for (std::size_t i = 0; i < n; ++i)
    if (polygon[i] == polygon[(i + 1) % n])
      throw std::invalid_argument("polygon repeats vertex " + std::to_string(polygon[i]));
  if (n == 3) {
    out.push_back({polygon[0], polygon[1], polygon[2]});
    return;
  }
  // Newell normal, exact: its dominant axis gives a projection that keeps the polygon simple.
  FT nx = 0, ny = 0, nz = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Point& p = points[polygon[i]];
    const Point& q = points[polygon[(i + 1) % n]];
    nx += (p.y() - q.y()) * (p.z() + q.z());
    ny += (p.z() - q.z()) * (p.x() + q.x());
    nz += (p.x() - q.x()) * (p.y() + q.y());
  }
  const FT ax = CGAL::abs(nx), ay = CGAL::abs(ny), az = CGAL::abs(nz);
  const int axis = (ax >= ay && ax >= az) ? 0 : (ay >= az ? 1 : 2);
  const FT& dominant = axis == 0 ? nx : axis == 1 ? ny : nz;
  if (CGAL::is_zero(dominant)) throw std::invalid_argument("degenerate polygon (zero area)");
  std::vector<Kernel::Point_2> flat;
  for (VertexIndex v : polygon) {
    const Point& p = points[v];
    if (axis == 0)
      flat.emplace_back(p.y(), p.z());
    else if (axis == 1)
      flat.emplace_back(p.z(), p.x());
    else
      flat.emplace_back(p.x(), p.y());
  }
  const CGAL::Orientation ccw =
      CGAL::sign(dominant) == CGAL::POSITIVE ? CGAL::LEFT_TURN : CGAL::RIGHT_TURN;
  std::vector<std::size_t> ring(n);
  for (std::size_t i = 0; i < n; ++i) ring[i] = i;
  while (ring.size() > 3) {
    bool clipped = false;
    for (std::size_t k = 0; k < ring.size() && !clipped; ++k) {
      const std::size_t a = ring[(k + ring.size() - 1) % ring.size()], b = ring[k],
                        c = ring[(k + 1) % ring.size()];
      if (CGAL::orientation(flat[a], flat[b], flat[c]) != ccw) continue;
      bool empty = true;
      for (std::size_t other : ring) {
        if (other == a || other == b || other == c) continue;
        const auto s0 = CGAL::orientation(flat[a], flat[b], flat[other]);
        const auto s1 = CGAL::orientation(flat[b], flat[c], flat[other]);
        const auto s2 = CGAL::orientation(flat[c], flat[a], flat[other]);
        if (s0 != -ccw && s1 != -ccw && s2 != -ccw) {
          empty = false;
          break;
        }
      }
      if (!empty) continue;
      out.push_back({polygon[a], polygon[b], polygon[c]});
      ring.erase(ring.begin() + std::ptrdiff_t(k));
      clipped = true;
    }
    if (!clipped)
      throw std::invalid_argument(
          "polygon cannot be triangulated (self-intersecting or degenerate)");
  }
  if (CGAL::orientation(flat[ring[0]], flat[ring[1]], flat[ring[2]]) != ccw)
    throw std::invalid_argument("polygon cannot be triangulated (degenerate)");
  out.push_back({polygon[ring[0]], polygon[ring[1]], polygon[ring[2]]});
}

namespace {

// ---------------------------------------------------------------------------------------------
// Text reading helpers: lines with numbers, comments stripped.

struct Line {
  std::size_t number;
  std::vector<std::string> tokens;
};

// <cctype> takes an int that must be an unsigned char value: bytes above 127 would be UB.
bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    std::size_t j = i;
    while (j < s.size() && !std::isspace(static_cast<unsigned char>(s[j]))) ++j;
    if (j > i) out.push_back(s.substr(i, j - i));
    i = j;
  }
  return out;
}

class LineReader {
 public:
  LineReader(const std::string& content, std::size_t begin = 0) : content_(content), pos_(begin) {}
  // Next line with at least one token; false at the end.
  bool next(Line& line) {
    while (pos_ < content_.size()) {
      std::size_t end = content_.find('\n', pos_);
      if (end == std::string::npos) end = content_.size();
      std::string text = content_.substr(pos_, end - pos_);
      pos_ = end + 1;
      ++number_;
      const std::size_t hash = text.find('#');
      if (hash != std::string::npos) text.resize(hash);
      line.tokens = split(text);
      line.number = number_;
      if (!line.tokens.empty()) return true;
    }
    return false;
  }
  std::size_t remaining_bytes() const {
    return pos_ < content_.size() ? content_.size() - pos_ : 0;
  }

 private:
  const std::string& content_;
  std::size_t pos_;
  std::size_t number_ = 0;
};

std::string at_line(std::size_t n) {
  return " at line " + std::to_string(n);
}

FT number(const std::string& token, const std::string& name, std::size_t line) {
  try {
    return parse_exact_number(token);
  } catch (const std::invalid_argument& e) {
    throw InputError(name, std::string(e.what()) + at_line(line));
  }
}

std::uint64_t count(const std::string& token, const std::string& name, std::size_t line,
                    const char* what) {
  if (token.empty() || !std::all_of(token.begin(), token.end(), is_digit) || token.size() > 18)
    throw InputError(name, std::string("invalid ") + what + " '" + token + "'" + at_line(line));
  return std::stoull(token);
}

void add_polygon(Mesh& mesh, const std::vector<VertexIndex>& polygon, const std::string& name,
                 std::size_t face, std::size_t line) {
  try {
    triangulate_polygon(mesh.points, polygon, mesh.triangles);
  } catch (const std::invalid_argument& e) {
    throw InputError(name,
                     std::string(e.what()) + ": face " + std::to_string(face) + at_line(line));
  }
}

// ---------------------------------------------------------------------------------------------
// OFF: plain or exact (rational coordinates).

Mesh read_off(const std::string& content, const std::string& name) {
  LineReader reader(content);
  Line line;
  if (!reader.next(line)) throw InputError(name, "empty file");
  std::vector<std::string> header = line.tokens;
  const std::string& magic = header[0];
  if (magic.size() < 3 || magic.compare(magic.size() - 3, 3, "OFF") != 0 ||
      magic.find('4') != std::string::npos)
    throw InputError(name, "not an OFF file: header is '" + magic + "'" + at_line(line.number));
  header.erase(header.begin());
  std::size_t counts_line = line.number;
  if (header.empty()) {
    if (!reader.next(line))
      throw InputError(name, "truncated file: missing vertex and face counts");
    header = line.tokens;
    counts_line = line.number;
  }
  if (header.size() < 2) throw InputError(name, "missing face count" + at_line(counts_line));
  const std::uint64_t nv = count(header[0], name, counts_line, "vertex count");
  const std::uint64_t nf = count(header[1], name, counts_line, "face count");
  // Every vertex needs at least 6 bytes ("0 0 0\n") and every face 8: never trust a huge count.
  if (nv * 6 + nf * 8 > reader.remaining_bytes() + 8)
    throw InputError(name, "truncated file: header announces " + std::to_string(nv) +
                               " vertices and " + std::to_string(nf) + " faces" +
                               at_line(counts_line));
  Mesh mesh;
  mesh.points.reserve(nv);
  for (std::uint64_t v = 0; v < nv; ++v) {
    if (!reader.next(line))
      throw InputError(
          name, "truncated file: " + std::to_string(v) + " of " + std::to_string(nv) + " vertices");
    if (line.tokens.size() < 3)
      throw InputError(name, "vertex " + std::to_string(v) + " has fewer than 3 coordinates" +
                                 at_line(line.number));
    mesh.points.emplace_back(number(line.tokens[0], name, line.number),
                             number(line.tokens[1], name, line.number),
                             number(line.tokens[2], name, line.number));
  }
  std::vector<VertexIndex> polygon;
  for (std::uint64_t f = 0; f < nf; ++f) {
    if (!reader.next(line))
      throw InputError(
          name, "truncated file: " + std::to_string(f) + " of " + std::to_string(nf) + " faces");
    const std::uint64_t n = count(line.tokens[0], name, line.number, "polygon size");
    if (line.tokens.size() < n + 1)
      throw InputError(name, "face " + std::to_string(f) + " lists fewer than " +
                                 std::to_string(n) + " vertices" + at_line(line.number));
    polygon.clear();
    for (std::uint64_t k = 1; k <= n; ++k) {
      const std::string& t = line.tokens[k];
      if (t.empty() || !std::all_of(t.begin(), t.end(), is_digit) || t.size() > 10 ||
          std::stoull(t) >= nv)
        throw InputError(name, "face " + std::to_string(f) + " has vertex index '" + t +
                                   "' out of range [0, " + std::to_string(nv) + ")" +
                                   at_line(line.number));
      polygon.push_back(VertexIndex(std::stoull(t)));
    }
    add_polygon(mesh, polygon, name, f, line.number);
  }
  return mesh;
}

// ---------------------------------------------------------------------------------------------
// OBJ: v and f records; other records are ignored.

Mesh read_obj(const std::string& content, const std::string& name) {
  LineReader reader(content);
  Line line;
  Mesh mesh;
  std::size_t faces = 0;
  std::vector<VertexIndex> polygon;
  while (reader.next(line)) {
    const std::string& kind = line.tokens[0];
    if (kind == "v") {
      if (line.tokens.size() < 4)
        throw InputError(name, "vertex with fewer than 3 coordinates" + at_line(line.number));
      mesh.points.emplace_back(number(line.tokens[1], name, line.number),
                               number(line.tokens[2], name, line.number),
                               number(line.tokens[3], name, line.number));
    } else if (kind == "f") {
      polygon.clear();
      for (std::size_t k = 1; k < line.tokens.size(); ++k) {
        const std::string index = line.tokens[k].substr(0, line.tokens[k].find('/'));
        long long i = 0;
        try {
          std::size_t used = 0;
          i = std::stoll(index, &used);
          if (used != index.size()) throw std::invalid_argument(index);
        } catch (const std::exception&) {
          throw InputError(name, "face " + std::to_string(faces) + " has malformed index '" +
                                     line.tokens[k] + "'" + at_line(line.number));
        }
        const long long n = static_cast<long long>(mesh.points.size());
        const long long resolved = i < 0 ? n + i : i - 1;  // negative indices count backwards
        if (i == 0 || resolved < 0 || resolved >= n)
          throw InputError(name, "face " + std::to_string(faces) + " has vertex index " +
                                     std::to_string(i) + " out of range" + at_line(line.number));
        polygon.push_back(VertexIndex(resolved));
      }
      add_polygon(mesh, polygon, name, faces, line.number);
      ++faces;
    }
  }
  if (mesh.points.empty() && faces == 0) throw InputError(name, "empty file: no vertices or faces");
  return mesh;
}

// ---------------------------------------------------------------------------------------------
// STL: triangle soup; vertices with identical coordinates are merged.

struct LessXYZ {
  bool operator()(const std::array<double, 3>& a, const std::array<double, 3>& b) const {
    return a < b;
  }
};

class SoupIndexer {
 public:
  explicit SoupIndexer(Mesh& mesh) : mesh_(mesh) {}
  VertexIndex add(const std::array<double, 3>& p) {
    auto [it, inserted] = index_.emplace(p, VertexIndex(mesh_.points.size()));
    if (inserted) mesh_.points.emplace_back(p[0], p[1], p[2]);
    return it->second;
  }

 private:
  Mesh& mesh_;
  std::map<std::array<double, 3>, VertexIndex, LessXYZ> index_;
};

double finite(double d, const std::string& name, const std::string& where) {
  if (!std::isfinite(d)) throw InputError(name, "non-finite coordinate " + where);
  return d;
}

Mesh read_stl_binary(const std::string& content, const std::string& name) {
  if (content.size() < 84)
    throw InputError(name, "truncated binary STL: shorter than its 84-byte header");
  std::uint32_t n = 0;
  std::memcpy(&n, content.data() + 80, 4);
  if (content.size() != 84 + std::uint64_t(n) * 50)
    throw InputError(name, "binary STL size mismatch: header announces " + std::to_string(n) +
                               " triangles (" + std::to_string(84 + std::uint64_t(n) * 50) +
                               " bytes), file has " + std::to_string(content.size()) + " bytes");
  Mesh mesh;
  SoupIndexer index(mesh);
  for (std::uint32_t t = 0; t < n; ++t) {
    const char* record = content.data() + 84 + std::size_t(t) * 50 + 12;  // skip the normal
    Triangle tri;
    for (int k = 0; k < 3; ++k) {
      float xyz[3];
      std::memcpy(xyz, record + 12 * k, 12);
      std::array<double, 3> p;
      for (int c = 0; c < 3; ++c) p[c] = finite(xyz[c], name, "in triangle " + std::to_string(t));
      tri[k] = index.add(p);
    }
    mesh.triangles.push_back(tri);
  }
  return mesh;
}

Mesh read_stl_ascii(const std::string& content, const std::string& name) {
  LineReader reader(content);
  Line line;
  Mesh mesh;
  SoupIndexer index(mesh);
  std::vector<VertexIndex> loop;
  bool ended = false;
  while (reader.next(line)) {
    const std::string& kind = line.tokens[0];
    if (kind == "vertex") {
      if (line.tokens.size() < 4)
        throw InputError(name, "vertex with fewer than 3 coordinates" + at_line(line.number));
      std::array<double, 3> p;
      for (int c = 0; c < 3; ++c)
        p[c] = CGAL::to_double(number(line.tokens[1 + c], name, line.number));
      loop.push_back(index.add(p));
    } else if (kind == "endloop") {
      if (loop.size() != 3)
        throw InputError(
            name, "facet with " + std::to_string(loop.size()) + " vertices" + at_line(line.number));
      mesh.triangles.push_back({loop[0], loop[1], loop[2]});
      loop.clear();
    } else if (kind == "endsolid") {
      ended = true;
    }
  }
  if (!ended) throw InputError(name, "truncated ASCII STL: no 'endsolid'");
  return mesh;
}

Mesh read_stl(const std::string& content, const std::string& name) {
  if (content.empty()) throw InputError(name, "empty file");
  // Binary files may also start with "solid": the size formula decides first.
  if (content.size() >= 84) {
    std::uint32_t n = 0;
    std::memcpy(&n, content.data() + 80, 4);
    if (content.size() == 84 + std::uint64_t(n) * 50) return read_stl_binary(content, name);
  }
  if (content.compare(0, 5, "solid") == 0) return read_stl_ascii(content, name);
  return read_stl_binary(content, name);
}

// ---------------------------------------------------------------------------------------------
// PLY: ascii, binary_little_endian, binary_big_endian.

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
    std::istringstream header(content.substr(0, end_header));
    std::string text;
    std::size_t number = 0;
    while (std::getline(header, text)) {
      ++number;
      const auto t = split(text);
      if (t.empty()) continue;
      if (t[0] == "format" && t.size() >= 2)
        format = t[1];
      else if (t[0] == "element" && t.size() >= 3)
        elements.push_back({t[1], count(t[2], name, number, "element count"), {}});
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
          throw InputError(name, "unknown PLY type in property '" + text + "'" + at_line(number));
        if (p.list && is_ply_float(p.list_count_type))
          throw InputError(name, "PLY list count must be an integer type in property '" + text +
                                     "'" + at_line(number));
        elements.back().properties.push_back(p);
      }
    }
  }
  if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
    throw InputError(name, "unsupported PLY format '" + format + "'");
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
  LineReader lines(content, data);
  PlyBinary binary(content, data, format == "binary_big_endian", name);
  std::vector<std::string> tokens;
  std::size_t token = 0, line_number = 0;
  auto next_value = [&](const std::string& type) -> double {
    if (!ascii) return binary.read(type);
    while (token >= tokens.size()) {
      Line line;
      if (!lines.next(line)) throw InputError(name, "truncated PLY data");
      tokens = line.tokens;
      token = 0;
      line_number = line.number;
    }
    return CGAL::to_double(number(tokens[token++], name, line_number));
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
              xyz[axis] = finite(v, name, "at vertex " + std::to_string(i));
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

std::atomic<std::uint64_t> max_file_bytes{InputLimits().max_file_bytes};
std::atomic<std::uint64_t> max_faces{InputLimits().max_faces};

std::string read_file(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path, "cannot open file: no such file");
  if (fs::is_directory(path, ec)) throw InputError(path, "cannot open file: is a directory");
  const auto size = fs::file_size(path, ec);
  if (!ec && size > max_file_bytes)
    throw InputError(path, "file too large: " + std::to_string(size) + " bytes (limit " +
                               std::to_string(max_file_bytes.load()) +
                               "; raise it with --max-input-mb)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, std::string("cannot open file: ") + std::strerror(errno));
  // Read in chunks under the same limit: a device or pipe (mesh:path=/dev/zero, <(cmd)) has no
  // size to check beforehand and may never end.
  std::string content;
  std::array<char, 1 << 16> chunk;
  while (in.read(chunk.data(), chunk.size()) || in.gcount() > 0) {
    content.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
    if (content.size() > max_file_bytes)
      throw InputError(path, "file too large: more than " + std::to_string(max_file_bytes.load()) +
                                 " bytes (raise the limit with --max-input-mb)");
  }
  if (in.bad()) throw InputError(path, std::string("cannot read file: ") + std::strerror(errno));
  return content;
}

}  // namespace

Mesh read_mesh_from_string(const std::string& content, MeshFormat format, const std::string& name) {
  if (content.find_first_not_of(" \t\r\n") == std::string::npos)
    throw InputError(name, "empty file");
  switch (format) {
    case MeshFormat::Off:
      return read_off(content, name);
    case MeshFormat::Obj:
      return read_obj(content, name);
    case MeshFormat::Stl:
      return read_stl(content, name);
    case MeshFormat::Ply:
      return read_ply(content, name);
  }
  throw InputError(name, "unknown format");
}

Mesh read_mesh(const std::string& path) {
  const MeshFormat format = format_from_path(path);
  Mesh mesh = read_mesh_from_string(read_file(path), format, path);
  if (mesh.num_triangles() > max_faces)
    throw InputError(path, "too many faces: " + std::to_string(mesh.num_triangles()) + " (limit " +
                               std::to_string(max_faces.load()) + "; raise it with --max-faces)");
  return mesh;
}

void set_input_limits(const InputLimits& limits) {
  max_file_bytes = limits.max_file_bytes;
  max_faces = limits.max_faces;
}

InputLimits input_limits() {
  return {max_file_bytes.load(), max_faces.load()};
}

// ---------------------------------------------------------------------------------------------
// Writing

namespace {
// Temporary files of writes in progress, in fixed slots so that a signal handler can unlink them
// without locks or allocation.
constexpr int kSlots = 64;
char pending_paths[kSlots][4096];
std::atomic<bool> pending_used[kSlots];

struct PendingTemporary {
  int slot = -1;
  explicit PendingTemporary(const std::string& path) {
    if (path.size() >= sizeof pending_paths[0]) return;
    for (int i = 0; i < kSlots; ++i) {
      bool expected = false;
      if (pending_used[i].compare_exchange_strong(expected, true)) {
        std::memcpy(pending_paths[i], path.c_str(), path.size() + 1);
        slot = i;
        return;
      }
    }
  }
  ~PendingTemporary() {
    if (slot >= 0) pending_used[slot] = false;
  }
};
}  // namespace

void remove_pending_temporary_files() noexcept {
  for (int i = 0; i < kSlots; ++i)
    if (pending_used[i]) unlink(pending_paths[i]);
}

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& writer) {
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::string tmp = (dir / ("." + target.filename().string() + ".tmp.XXXXXX")).string();
  const int fd = mkstemp(tmp.data());
  if (fd < 0)
    throw std::runtime_error(path + ": cannot create a temporary file: " + std::strerror(errno));
  close(fd);
  const PendingTemporary pending(tmp);
  try {
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      if (!out) throw std::runtime_error(path + ": cannot write");
      writer(out);
      out.flush();
      if (!out) throw std::runtime_error(path + ": write failed");
    }
    const int sync_fd = open(tmp.c_str(), O_RDONLY);
    if (sync_fd >= 0) {
      fsync(sync_fd);
      close(sync_fd);
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
      throw std::runtime_error(path +
                               ": cannot rename the temporary file: " + std::strerror(errno));
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
}

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec);
}

namespace {

void write_off(const Mesh& m, std::ostream& out, bool exact) {
  out << "OFF\n" << m.points.size() << ' ' << m.triangles.size() << " 0\n";
  out << std::setprecision(17);
  for (const Point& p : m.points) {
    if (exact)
      out << to_rational_string(p.x()) << ' ' << to_rational_string(p.y()) << ' '
          << to_rational_string(p.z()) << '\n';
    else
      out << CGAL::to_double(p.x()) << ' ' << CGAL::to_double(p.y()) << ' '
          << CGAL::to_double(p.z()) << '\n';
  }
  for (const Triangle& t : m.triangles) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
}

void write_obj(const Mesh& m, std::ostream& out) {
  out << std::setprecision(17);
  for (const Point& p : m.points)
    out << "v " << CGAL::to_double(p.x()) << ' ' << CGAL::to_double(p.y()) << ' '
        << CGAL::to_double(p.z()) << '\n';
  for (const Triangle& t : m.triangles)
    out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
}

void write_stl(const Mesh& m, std::ostream& out) {
  char header[80] = "binary STL written by morphex";
  out.write(header, 80);
  const std::uint32_t n = std::uint32_t(m.triangles.size());
  out.write(reinterpret_cast<const char*>(&n), 4);
  const DoubleMesh d = to_double(m);
  for (const Triangle& t : m.triangles) {
    float record[12] = {0, 0, 0};
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) record[3 + 3 * k + c] = float(d.points[t[k]][c]);
    out.write(reinterpret_cast<const char*>(record), 48);
    const std::uint16_t attributes = 0;
    out.write(reinterpret_cast<const char*>(&attributes), 2);
  }
}

void write_ply(const Mesh& m, std::ostream& out) {
  out << "ply\nformat binary_little_endian 1.0\ncomment written by morphex\nelement vertex "
      << m.points.size()
      << "\nproperty double x\nproperty double y\nproperty double z\nelement face "
      << m.triangles.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : to_double(m).points) out.write(reinterpret_cast<const char*>(p.data()), 24);
  for (const Triangle& t : m.triangles) {
    const unsigned char three = 3;
    out.write(reinterpret_cast<const char*>(&three), 1);
    const std::int32_t v[3] = {std::int32_t(t[0]), std::int32_t(t[1]), std::int32_t(t[2])};
    out.write(reinterpret_cast<const char*>(v), 12);
  }
}

}  // namespace

void write_mesh(const Mesh& mesh, const std::string& path, const WriteOptions& options) {
  const MeshFormat format = format_from_path(path);
  if (options.exact && format != MeshFormat::Off)
    throw InputError(path, "the exact format is OFF: use a .off output with --exact");
  write_file_atomically(path, [&](std::ostream& out) {
    switch (format) {
      case MeshFormat::Off:
        write_off(mesh, out, options.exact);
        break;
      case MeshFormat::Obj:
        write_obj(mesh, out);
        break;
      case MeshFormat::Stl:
        write_stl(mesh, out);
        break;
      case MeshFormat::Ply:
        write_ply(mesh, out);
        break;
    }
  });
}

}  // namespace morphex
