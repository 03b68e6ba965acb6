// SPDX-License-Identifier: GPL-3.0-or-later
// What the mesh readers and writers share: the per-format entry points, a text scanner that
// splits lines into tokens without copying them, exact number parsing with the fast paths that
// plain files need, and the wording of located errors.
#pragma once

#include <gmpxx.h>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "boolean/step1_triangulate.h"
#include "morphex/internal/files.h"
#include "morphex/io.h"

namespace morphex {
// The comment line a file written with `provenance` carries, without the format's comment marker:
// "written by morphex VERSION[: provenance]".
std::string provenance_line(const std::string& provenance);
}  // namespace morphex

namespace morphex::detail {

// One reader and one writer per format (io_off.cpp, io_obj.cpp, io_stl.cpp, io_ply.cpp).
Mesh read_off(const std::string& content, const std::string& name);
Mesh read_obj(const std::string& content, const std::string& name);
Mesh read_stl(const std::string& content, const std::string& name);
Mesh read_ply(const std::string& content, const std::string& name);
// `note`: one line of provenance, written as the format's comment (provenance_line, io.h).
// Plain formats write a mesh already rounded to their grid (morphex/rounding.h).
void write_off_exact(const Mesh& mesh, std::ostream& out, const std::string& note);
void write_off(const DoubleMesh& mesh, std::ostream& out, const std::string& note);
void write_obj(const DoubleMesh& mesh, std::ostream& out, const std::string& note);
void write_stl(const DoubleMesh& mesh, std::ostream& out, const std::string& note);
void write_ply(const DoubleMesh& mesh, std::ostream& out, const std::string& note);
// 3MF through lib3mf (io_3mf.cpp), loaded when first needed; without it (MORPHEX_3MF off, or
// the library cannot be loaded) they throw InputError, saying why_no_3mf().
bool have_3mf();
std::string why_no_3mf();
// Loads lib3mf's functions from `soname` into a table of its own: "" when it can, else why not
// (a test's hook for the message a user without the library would see).
std::string load_3mf_library(const char* soname);
Mesh read_3mf(const std::string& content, const std::string& name);
// Refuses (LossyOutputError) a mesh that lib3mf's text would change into another one.
void write_3mf(const DoubleMesh& mesh, std::ostream& out, const std::string& note,
               const std::string& name);
// glTF 2.0 binary, for viewers (io_glb.cpp): float positions and uint32 indices.
void write_glb(const DoubleMesh& mesh, std::ostream& out, const std::string& note);
// gzip (io_gzip.cpp): the first two bytes; the whole stream (every member) inflated, refused
// (InputError naming `name`) past `limit` bytes or when corrupt or truncated; compressed.
bool is_gzip(const std::string& content);
std::string gunzip(const std::string& content, const std::string& name, std::uint64_t limit);
std::string gzip(const std::string& content);

// Lines of a text, '#' comments stripped, split on whitespace; the tokens view the text.
struct Line {
  std::size_t number = 0;
  std::vector<std::string_view> tokens;
};

class TextReader {
 public:
  explicit TextReader(std::string_view content, std::size_t begin = 0)
      : content_(content), pos_(begin) {}
  // The next line with at least one token; false at the end.
  bool next(Line& line);
  std::size_t remaining_bytes() const {
    return pos_ < content_.size() ? content_.size() - pos_ : 0;
  }

 private:
  std::string_view content_;
  std::size_t pos_;
  std::size_t number_ = 0;
};

// Whitespace-separated tokens of one piece of text (header lines).
std::vector<std::string_view> split(std::string_view text);

// <cctype> takes an int that must be an unsigned char value: bytes above 127 would be UB.
inline bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

std::string at_line(std::size_t line);
// A token as shown in a message: quoted, bytes outside printable ASCII escaped, long ones cut.
std::string shown(std::string_view token);

// A coordinate: integers and fractions exactly, decimals as the nearest double. InputError
// naming the file and the line when malformed.
FT number(std::string_view token, const std::string& name, std::size_t line);
// The value of the literals parse_exact_number reads as a double (decimals, and integers short
// enough to be one exactly); nullopt for the others (fractions, long integers, malformed or
// non-finite text), which parse_exact_number then reads or refuses (mesh.cpp).
std::optional<double> double_literal(std::string_view text);
// The point of three coordinate tokens: made from the doubles at once when all three are double
// literals (one lazy object holding them, where three exact numbers and a point made of them are
// four allocations; reading a large mesh spent more time there than in parsing).
Point point_of(std::string_view x, std::string_view y, std::string_view z, const std::string& name,
               std::size_t line);
// The same as a double (formats that store doubles), refusing non-finite values.
double double_number(std::string_view token, const std::string& name, std::size_t line);
// A binary format's coordinate: InputError naming the file and `where` when it is not finite.
double finite_coordinate(double d, const std::string& name, const std::string& where);
// A non-negative count of at most 18 digits.
std::uint64_t count(std::string_view token, const std::string& name, std::size_t line,
                    const char* what);

// Appends the triangulation of a polygon face; InputError naming the face when it cannot be.
void add_polygon(Mesh& mesh, const std::vector<VertexIndex>& polygon, const std::string& name,
                 std::size_t face, std::size_t line);

// Appends the shortest decimal that reads back as exactly `value`.
void append_double(std::string& out, double value);
// Appends an exact number as exact OFF writes it: "num/den" in lowest terms, "num" for integers
// (mesh.cpp, beside to_rational_string, which they make).
void append_rational(std::string& out, const mpq_class& value);
void append_rational(std::string& out, double value);

// A hash of coordinate triples for maps keyed by position. +0 and -0 hash alike, as == treats
// them as one value (a hash that told them apart would keep one position twice).
struct DoublePointHash {
  std::size_t operator()(const std::array<double, 3>& p) const {
    std::size_t h = 1469598103934665603ULL;
    for (double c : p) {
      c += 0.0;  // -0 + 0 = +0
      std::uint64_t bits;
      std::memcpy(&bits, &c, 8);
      h = (h ^ bits) * 1099511628211ULL;
    }
    return h;
  }
};

}  // namespace morphex::detail
