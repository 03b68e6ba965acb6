// SPDX-License-Identifier: GPL-3.0-or-later
// Mesh files: OFF (plain and exact), OBJ, STL (ASCII and binary), PLY (ASCII and binary), 3MF
// (when built with lib3mf) and glTF binary (.glb, written only, for viewers). The path "-" is
// standard input or output. Readers triangulate polygons and throw InputError naming the file, the
// problem and the line, vertex or face. Writers are atomic: a temporary file in the target's
// directory, then rename (morphex/atomic_files.h); standard output gets the whole file at once,
// once it is complete.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <stdexcept>
#include <string>

#include "morphex/atomic_files.h"
#include "morphex/error.h"
#include "morphex/mesh.h"
#include "morphex/rounding.h"
#include "morphex/version.h"

namespace morphex {

enum class MeshFormat { Off, Obj, Stl, Ply, ThreeMf, Glb };

// The path that means standard input (read_mesh) or standard output (write_mesh), named
// "<stdin>" / "<stdout>" in messages.
inline const std::string kStandardStream = "-";

// From the file extension (case-insensitive; "x.off.gz" is gzip-compressed OFF, read and written
// through zlib); throws InputError for an unknown one, for .3mf when
// morphex was built without lib3mf, and for "-" (a stream has no extension: see
// format_from_name).
MeshFormat format_from_path(const std::string& path);
// From a format name as given on a command line ("off", "obj", "stl", "ply", "3mf", "glb").
MeshFormat format_from_name(const std::string& name);
// False for 3MF when morphex was built without lib3mf (option MORPHEX_3MF).
bool format_available(MeshFormat format);
// True for the formats that can be read (all but glb).
bool format_readable(MeshFormat format);
// The format of content without a file name (standard input), from its first bytes: binary STL
// (its size matches the triangle count of its 84-byte header), "solid" (ASCII STL), an OFF header
// (after '#' comments), "ply", or a ZIP archive (3MF). Throws InputError naming `name` otherwise.
MeshFormat detect_format(const std::string& content, const std::string& name);

// "-" reads standard input (under the input limits), the format detected from the content.
// gzip-compressed content (a file or standard input) is inflated first, within the input size
// limit (max_file_bytes applies to the inflated bytes too).
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

struct WriteOptions {
  bool exact = false;  // OFF with rational coordinates; only for .off
  // Provenance, one line (what made the file: the command or pipeline stage), written with the
  // morphex version as a comment where the format has one: OFF and OBJ '#', PLY "comment", binary
  // STL's 80-byte header (cut to fit). Empty: the version alone.
  std::string provenance;
  // The format written to standard output (path "-"), which has no extension to choose it.
  MeshFormat stream_format = MeshFormat::Off;
  // Measure the volume change of rounding (RoundingReport::volume_change): two exact volumes.
  bool measure_rounding = false;
};
// Plain formats store doubles (OFF, OBJ, PLY), floats (STL, glb) or lib3mf's decimals (3MF):
// the mesh is rounded to the format's grid as a valid solid (round_mesh, morphex/rounding.h), so
// that the file read back is a valid solid within a few units in the last place of the exact one;
// what rounding did is returned (all zero for the exact OFF). A coordinate outside the format's
// range throws LossyOutputError. "-" writes to standard output in options.stream_format.
RoundingReport write_mesh(const Mesh& mesh, const std::string& path,
                          const WriteOptions& options = {});
// The same into a stream: the whole file is composed in memory first, so a failure writes nothing.
RoundingReport write_mesh(const Mesh& mesh, std::ostream& out, MeshFormat format,
                          const WriteOptions& options = {});
// The grid a format's readers see: doubles, floats (STL, glb) or lib3mf's decimals (3MF).
RoundingGrid grid_of(MeshFormat format);

}  // namespace morphex
