// SPDX-License-Identifier: GPL-3.0-or-later
// Mesh files: the format from the extension, reading under the process's input limits, and the
// dispatch to one reader and writer per format (io_off.cpp, io_obj.cpp, io_stl.cpp, io_ply.cpp).
#include "morphex/io.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "mesh/io_text.h"

namespace morphex {

namespace fs = std::filesystem;

namespace {

std::string name_of(const std::string& path) {
  return path == kStandardStream ? "<stdin>" : path;
}

const char* const kExpected = "(expected .off, .obj, .stl, .ply, .3mf or .glb)";

bool lookup_format(std::string name, MeshFormat& format) {
  static const std::pair<const char*, MeshFormat> kNames[] = {
      {"off", MeshFormat::Off}, {"obj", MeshFormat::Obj},     {"stl", MeshFormat::Stl},
      {"ply", MeshFormat::Ply}, {"3mf", MeshFormat::ThreeMf}, {"glb", MeshFormat::Glb}};
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  for (const auto& [known, value] : kNames)
    if (name == known) {
      format = value;
      return true;
    }
  return false;
}

}  // namespace

namespace {

bool is_gzip_path(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext == ".gz";
}

}  // namespace

MeshFormat format_from_path(const std::string& path) {
  if (path == kStandardStream)
    throw InputError("-", "a standard stream has no extension to give its format");
  // "x.off.gz": the format of the file inside.
  std::string ext =
      fs::path(is_gzip_path(path) ? fs::path(path).stem() : fs::path(path)).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  MeshFormat format;
  if (ext.size() < 2 || !lookup_format(ext.substr(1), format))
    throw InputError(path, "unknown mesh format '" + ext + "' " + kExpected);
  if (!format_available(format))
    throw InputError(path, "3MF is not available: " + detail::why_no_3mf());
  return format;
}

MeshFormat format_from_name(const std::string& name) {
  MeshFormat format;
  if (!lookup_format(name, format))
    throw InputError(name, "unknown mesh format '." + name + "' " + kExpected);
  return format;
}

bool format_available(MeshFormat format) {
  return format != MeshFormat::ThreeMf || detail::have_3mf();
}

bool format_readable(MeshFormat format) {
  return format != MeshFormat::Glb;
}

MeshFormat detect_format(const std::string& content, const std::string& name) {
  if (content.size() >= 84) {
    std::uint32_t n = 0;
    std::memcpy(&n, content.data() + 80, 4);
    if (content.size() == 84 + std::uint64_t(n) * 50) return MeshFormat::Stl;
  }
  if (content.compare(0, 5, "solid") == 0) return MeshFormat::Stl;
  if (content.compare(0, 4, "PK\x03\x04") == 0) return MeshFormat::ThreeMf;
  if (content.compare(0, 3, "ply") == 0) return MeshFormat::Ply;
  // OFF: the first token after blank lines and '#' comments is OFF (or COFF, NOFF, ...).
  std::size_t pos = 0;
  while (pos < content.size()) {
    pos = content.find_first_not_of(" \t\r\n", pos);
    if (pos == std::string::npos || content[pos] != '#') break;
    pos = content.find('\n', pos);
  }
  if (pos != std::string::npos && pos < content.size()) {
    const std::size_t end = std::min(content.find_first_of(" \t\r\n", pos), content.size());
    const std::string token = content.substr(pos, end - pos);
    if (token.size() >= 3 && token.compare(token.size() - 3, 3, "OFF") == 0) return MeshFormat::Off;
  }
  throw InputError(name, "cannot tell the mesh format from the first bytes " +
                             detail::shown(content.substr(0, 16)) +
                             ": standard input takes OFF, STL (ASCII or binary), PLY or 3MF");
}

namespace {

std::atomic<std::uint64_t> max_file_bytes{InputLimits().max_file_bytes};
std::atomic<std::uint64_t> max_faces{InputLimits().max_faces};

// Reads a whole stream under the size limit, in chunks: a device or pipe (mesh:path=/dev/zero,
// <(cmd), standard input) has no size to check beforehand and may never end.
std::string read_stream(std::istream& in, const std::string& name) {
  std::string content;
  std::array<char, 1 << 16> chunk;
  while (in.read(chunk.data(), chunk.size()) || in.gcount() > 0) {
    content.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
    if (content.size() > max_file_bytes)
      throw InputError(name, "file too large: more than " + std::to_string(max_file_bytes.load()) +
                                 " bytes (raise the limit with --max-input-mb)");
  }
  if (in.bad()) throw InputError(name, std::string("cannot read: ") + std::strerror(errno));
  return content;
}

std::string read_file_bytes(const std::string& path) {
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
  return read_stream(in, path);
}

// A file's content, inflated when it is gzip-compressed (by its first bytes: a ".gz" name is not
// needed, and a ".gz" file that is not compressed is read as it is).
std::string read_file(const std::string& path) {
  std::string content = read_file_bytes(path);
  if (detail::is_gzip(content)) return detail::gunzip(content, path, max_file_bytes);
  return content;
}

// Standard input, whose format has to be read from its content.
Mesh read_standard_input() {
  const std::string name = name_of(kStandardStream);
  std::string content = read_stream(std::cin, name);
  if (detail::is_gzip(content)) content = detail::gunzip(content, name, max_file_bytes);
  if (content.find_first_not_of(" \t\r\n") == std::string::npos)
    throw InputError(name, "empty input: nothing was piped into standard input");
  return read_mesh_from_string(content, detect_format(content, name), name);
}

void check_face_limit(const Mesh& mesh, const std::string& name) {
  if (mesh.num_triangles() > max_faces)
    throw InputError(name, "too many faces: " + std::to_string(mesh.num_triangles()) + " (limit " +
                               std::to_string(max_faces.load()) + "; raise it with --max-faces)");
}

}  // namespace

Mesh read_mesh_from_string(const std::string& content, MeshFormat format, const std::string& name) {
  if (content.find_first_not_of(" \t\r\n") == std::string::npos)
    throw InputError(name, "empty file");
  switch (format) {
    case MeshFormat::Off:
      return detail::read_off(content, name);
    case MeshFormat::Obj:
      return detail::read_obj(content, name);
    case MeshFormat::Stl:
      return detail::read_stl(content, name);
    case MeshFormat::Ply:
      return detail::read_ply(content, name);
    case MeshFormat::ThreeMf:
      return detail::read_3mf(content, name);
    case MeshFormat::Glb:
      break;
  }
  throw InputError(name,
                   "glb files are written for viewers, not read: give OFF, OBJ, STL, PLY or 3MF");
}

Mesh read_mesh(const std::string& path) {
  // What is wrong with the path itself comes first: "unknown mesh format ''" would mislead.
  std::error_code error;
  if (path == kStandardStream) {
    Mesh mesh = read_standard_input();
    check_face_limit(mesh, name_of(path));
    return mesh;
  }
  if (fs::is_directory(path, error)) throw InputError(path, "is a directory, not a mesh file");
  if (!fs::exists(path, error)) throw InputError(path, "cannot open file: no such file");
  const MeshFormat format = format_from_path(path);
  if (!format_readable(format))
    throw InputError(path,
                     "glb files are written for viewers, not read: give OFF, OBJ, STL, PLY or 3MF");
  Mesh mesh = read_mesh_from_string(read_file(path), format, path);
  check_face_limit(mesh, path);
  return mesh;
}

void set_input_limits(const InputLimits& limits) {
  max_file_bytes = limits.max_file_bytes;
  max_faces = limits.max_faces;
}

InputLimits input_limits() {
  return {max_file_bytes.load(), max_faces.load()};
}

std::string provenance_line(const std::string& provenance) {
  std::string line = std::string("written by morphex ") + version();
  if (!provenance.empty()) line += ": " + provenance;
  for (char& c : line)  // one line of printable text in every format
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
  return line;
}

namespace {

Mesh scaled(const Mesh& mesh, int factor) {
  Mesh out;
  out.triangles = mesh.triangles;
  out.points.reserve(mesh.points.size());
  for (const Point& p : mesh.points) {
    const auto& e = CGAL::exact(p);
    out.points.push_back(point_from_exact({e.x() * factor, e.y() * factor, e.z() * factor}));
  }
  return out;
}

void check_exact_format(MeshFormat format, const WriteOptions& options, const std::string& name) {
  if (options.exact && format != MeshFormat::Off)
    throw InputError(name, "the exact format is OFF: use a .off output with --exact");
}

// The file's bytes: the exact OFF as it is, a plain format from the mesh rounded to its grid as a
// valid solid (morphex/rounding.h). Composed before anything is written, so that a failure
// leaves nothing behind.
void emit(const Mesh& mesh, std::ostream& out, MeshFormat format, const WriteOptions& options,
          const std::string& name, RoundingReport& report) {
  const std::string note = provenance_line(options.provenance);
  if (options.exact) {
    detail::write_off_exact(mesh, out, note);
    return;
  }
  RoundingOptions rounding;
  rounding.grid = grid_of(format);
  rounding.measure_volume = options.measure_rounding;
  RoundedMesh rounded;
  try {
    // 3MF is written in micrometres: lib3mf keeps six decimals of a float, as fine as the float
    // itself from 16 units on, where in millimetres a micrometre is a coarse grid for small parts.
    // Scaling by 1000 is exact and keeps the solid valid; readers convert back exactly.
    rounded = format == MeshFormat::ThreeMf ? round_mesh(scaled(mesh, 1000), rounding)
                                            : round_mesh(mesh, rounding);
  } catch (const LossyOutputError& e) {
    throw LossyOutputError(name, e.problem());
  }
  report = rounded.report;
  if (format == MeshFormat::ThreeMf) {  // the report in the mesh's own units
    report.max_displacement /= 1000;
    report.volume_change /= 1e9;
  }
  const DoubleMesh& d = rounded.mesh;
  switch (format) {
    case MeshFormat::Off:
      detail::write_off(d, out, note);
      break;
    case MeshFormat::Obj:
      detail::write_obj(d, out, note);
      break;
    case MeshFormat::Stl:
      detail::write_stl(d, out, note);
      break;
    case MeshFormat::Ply:
      detail::write_ply(d, out, note);
      break;
    case MeshFormat::ThreeMf:
      detail::write_3mf(d, out, note, name);
      break;
    case MeshFormat::Glb:
      detail::write_glb(d, out, note);
      break;
  }
}

}  // namespace

RoundingGrid grid_of(MeshFormat format) {
  switch (format) {
    case MeshFormat::Stl:
    case MeshFormat::Glb:
      return RoundingGrid::Float;
    case MeshFormat::ThreeMf:
      return RoundingGrid::ThreeMf;
    default:
      return RoundingGrid::Double;
  }
}

RoundingReport write_mesh(const Mesh& mesh, std::ostream& out, MeshFormat format,
                          const WriteOptions& options) {
  const std::string name = "<stdout>";
  check_exact_format(format, options, name);
  // Composed in memory, then written at once: a failure midway leaves nothing on the stream.
  std::ostringstream text;
  RoundingReport report;
  emit(mesh, text, format, options, name, report);
  const std::string bytes = std::move(text).str();
  out.write(bytes.data(), std::streamsize(bytes.size()));
  out.flush();
  if (!out) throw StorageError(name, "write failed");
  return report;
}

RoundingReport write_mesh(const Mesh& mesh, const std::string& path, const WriteOptions& options) {
  if (path == kStandardStream) {
    if (!format_available(options.stream_format)) format_from_path("<stdout>.3mf");  // says why
    return write_mesh(mesh, std::cout, options.stream_format, options);
  }
  const MeshFormat format = format_from_path(path);
  check_exact_format(format, options, path);
  RoundingReport report;
  if (!is_gzip_path(path)) {
    write_file_atomically(
        path, [&](std::ostream& out) { emit(mesh, out, format, options, path, report); });
    return report;
  }
  std::ostringstream text;  // "x.stl.gz": the format's bytes, compressed whole
  emit(mesh, text, format, options, path, report);
  const std::string bytes = detail::gzip(std::move(text).str());
  write_file_atomically(
      path, [&](std::ostream& out) { out.write(bytes.data(), std::streamsize(bytes.size())); });
  return report;
}

}  // namespace morphex
