// SPDX-License-Identifier: GPL-3.0-or-later
// Text scanning and number parsing for the mesh readers (io_text.h).
#include "mesh/io_text.h"

#include <charconv>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace morphex::detail {

namespace {

// ' ', and '\t', '\n', '\v', '\f', '\r' (9 to 13): two comparisons per byte.
bool is_space(char c) {
  return c == ' ' || static_cast<unsigned char>(c - '\t') < 5;
}

// On pointers, one token per pass of the inner loops: most of a large mesh file's reading time
// is spent here, a byte at a time.
void split_into(std::string_view text, std::vector<std::string_view>& out) {
  out.clear();
  const char* p = text.data();
  const char* const end = p + text.size();
  for (;;) {
    while (p != end && is_space(*p)) ++p;
    if (p == end) return;
    const char* q = p + 1;
    while (q != end && !is_space(*q)) ++q;
    out.emplace_back(p, std::size_t(q - p));
    p = q;
  }
}

}  // namespace

bool TextReader::next(Line& line) {
  while (pos_ < content_.size()) {
    const char* start = content_.data() + pos_;
    const void* newline = std::memchr(start, '\n', content_.size() - pos_);
    const std::size_t end = newline
                                ? std::size_t(static_cast<const char*>(newline) - content_.data())
                                : content_.size();
    std::string_view text = content_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++number_;
    const std::size_t hash = text.find('#');
    if (hash != std::string_view::npos) text = text.substr(0, hash);
    split_into(text, line.tokens);
    line.number = number_;
    if (!line.tokens.empty()) return true;
  }
  return false;
}

std::vector<std::string_view> split(std::string_view text) {
  std::vector<std::string_view> out;
  split_into(text, out);
  return out;
}

std::string at_line(std::size_t line) {
  return " at line " + std::to_string(line);
}

std::string shown(std::string_view token) {
  constexpr std::size_t kShown = 40;
  std::string out = "'";
  for (std::size_t i = 0; i < token.size() && i < kShown; ++i) {
    const auto c = static_cast<unsigned char>(token[i]);
    if (c >= 32 && c < 127 && c != '\\' && c != '\'') {
      out += char(c);
    } else {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", c);
      out += escaped;
    }
  }
  if (token.size() > kShown) out += "...";
  return out + "'";
}

FT number(std::string_view token, const std::string& name, std::size_t line) {
  try {
    return parse_exact_number(token);
  } catch (const InputError& e) {
    throw InputError(name, e.problem() + at_line(line));
  }
}

Point point_of(std::string_view x, std::string_view y, std::string_view z, const std::string& name,
               std::size_t line) {
  const std::optional<double> dx = double_literal(x), dy = double_literal(y),
                              dz = double_literal(z);
  if (dx && dy && dz) return Point(*dx, *dy, *dz);
  return Point(number(x, name, line), number(y, name, line), number(z, name, line));
}

double finite_coordinate(double d, const std::string& name, const std::string& where) {
  if (!std::isfinite(d)) throw InputError(name, "non-finite coordinate " + where);
  return d;
}

double double_number(std::string_view token, const std::string& name, std::size_t line) {
  if (const std::optional<double> d = double_literal(token)) return *d;
  const double d = CGAL::to_double(number(token, name, line));
  if (!std::isfinite(d))
    throw InputError(name, "non-finite coordinate " + shown(token) + at_line(line));
  return d;
}

std::uint64_t count(std::string_view token, const std::string& name, std::size_t line,
                    const char* what) {
  bool digits = !token.empty() && token.size() <= 18;
  for (char c : token) digits = digits && is_digit(c);
  if (!digits)
    throw InputError(name, std::string("invalid ") + what + " " + shown(token) + at_line(line));
  std::uint64_t value = 0;
  std::from_chars(token.data(), token.data() + token.size(), value);
  return value;
}

void add_polygon(Mesh& mesh, const std::vector<VertexIndex>& polygon, const std::string& name,
                 std::size_t face, std::size_t line) {
  if (polygon.size() == 3 && polygon[0] != polygon[1] && polygon[1] != polygon[2] &&
      polygon[0] != polygon[2]) {
    mesh.triangles.push_back({polygon[0], polygon[1], polygon[2]});
    return;
  }
  try {
    triangulate_polygon(mesh.points, polygon, mesh.triangles);
  } catch (const InputError& e) {
    throw InputError(name, e.problem() + ": face " + std::to_string(face) + at_line(line));
  }
}

void append_double(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

}  // namespace morphex::detail
