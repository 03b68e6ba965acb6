// SPDX-License-Identifier: GPL-3.0-or-later
// STL, ASCII and binary: a triangle soup whose vertices with identical coordinates are merged.
#include <cmath>
#include <cstring>
#include <ostream>
#include <unordered_map>

#include "mesh/io_text.h"
#include "mesh/separate_touching.h"

namespace morphex::detail {

namespace {

// One vertex per distinct coordinate triple, in order of first appearance.
class SoupIndexer {
 public:
  explicit SoupIndexer(Mesh& mesh) : mesh_(mesh) {}
  VertexIndex add(const std::array<double, 3>& p) {
    // +0 and -0 are one position.
    const std::array<double, 3> key = {p[0] + 0.0, p[1] + 0.0, p[2] + 0.0};
    auto [it, inserted] = index_.emplace(key, VertexIndex(mesh_.points.size()));
    if (inserted) mesh_.points.emplace_back(p[0], p[1], p[2]);
    return it->second;
  }

 private:
  Mesh& mesh_;
  std::unordered_map<std::array<double, 3>, VertexIndex, DoublePointHash> index_;
};

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
  mesh.triangles.reserve(n);
  SoupIndexer index(mesh);
  for (std::uint32_t t = 0; t < n; ++t) {
    const char* record = content.data() + 84 + std::size_t(t) * 50 + 12;  // skip the normal
    Triangle tri;
    for (int k = 0; k < 3; ++k) {
      float xyz[3];
      std::memcpy(xyz, record + 12 * k, 12);
      std::array<double, 3> p;
      for (int c = 0; c < 3; ++c)
        p[c] = finite_coordinate(xyz[c], name, "in triangle " + std::to_string(t));
      tri[k] = index.add(p);
    }
    mesh.triangles.push_back(tri);
  }
  return mesh;
}

Mesh read_stl_ascii(const std::string& content, const std::string& name) {
  TextReader reader(content);
  Line line;
  Mesh mesh;
  SoupIndexer index(mesh);
  std::vector<VertexIndex> loop;
  bool ended = false;
  while (reader.next(line)) {
    const std::string_view kind = line.tokens[0];
    if (kind == "vertex") {
      if (line.tokens.size() < 4)
        throw InputError(name, "vertex with fewer than 3 coordinates" + at_line(line.number));
      std::array<double, 3> p;
      for (int c = 0; c < 3; ++c) p[c] = double_number(line.tokens[1 + c], name, line.number);
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

Mesh read_stl_welded(const std::string& content, const std::string& name) {
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

}  // namespace

Mesh read_stl(const std::string& content, const std::string& name) {
  Mesh mesh = read_stl_welded(content, name);
  separate_touching(mesh);  // welding joined where a solid touches itself: undone
  return mesh;
}

void write_stl(const DoubleMesh& d, std::ostream& out, const std::string& note) {
  // The header is free text, but it must not start with "solid" (ASCII STL); the note never does.
  char header[80] = {};
  note.copy(header, sizeof header);
  out.write(header, 80);
  const std::uint32_t n = std::uint32_t(d.triangles.size());
  out.write(reinterpret_cast<const char*>(&n), 4);
  std::string records;
  records.reserve(std::size_t(n) * 50);
  for (const Triangle& t : d.triangles) {
    float record[12] = {0, 0, 0};
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) record[3 + 3 * k + c] = float(d.points[t[k]][c]);
    records.append(reinterpret_cast<const char*>(record), 48);
    records.append(2, '\0');  // attribute byte count
  }
  out.write(records.data(), std::streamsize(records.size()));
}

}  // namespace morphex::detail
