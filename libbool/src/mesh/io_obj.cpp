// SPDX-License-Identifier: GPL-3.0-or-later
// Wavefront OBJ: v and f records (indices from 1, negative ones counting back); other records
// are ignored.
#include <charconv>
#include <ostream>

#include "mesh/io_text.h"

namespace morphex::detail {

Mesh read_obj(const std::string& content, const std::string& name) {
  TextReader reader(content);
  Line line;
  Mesh mesh;
  std::size_t faces = 0;
  std::vector<VertexIndex> polygon;
  while (reader.next(line)) {
    const std::string_view kind = line.tokens[0];
    if (kind == "v") {
      if (line.tokens.size() < 4)
        throw InputError(name, "vertex with fewer than 3 coordinates" + at_line(line.number));
      mesh.points.push_back(
          point_of(line.tokens[1], line.tokens[2], line.tokens[3], name, line.number));
    } else if (kind == "f") {
      polygon.clear();
      for (std::size_t k = 1; k < line.tokens.size(); ++k) {
        const std::string_view index = line.tokens[k].substr(0, line.tokens[k].find('/'));
        long long i = 0;
        const auto r = std::from_chars(index.data(), index.data() + index.size(), i);
        if (index.empty() || r.ec != std::errc() || r.ptr != index.data() + index.size())
          throw InputError(name, "face " + std::to_string(faces) + " has malformed index " +
                                     shown(line.tokens[k]) + at_line(line.number));
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

void write_obj(const DoubleMesh& m, std::ostream& out, const std::string& note) {
  std::string text = "# " + note + "\n";
  for (const auto& p : m.points) {
    text += "v";
    for (int k = 0; k < 3; ++k) {
      text += ' ';
      append_double(text, p[k]);
    }
    text += '\n';
  }
  for (const Triangle& t : m.triangles)
    text += "f " + std::to_string(t[0] + 1) + ' ' + std::to_string(t[1] + 1) + ' ' +
            std::to_string(t[2] + 1) + '\n';
  out.write(text.data(), std::streamsize(text.size()));
}

}  // namespace morphex::detail
