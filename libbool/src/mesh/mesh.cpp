// SPDX-License-Identifier: GPL-3.0-or-later
#include "morphex/mesh.h"

#include <gmpxx.h>
#include <tbb/parallel_for.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <sstream>
#include <type_traits>

#include "exact/number_parts.h"
#include "mesh/io_text.h"

namespace morphex {

using ExactFT = std::decay_t<decltype(CGAL::exact(std::declval<FT>()))>;

DoubleMesh to_double(const Mesh& mesh) {
  DoubleMesh out;
  out.points.reserve(mesh.points.size());
  for (const Point& p : mesh.points)
    out.points.push_back({CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())});
  out.triangles = mesh.triangles;
  return out;
}

Mesh from_double(const DoubleMesh& mesh) {
  Mesh out;
  out.points.reserve(mesh.points.size());
  for (const auto& p : mesh.points) out.points.emplace_back(p[0], p[1], p[2]);
  out.triangles = mesh.triangles;
  return out;
}

Point point_from_exact(Kernel::Exact_kernel::Point_3 exact) {
  return Point(Point::Rep(std::move(exact)));
}

bool has_double_coordinates(const Point& p) {
  // The interval approximation encloses the exact value: a zero-width interval is that value.
  const auto& a = CGAL::approx(p);
  return a.x().is_point() && a.y().is_point() && a.z().is_point();
}

void make_exact(Mesh& mesh) {
  for (Point& p : mesh.points) {
    if (has_double_coordinates(p)) {
      // A point made of doubles needs no rational at all, and may still carry a history.
      const auto& a = CGAL::approx(p);
      p = Point(a.x().inf(), a.y().inf(), a.z().inf());
      continue;
    }
    // Evaluating a lazy point stores its exact value, tightens its interval and cuts the
    // construction graph below it; an already evaluated point returns at once.
    CGAL::exact(p);
  }
}

namespace detail {

void append_rational(std::string& out, const mpq_class& q) {
  static_assert(std::is_same_v<ExactFT, mpq_class>, "the exact numbers are GMP's (CGAL_USE_GMPXX)");
  // GMP prints lowest terms (CGAL keeps them canonical) without "/1", and allocates nothing:
  // room for both numbers, their sign and the slash, then cut to what it wrote.
  const std::size_t at = out.size();
  out.resize(at + mpz_sizeinbase(q.get_num_mpz_t(), 10) + mpz_sizeinbase(q.get_den_mpz_t(), 10) +
             3);
  mpq_get_str(out.data() + at, 10, q.get_mpq_t());
  out.resize(at + std::strlen(out.data() + at));
}

void append_rational(std::string& out, double d) {
  // d = odd 2^e: "odd" or "odd/2^-e", on machine integers when they hold them (every coordinate
  // of a mesh file but the tiny and the huge), else by GMP.
  if (d == 0) {
    out += '0';
    return;
  }
  const auto [m, e] = odd_times_power(d);
  auto append_integer = [&](auto value) {
    char buffer[24];
    out.append(buffer, std::to_chars(buffer, buffer + sizeof buffer, value).ptr);
  };
  if (e >= 0 && e <= 10) {
    append_integer(m * (std::int64_t(1) << e));  // |m| < 2^53
  } else if (e < 0 && e >= -63) {
    append_integer(m);
    out += '/';
    append_integer(std::uint64_t(1) << -e);
  } else {
    append_rational(out, mpq_class(d));
  }
}

}  // namespace detail

std::string to_rational_string(const FT& value) {
  std::string text;
  const auto& approx = CGAL::approx(value);
  if (approx.is_point())  // a double: no exact number to evaluate
    detail::append_rational(text, approx.inf());
  else
    detail::append_rational(text, CGAL::exact(value));
  return text;
}

namespace detail {

// Short integers (at most 15 digits) are doubles exactly, and decimals mean the nearest one: no
// rational arithmetic for the commonest coordinates.
std::optional<double> double_literal(std::string_view text) {
  const std::string_view digits = !text.empty() && text[0] == '+' ? text.substr(1) : text;
  const char* const end = digits.data() + digits.size();
  if (digits.find_first_of(".eEnNiI") == std::string_view::npos) {
    // Longer integers and fractions are exact rationals (parse_exact_number).
    if (digits.empty() || digits.size() > 15 || digits.find('/') != std::string_view::npos)
      return std::nullopt;
    long long value = 0;
    const auto r = std::from_chars(digits.data(), end, value);
    if (r.ec != std::errc() || r.ptr != end) return std::nullopt;
    return double(value);
  }
  double d = 0;
  const auto r = std::from_chars(digits.data(), end, d);
  if (r.ec != std::errc() || r.ptr != end || !std::isfinite(d)) return std::nullopt;
  return d;
}

}  // namespace detail

FT parse_exact_number(std::string_view text) {
  // Integers and fractions are exact; decimal literals mean the nearest double, as in any mesh
  // file written by floating-point software. Most are read by the fast path; what is left here
  // is long integers, fractions, forms from_chars does not take, and malformed text.
  if (const std::optional<double> d = detail::double_literal(text)) return FT(*d);
  if (text.empty()) throw InputError("", "empty number");
  const std::string_view digits = text[0] == '+' ? text.substr(1) : text;  // GMP rejects '+'
  auto malformed = [&] {
    std::string shown(text.substr(0, 40));
    for (char& c : shown)
      if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
    return InputError("", "malformed number '" + shown + (text.size() > 40 ? "...'" : "'"));
  };
  if (digits.find_first_of(".eEnNiI") == std::string_view::npos) {
    mpq_class q;
    const std::string copy(digits);
    if (copy.empty() || copy[0] == '+' || q.set_str(copy, 10) != 0 || q.get_den() == 0)
      throw malformed();
    q.canonicalize();
    return FT(ExactFT(q.get_str()));
  }
  double d = 0;
  const auto r = std::from_chars(digits.data(), digits.data() + digits.size(), d);
  if (r.ec != std::errc() || r.ptr != digits.data() + digits.size()) {
    // Forms from_chars does not take (hexadecimal floats): strtod decides.
    const std::string copy(text);
    char* end = nullptr;
    d = std::strtod(copy.c_str(), &end);
    if (end == copy.c_str() || *end != '\0') throw malformed();
  }
  if (!std::isfinite(d)) {
    std::string shown(text.substr(0, 40));
    throw InputError("", "non-finite number '" + shown + "'");
  }
  return FT(d);
}

}  // namespace morphex
