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

#include "io_text.h"

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

namespace {

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
      return detail::read_off(content, name);
    case MeshFormat::Obj:
      return detail::read_obj(content, name);
    case MeshFormat::Stl:
      return detail::read_stl(content, name);
    case MeshFormat::Ply:
      return detail::read_ply(content, name);
  }
  throw InputError(name, "unknown format");
}

Mesh read_mesh(const std::string& path) {
  // What is wrong with the path itself comes first: "unknown mesh format ''" would mislead.
  std::error_code error;
  if (path == "-") throw InputError(path, "standard input is not read: give a mesh file");
  if (fs::is_directory(path, error)) throw InputError(path, "is a directory, not a mesh file");
  if (!fs::exists(path, error)) throw InputError(path, "cannot open file: no such file");
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

std::string provenance_line(const std::string& provenance) {
  std::string line = std::string("written by morphex ") + version();
  if (!provenance.empty()) line += ": " + provenance;
  for (char& c : line)  // one line of printable text in every format
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
  return line;
}

void write_mesh(const Mesh& mesh, const std::string& path, const WriteOptions& options) {
  const std::string note = provenance_line(options.provenance);
  const MeshFormat format = format_from_path(path);
  if (options.exact && format != MeshFormat::Off)
    throw InputError(path, "the exact format is OFF: use a .off output with --exact");
  write_file_atomically(path, [&](std::ostream& out) {
    switch (format) {
      case MeshFormat::Off:
        detail::write_off(mesh, out, options.exact, note);
        break;
      case MeshFormat::Obj:
        detail::write_obj(mesh, out, note);
        break;
      case MeshFormat::Stl:
        detail::write_stl(mesh, out, note);
        break;
      case MeshFormat::Ply:
        detail::write_ply(mesh, out, note);
        break;
    }
  });
}

}  // namespace morphex
