// SPDX-License-Identifier: GPL-3.0-or-later
// Six times the exact volume of a mesh whose vertices lie over many different denominators: the
// results of Booleans and morphology, whose new vertices are crossings of three planes, each over
// the determinant of their normals.
//
// Vertex v over its own denominator w_v (the least common multiple of its three) has integer
// coordinates X_v, and face (a, b, c) adds det(X_a, X_b, X_c) / (w_a w_b w_c). On such meshes the
// sum is a rational of hundreds of thousands of bits (knot1 opened by an octahedron: 544,000), and
// adding the terms as rationals reduces every partial sum by a gcd, which at those sizes costs
// many times the products: it was nearly all of the time. Here a partial sum's denominator is kept
// as a product of known factors (the power of two, the small odd primes and the distinct rest of
// the vertices' denominators, each by index, at the largest power either operand needs), so that
// two partial sums come over one denominator by products alone, and one gcd at the end reduces
// the result. Where two rests share a factor the denominators are larger than needed, never wrong.
#include <gmpxx.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "mesh/volume_internal.h"

namespace morphex::detail {
namespace {

constexpr std::uint32_t kNoFactor = 0xffffffffu;

// The odd primes below 64. Vertices' denominators differ mostly by powers of these (knot1 opened:
// 7,272 distinct odd parts, 3,248 once these are taken out), and as factors of their own they are
// multiplied in at the largest power any term needs, not once per distinct odd part.
constexpr std::array<unsigned long, 17> kSmallPrimes = {3,  5,  7,  11, 13, 17, 19, 23, 29,
                                                        31, 37, 41, 43, 47, 53, 59, 61};

// Factors by index, with their powers, sorted by index: a small prime's index is its position in
// kSmallPrimes, the others follow.
using Factors = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

// The vertices over their own denominators: w_v = 2^twos[v] times the product of factor[id] ^
// power over factors_of[v]; integer[v] = the coordinates times w_v.
struct VertexDenominators {
  std::vector<std::array<mpz_class, 3>> integer;
  std::vector<unsigned long> twos;
  std::vector<Factors> factors_of;
  std::vector<mpz_class> factor;  // the small primes, then the distinct rest of the odd parts
};

VertexDenominators vertex_denominators(const Mesh& mesh) {
  const std::size_t n = mesh.points.size();
  VertexDenominators d;
  d.integer.resize(n);
  d.twos.resize(n);
  d.factors_of.resize(n);
  std::vector<mpz_class> rest(n);  // the odd part without the small primes
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t v) {
    const auto& p = CGAL::exact(mesh.points[v]);
    mpz_class w = p.x().get_den();
    for (int k = 1; k < 3; ++k)
      mpz_lcm(w.get_mpz_t(), w.get_mpz_t(), p.cartesian(k).get_den_mpz_t());
    for (int k = 0; k < 3; ++k) {
      const mpq_class& c = p.cartesian(k);
      mpz_divexact(d.integer[v][k].get_mpz_t(), w.get_mpz_t(), c.get_den_mpz_t());
      d.integer[v][k] *= c.get_num();
    }
    d.twos[v] = mpz_scan1(w.get_mpz_t(), 0);
    mpz_tdiv_q_2exp(rest[v].get_mpz_t(), w.get_mpz_t(), d.twos[v]);
    for (std::uint32_t i = 0; i < kSmallPrimes.size(); ++i) {
      std::uint32_t power = 0;
      for (; mpz_divisible_ui_p(rest[v].get_mpz_t(), kSmallPrimes[i]); ++power)
        mpz_divexact_ui(rest[v].get_mpz_t(), rest[v].get_mpz_t(), kSmallPrimes[i]);
      if (power > 0) d.factors_of[v].push_back({i, power});
    }
  });
  for (const unsigned long prime : kSmallPrimes) d.factor.emplace_back(prime);
  // Equal rests get one index (a vertex of the input and most constructed ones share theirs with
  // neighbours built from the same planes).
  std::vector<std::uint32_t> order;
  for (std::uint32_t v = 0; v < n; ++v)
    if (rest[v] != 1) order.push_back(v);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return mpz_cmp(rest[a].get_mpz_t(), rest[b].get_mpz_t()) < 0;
  });
  for (std::size_t i = 0; i < order.size(); ++i) {
    if (i == 0 || rest[order[i]] != d.factor.back()) d.factor.push_back(rest[order[i]]);
    d.factors_of[order[i]].push_back({std::uint32_t(d.factor.size() - 1), 1});
  }
  return d;
}

// numerator / denominator, denominator = 2^twos times the product of factor[id] ^ power over
// factors.
struct Partial {
  mpz_class numerator, denominator = 1;
  unsigned long twos = 0;
  Factors factors;
};

// The product of factor[id] ^ power over `powers`, as a balanced tree: operands of similar size.
mpz_class product(const VertexDenominators& d, const Factors& powers) {
  if (powers.empty()) return 1;
  std::vector<mpz_class> level(powers.size());
  for (std::size_t i = 0; i < powers.size(); ++i)
    mpz_pow_ui(level[i].get_mpz_t(), d.factor[powers[i].first].get_mpz_t(), powers[i].second);
  while (level.size() > 1) {
    for (std::size_t i = 0; 2 * i + 1 < level.size(); ++i)
      level[i] = level[2 * i] * level[2 * i + 1];
    if (level.size() % 2 == 1) level[level.size() / 2] = std::move(level.back());
    level.resize((level.size() + 1) / 2);
  }
  return std::move(level[0]);
}

Partial face_term(const Mesh& mesh, const VertexDenominators& d, std::uint32_t f) {
  const Triangle& t = mesh.triangles[f];
  const auto &a = d.integer[t[0]], &b = d.integer[t[1]], &c = d.integer[t[2]];
  Partial p;
  // a . (b x c)
  p.numerator = a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
                a[2] * (b[0] * c[1] - b[1] * c[0]);
  if (p.numerator == 0) return p;  // adds nothing: no denominator to carry
  for (const VertexIndex v : t) {
    p.twos += d.twos[v];
    p.factors.insert(p.factors.end(), d.factors_of[v].begin(), d.factors_of[v].end());
  }
  std::sort(p.factors.begin(), p.factors.end());
  std::size_t kept = 0;  // equal indices merged, their powers added
  for (std::size_t i = 0; i < p.factors.size(); ++i) {
    if (kept > 0 && p.factors[kept - 1].first == p.factors[i].first)
      p.factors[kept - 1].second += p.factors[i].second;
    else
      p.factors[kept++] = p.factors[i];
  }
  p.factors.resize(kept);
  // A face whose corners share a denominator often has a determinant divisible by it (three
  // points of one plane): dividing the known factors out here keeps every partial sum smaller.
  const unsigned long common_twos = std::min(p.twos, mpz_scan1(p.numerator.get_mpz_t(), 0));
  mpz_tdiv_q_2exp(p.numerator.get_mpz_t(), p.numerator.get_mpz_t(), common_twos);
  p.twos -= common_twos;
  kept = 0;
  for (auto [id, power] : p.factors) {
    const mpz_srcptr f = d.factor[id].get_mpz_t();
    for (; power > 0 && mpz_divisible_p(p.numerator.get_mpz_t(), f); --power)
      mpz_divexact(p.numerator.get_mpz_t(), p.numerator.get_mpz_t(), f);
    if (power > 0) p.factors[kept++] = {id, power};
  }
  p.factors.resize(kept);
  p.denominator = product(d, p.factors);
  mpz_mul_2exp(p.denominator.get_mpz_t(), p.denominator.get_mpz_t(), p.twos);
  return p;
}

// a + b over the least product of the vertices' denominators that both divide.
Partial add(const VertexDenominators& d, Partial a, Partial b) {
  if (a.numerator == 0) return b;
  if (b.numerator == 0) return a;
  Partial sum;
  Factors raise_a, raise_b;  // what each lacks
  std::size_t i = 0, j = 0;
  while (i < a.factors.size() || j < b.factors.size()) {
    const std::uint32_t id = std::min(i < a.factors.size() ? a.factors[i].first : kNoFactor,
                                      j < b.factors.size() ? b.factors[j].first : kNoFactor);
    const std::uint32_t in_a =
        i < a.factors.size() && a.factors[i].first == id ? a.factors[i++].second : 0;
    const std::uint32_t in_b =
        j < b.factors.size() && b.factors[j].first == id ? b.factors[j++].second : 0;
    const std::uint32_t count = std::max(in_a, in_b);
    sum.factors.push_back({id, count});
    if (count > in_a) raise_a.push_back({id, count - in_a});
    if (count > in_b) raise_b.push_back({id, count - in_b});
  }
  sum.twos = std::max(a.twos, b.twos);
  const mpz_class to_a = product(d, raise_a), to_b = product(d, raise_b);
  a.numerator *= to_a;
  b.numerator *= to_b;
  mpz_mul_2exp(a.numerator.get_mpz_t(), a.numerator.get_mpz_t(), sum.twos - a.twos);
  mpz_mul_2exp(b.numerator.get_mpz_t(), b.numerator.get_mpz_t(), sum.twos - b.twos);
  sum.numerator = a.numerator + b.numerator;
  sum.denominator = a.denominator * to_a;
  mpz_mul_2exp(sum.denominator.get_mpz_t(), sum.denominator.get_mpz_t(), sum.twos - a.twos);
  return sum;
}

}  // namespace

mpq_class factored_volume_times_6(const Mesh& mesh) {
  if (mesh.triangles.empty()) return 0;
  const VertexDenominators d = vertex_denominators(mesh);
  std::vector<Partial> level(mesh.triangles.size());
  tbb::parallel_for(std::size_t(0), level.size(),
                    [&](std::size_t f) { level[f] = face_term(mesh, d, std::uint32_t(f)); });
  // Neighbours in the mesh's order first: consecutive faces mostly share vertices, so their
  // denominators have factors in common and the partial sums stay small.
  while (level.size() > 1) {
    std::vector<Partial> up((level.size() + 1) / 2);
    tbb::parallel_for(std::size_t(0), level.size() / 2, [&](std::size_t i) {
      up[i] = add(d, std::move(level[2 * i]), std::move(level[2 * i + 1]));
    });
    if (level.size() % 2 == 1) up.back() = std::move(level.back());
    level = std::move(up);
  }
  mpq_class six(level[0].numerator, level[0].denominator);
  six.canonicalize();
  return six;
}

}  // namespace morphex::detail
