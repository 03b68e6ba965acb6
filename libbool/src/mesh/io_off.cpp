// SPDX-License-Identifier: GPL-3.0-or-later
// OFF, plain (coordinates as decimals) and exact (integers and fractions num/den, read and
// written without loss).
#include <algorithm>
#include <charconv>
#include <ostream>

#include "mesh/io_text.h"

namespace morphex::detail {

namespace {

// Geomview's "appearance { ... }" blocks before the header (braces balanced, any number of
// lines): skipped. Returns the first line after them, false at the end.
bool skip_appearance(TextReader& reader, Line& line, const std::string& name) {
  while (line.tokens[0] == "appearance") {
    int depth = 0;
    bool opened = false;
    do {
      for (const std::string_view t : line.tokens)
        for (const char c : t) {
          depth += c == '{';
          depth -= c == '}';
          opened = opened || c == '{';
        }
      if (opened && depth <= 0) break;
    } while (reader.next(line));
    if (!opened || depth > 0)
      throw InputError(name, "unterminated appearance block" + at_line(line.number));
    if (!reader.next(line)) return false;
  }
  return true;
}

bool is_count(std::string_view t) {
  return !t.empty() && std::all_of(t.begin(), t.end(), [](char c) { return is_digit(c); });
}

}  // namespace

// The OFF family: OFF with the optional prefixes ST (texture coordinates), C (colours), N
// (normals) in any combination (COFF, NOFF, CNOFF, STOFF, ...), whose extra numbers after x y z
// are ignored; the header keyword may be left out (Geomview reads a file that starts with its
// counts as OFF); Geomview's appearance blocks before it are skipped. Four-dimensional (4OFF) and
// n-dimensional (nOFF) files are refused by name.
Mesh read_off(const std::string& content, const std::string& name) {
  TextReader reader(content);
  Line line;
  if (!reader.next(line) || !skip_appearance(reader, line, name))
    throw InputError(name, "empty file");
  std::vector<std::string_view> header = line.tokens;
  const std::string_view magic = header[0];
  if (magic.size() >= 4 && magic.compare(magic.size() - 4, 4, "4OFF") == 0)
    throw InputError(
        name, "4OFF: four-dimensional vertices; morphex reads 3D meshes" + at_line(line.number));
  if (magic.size() >= 4 && magic.compare(magic.size() - 4, 4, "nOFF") == 0)
    throw InputError(name,
                     "nOFF: vertices of a given dimension are not supported; morphex reads "
                     "3D meshes (OFF, COFF, NOFF, CNOFF, STOFF)" +
                         at_line(line.number));
  const bool keyword = magic.size() >= 3 && magic.compare(magic.size() - 3, 3, "OFF") == 0;
  if (!keyword && !(is_count(magic) && header.size() >= 2 && is_count(header[1])))
    throw InputError(name, "not an OFF file: header is " + shown(magic) + at_line(line.number));
  if (keyword) header.erase(header.begin());
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
    mesh.points.push_back(
        point_of(line.tokens[0], line.tokens[1], line.tokens[2], name, line.number));
  }
  mesh.triangles.reserve(nf);
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
      const std::string_view t = line.tokens[k];
      std::uint64_t index = 0;
      const auto r = std::from_chars(t.data(), t.data() + t.size(), index);
      if (t.size() > 10 || r.ec != std::errc() || r.ptr != t.data() + t.size() || index >= nv)
        throw InputError(name, "face " + std::to_string(f) + " has vertex index " + shown(t) +
                                   " out of range [0, " + std::to_string(nv) + ")" +
                                   at_line(line.number));
      polygon.push_back(VertexIndex(index));
    }
    add_polygon(mesh, polygon, name, f, line.number);
  }
  return mesh;
}

namespace {

// OFF's text, with each vertex's three coordinates appended by `coordinates`.
template <class Points, class Coordinates>
void write_off_text(const Points& points, const std::vector<Triangle>& triangles, std::ostream& out,
                    const std::string& note, Coordinates coordinates) {
  std::string text = "OFF\n# " + note + "\n" + std::to_string(points.size()) + ' ' +
                     std::to_string(triangles.size()) + " 0\n";
  auto flush = [&](bool always) {
    if (always || text.size() > (1u << 20)) {
      out.write(text.data(), std::streamsize(text.size()));
      text.clear();
    }
  };
  for (const auto& p : points) {
    coordinates(text, p);
    flush(false);
  }
  for (const Triangle& t : triangles) {
    text += "3 ";
    for (int k = 0; k < 3; ++k) {
      text += std::to_string(t[k]);
      text += k < 2 ? ' ' : '\n';
    }
    flush(false);
  }
  flush(true);
}

}  // namespace

void write_off_exact(const Mesh& m, std::ostream& out, const std::string& note) {
  // A point of doubles is written from its doubles; another from its exact coordinates, read
  // from the exact point itself: each p.cartesian(k) would be a lazy number of its own, to be
  // evaluated once more (a lock and a system call each, in CGAL's thread-safe evaluation).
  write_off_text(m.points, m.triangles, out, note, [](std::string& text, const Point& p) {
    const bool doubles = has_double_coordinates(p);
    for (int k = 0; k < 3; ++k) {
      if (doubles)
        append_rational(text, CGAL::approx(p).cartesian(k).inf());
      else
        append_rational(text, CGAL::exact(p).cartesian(k));
      text += k < 2 ? ' ' : '\n';
    }
  });
}

void write_off(const DoubleMesh& m, std::ostream& out, const std::string& note) {
  write_off_text(m.points, m.triangles, out, note,
                 [](std::string& text, const std::array<double, 3>& p) {
                   for (int k = 0; k < 3; ++k) {
                     append_double(text, p[k]);
                     text += k < 2 ? ' ' : '\n';
                   }
                 });
}

}  // namespace morphex::detail
