// SPDX-License-Identifier: GPL-3.0-or-later
// Mesh files: OFF (plain and exact), OBJ, STL (ASCII and binary), PLY (ASCII and binary).
// Readers triangulate polygons and throw InputError naming the file, the problem and the line,
// vertex or face. Writers are atomic: a temporary file in the target's directory, then rename.
#pragma once

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>

#include "morphex/mesh.h"

namespace morphex {

enum class MeshFormat { Off, Obj, Stl, Ply };

// From the file extension (case-insensitive); throws InputError for an unknown one.
MeshFormat format_from_path(const std::string& path);

Mesh read_mesh(const std::string& path);

// Limits that protect a process from inputs it cannot hold: files larger than max_file_bytes are
// refused before they are read, meshes with more than max_faces faces after reading. Process-wide.
struct InputLimits {
  std::uint64_t max_file_bytes = std::uint64_t(2) << 30;  // 2 GiB
  std::uint64_t max_faces = 50'000'000;
};
void set_input_limits(const InputLimits& limits);
InputLimits input_limits();
// `name` is used in error messages in place of a file name.
Mesh read_mesh_from_string(const std::string& content, MeshFormat format, const std::string& name);

// Removes the temporary files of writes in progress. Async-signal-safe: a SIGINT handler calls it
// before exiting, so an interrupted run leaves neither a half-written output nor a stray temporary.
void remove_pending_temporary_files() noexcept;

struct WriteOptions {
  bool exact = false;  // OFF with rational coordinates; only for .off
  // Provenance, one line (what made the file: the command or pipeline stage), written with the
  // morphex version as a comment where the format has one: OFF and OBJ '#', PLY "comment", binary
  // STL's 80-byte header (cut to fit). Empty: the version alone.
  std::string provenance;
};
// The library's version ("0.1.0").
const char* version();
// The comment line a file written with `provenance` carries, without the format's comment marker.
std::string provenance_line(const std::string& provenance);
void write_mesh(const Mesh& mesh, const std::string& path, const WriteOptions& options = {});

// Writes through `writer` into a temporary file next to `path`, then renames it over `path`:
// readers never see a half-written file and a failure leaves the old file untouched.
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& writer);

// True when both paths name the same file (existing or not).
bool same_file(const std::string& a, const std::string& b);

// Triangulates a simple polygon (possibly non-convex, approximately planar) given by vertex
// indices, by ear clipping in the plane of its exact Newell normal. Throws std::invalid_argument
// when the polygon is degenerate or cannot be triangulated.
void triangulate_polygon(const std::vector<Point>& points, const std::vector<VertexIndex>& polygon,
                         std::vector<Triangle>& out);

}  // namespace morphex
