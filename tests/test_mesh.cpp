// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <gmpxx.h>

#include "morphex/boolean.h"
#include "morphex/internal/parallel_points.h"
#include "morphex/internal/union_find.h"
#include "morphex/mesh.h"
#include "morphex/shapes.h"
#include "morphex/solid.h"

using namespace morphex;

TEST(Rational, PrintsLowestTerms) {
  EXPECT_EQ(to_rational_string(FT(6) / FT(16)), "3/8");
  EXPECT_EQ(to_rational_string(FT(27)), "27");
  EXPECT_EQ(to_rational_string(FT(-1) / FT(3)), "-1/3");
  EXPECT_EQ(to_rational_string(FT(0.1)), "3602879701896397/36028797018963968");
}

// Doubles are written from their bits (machine integers where they fit), other numbers by GMP:
// both must print what GMP prints for the exact value, and read back as it.
TEST(Rational, PrintsEveryDoubleAsGmpDoes) {
  std::mt19937_64 random(7);
  std::vector<double> values = {0.0,
                                -0.0,
                                1.0,
                                -1.0,
                                0.5,
                                3.0,
                                1024.0,
                                2047.0,
                                1e15,
                                0.1,
                                -0.75,
                                1e-300,
                                4.9e-324,
                                1e308,
                                -2.5e-3,
                                9007199254740992.0,
                                9007199254740991.0,
                                0x1p-63,
                                0x1p-64,
                                0x1p62};
  for (int i = 0; i < 2000; ++i) {
    const double mantissa = std::ldexp(double(random() >> 11), -53) * (i % 2 ? -1 : 1);
    values.push_back(std::ldexp(mantissa, int(random() % 2098) - 1074));
  }
  for (const double d : values) {
    const std::string text = to_rational_string(FT(d));
    EXPECT_EQ(text, mpq_class(d).get_str()) << d;
    EXPECT_EQ(parse_exact_number(text), FT(d)) << text;
  }
  const FT third = FT(1) / 3 + FT(0.1);  // a lazy number that is no double
  mpq_class expected = mpq_class(1, 3) + mpq_class(0.1);
  expected.canonicalize();
  EXPECT_EQ(to_rational_string(third), expected.get_str());
  EXPECT_EQ(to_rational_string(-third * 6), mpq_class(-expected * 6).get_str());
}

TEST(Rational, ParsesRationalsAndDecimals) {
  EXPECT_EQ(parse_exact_number("6/16"), FT(3) / FT(8));
  EXPECT_EQ(parse_exact_number("-7"), FT(-7));
  EXPECT_EQ(parse_exact_number("0.1"), FT(0.1));
  EXPECT_EQ(parse_exact_number("1e2"), FT(100));
  EXPECT_EQ(parse_exact_number("123456789012345678901234567890/3"),
            FT(CGAL::exact(parse_exact_number("41152263004115226300411522630"))));
  EXPECT_THROW(parse_exact_number("1/0"), InputError);
  EXPECT_THROW(parse_exact_number("abc"), InputError);
  EXPECT_THROW(parse_exact_number("nan"), InputError);
  EXPECT_THROW(parse_exact_number("inf"), InputError);
  EXPECT_THROW(parse_exact_number(""), InputError);
}

namespace {
Mesh unit_cube() {
  Mesh m;
  for (int i = 0; i < 8; ++i) m.points.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}
}  // namespace

TEST(Volume, UnitCubeIsExactlyOne) {
  EXPECT_EQ(signed_volume(unit_cube()), FT(1));
}

TEST(Volume, ScaledByAThirdIsExact) {
  Mesh m = unit_cube();
  for (Point& p : m.points) p = Point(p.x() / 3, p.y() / 3, p.z() / 3);
  EXPECT_EQ(to_rational_string(signed_volume(m)), "1/27");
  make_exact(m);
  EXPECT_EQ(to_rational_string(signed_volume(m)), "1/27");
}

TEST(Volume, ReversedOrientationIsNegative) {
  Mesh m = unit_cube();
  for (Triangle& t : m.triangles) std::swap(t[1], t[2]);
  EXPECT_EQ(signed_volume(m), FT(-1));
}

namespace {
// The volume by the definition, in exact rationals: an independent computation for the tests.
FT volume_by_rationals(const Mesh& m) {
  FT six = 0;
  for (const Triangle& t : m.triangles) {
    const Point &a = m.points[t[0]], &b = m.points[t[1]], &c = m.points[t[2]];
    six += CGAL::determinant(a.x(), a.y(), a.z(), b.x(), b.y(), b.z(), c.x(), c.y(), c.z());
  }
  return six / 6;
}

// Random triangles (not a closed mesh: the sum is what is tested) over double coordinates with
// mantissas of every length and exponents spread over `spread` binary orders.
Mesh random_double_triangles(unsigned seed, int spread, std::size_t faces) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::uniform_int_distribution<int> exponent(-spread / 2, spread / 2);
  Mesh m;
  for (std::size_t i = 0; i < 3 * faces; ++i) {
    double c[3];
    for (double& x : c) x = random() % 7 == 0 ? 0.0 : std::ldexp(unit(random), exponent(random));
    m.points.emplace_back(c[0], c[1], c[2]);
  }
  for (VertexIndex i = 0; i < 3 * faces; i += 3) m.triangles.push_back({i, i + 1, i + 2});
  return m;
}
}  // namespace

// Double coordinates take the fixed-size integer sum (exponents up to 100 bits apart), others the
// rational one; both must equal the definition exactly, signs and tiny or huge scales included.
TEST(Volume, EqualsTheRationalSumForEveryScale) {
  for (int spread : {0, 10, 40, 90, 150}) {
    for (unsigned seed = 1; seed <= 4; ++seed) {
      const Mesh m = random_double_triangles(seed * 100 + unsigned(spread), spread, 2000);
      EXPECT_EQ(signed_volume(m), volume_by_rationals(m)) << "spread " << spread;
    }
  }
  Mesh extreme = random_double_triangles(7, 0, 10);
  extreme.points[0] = Point(std::ldexp(1.0, 99), 0.75, -1);  // 2^99 and 2^-2: 101 bits apart
  extreme.points[1] = Point(std::ldexp(-1.0, 1000), std::ldexp(1.0, -1070), 3);
  EXPECT_EQ(signed_volume(extreme), volume_by_rationals(extreme));
  Mesh thirds = random_double_triangles(8, 20, 50);  // constructed (non-double) coordinates
  for (Point& p : thirds.points) p = Point(p.x() / 3, p.y(), p.z() * 5 / 7);
  EXPECT_EQ(signed_volume(thirds), volume_by_rationals(thirds));
  EXPECT_EQ(signed_volume(Mesh{}), FT(0));
}

// Rational coordinates over a few shared denominators (thirds and sevenths, a rational rotation,
// scales down to 2^-600) take the sum over their common denominator; coordinates over
// denominators with nothing in common (distinct primes: the common one passes 4096 bits) the
// sum of rationals. Both must equal the definition exactly.
TEST(Volume, RationalCoordinatesEqualTheDefinition) {
  const Transformation turn(FT(3) / 5, FT(-4) / 5, 0, FT(4) / 5, FT(3) / 5, 0, 0, 0, 1);
  const Transformation tilt(1, 0, 0, 0, FT(5) / 13, FT(-12) / 13, 0, FT(12) / 13, FT(5) / 13);
  for (int scale : {0, -40, -600}) {
    Mesh m = random_double_triangles(unsigned(11 - scale), 30, 300);
    for (Point& p : m.points)
      p = tilt(turn(Point(p.x() * std::ldexp(1.0, scale) / 3, p.y() * 5 / 7, p.z())));
    EXPECT_EQ(signed_volume(m), volume_by_rationals(m)) << "scale 2^" << scale;
  }
  Mesh primes = random_double_triangles(12, 10, 200);
  int next = 1000003;
  auto prime_after = [](int n) {
    for (;; ++n) {
      bool prime = n > 1;
      for (int d = 2; d * d <= n && prime; ++d) prime = n % d != 0;
      if (prime) return n;
    }
  };
  for (Point& p : primes.points) {
    FT c[3];
    for (int k = 0; k < 3; ++k) {
      next = prime_after(next + 1);
      c[k] = p[k] / next;
    }
    p = Point(c[0], c[1], c[2]);
  }
  EXPECT_EQ(signed_volume(primes), volume_by_rationals(primes));
}

// Coordinates over many denominators (a Boolean's or a morphology's result: each new vertex over
// the determinant of three planes' normals) take the sum whose partial denominators are products
// of known factors (the power of two, the small odd primes, the distinct rest), reduced once at the
// end. Denominators that share small primes, larger factors and powers of two, corners over one
// denominator, integer corners and faces without area must all give the definition exactly.
TEST(Volume, ManyDenominatorsWithCommonFactorsEqualTheDefinition) {
  std::mt19937_64 random(47);
  auto pick = [&](std::size_t n) { return std::size_t(random() % n); };
  // Large factors from a pool of 500 primes of about 20 bits (their product passes the common
  // denominator's 4096 bits), used alone, twice over, or two together (rests that share one).
  std::vector<int> large;
  for (int n = 1000003; large.size() < 500; n += 2) {
    bool prime = true;
    for (int d = 3; d * d <= n && prime; d += 2) prime = n % d != 0;
    if (prime) large.push_back(n);
  }
  const std::vector<int> small = {3, 5, 7, 9, 25, 27, 61, 127};
  auto denominator = [&] {
    FT d = FT(1) / FT(1L << pick(40));  // a power of two, as a double's coordinates have
    for (std::size_t k = pick(4); k > 0; --k) d *= FT(small[pick(small.size())]);
    for (std::size_t k = pick(3); k > 0; --k) d *= FT(large[pick(large.size())]);
    return d;
  };
  for (unsigned seed = 1; seed <= 3; ++seed) {
    Mesh m = random_double_triangles(seed + 40, 20, 600);
    for (Point& p : m.points) {
      switch (pick(4)) {
        case 0:  // integer coordinates (the denominator 1)
          p = Point(std::round(CGAL::to_double(p.x()) * 64),
                    std::round(CGAL::to_double(p.y()) * 64), 7);
          break;
        case 1: {  // one denominator for all three
          const FT d = denominator();
          p = Point(p.x() / d, p.y() / d, p.z() / d);
          break;
        }
        default:
          p = Point(p.x() / denominator(), p.y() / denominator(), p.z() / denominator());
      }
    }
    // Faces whose corners are shared with other faces, over one denominator, and without area.
    const VertexIndex n = VertexIndex(m.points.size());
    for (VertexIndex i = 0; i + 5 < n; i += 7) m.triangles.push_back({i, i + 3, i + 5});
    m.triangles.push_back({0, 0, 1});
    m.triangles.push_back({1, 2, 1});
    EXPECT_EQ(signed_volume(m), volume_by_rationals(m)) << "seed " << seed;
    EXPECT_EQ(signed_volume(reversed(m)), -volume_by_rationals(m)) << "seed " << seed;
  }
}

// A Boolean's result has a denominator per crossing of two faces: the union and intersection of
// a sphere with a turned, moved copy pass the common denominator's bound, and their volumes keep
// the exact identity vol(A u B) + vol(A n B) = vol(A) + vol(B) and equal the definition.
TEST(Volume, ABooleansResultOverManyDenominatorsIsExact) {
  const Solid a = check_solid(make_icosphere(2, FT(1)));
  const Solid b = check_solid(translated(transformed(a, quaternion_rotation(1, 2, 3, 4)),
                                         Vector(FT(1) / 3, FT(2) / 7, FT(1) / 11)));
  const Solid joined = compute_boolean(a, b, BooleanOp::Union).solid;
  const Solid common = compute_boolean(a, b, BooleanOp::Intersection).solid;
  EXPECT_EQ(signed_volume(joined), volume_by_rationals(joined));
  EXPECT_EQ(signed_volume(common), volume_by_rationals(common));
  EXPECT_EQ(signed_volume(joined) + signed_volume(common), signed_volume(a) + signed_volume(b));
}

// Rational coordinates over their common denominator are summed in fixed-size integers of three
// widths, chosen by the largest numerator times its quotient, and in GMP's past them: numerators
// of one bit below, at and above each width's limit (100, 160 and 250 bits), of both signs, over
// denominators 3 and 9 (quotients 3 and 1), give the rational sum every time.
TEST(Volume, RationalCoordinatesAtEveryIntegerWidth) {
  gmp_randclass random(gmp_randinit_default);
  random.seed(2026);
  for (const int limit : {100, 160, 250}) {
    for (const int bits : {limit - 3, limit - 2, limit - 1, limit, limit + 1}) {
      Mesh m = random_double_triangles(unsigned(bits), 0, 40);
      int k = 0;
      for (Point& p : m.points) {
        mpq_class c[3];
        for (mpq_class& x : c) {
          mpz_class n = random.get_z_bits(bits);
          mpz_setbit(n.get_mpz_t(), bits - 1);  // exactly `bits` bits
          if (++k % 3 == 0) n = -n;
          x = mpq_class(n, k % 2 == 0 ? 3 : 9);
          x.canonicalize();
        }
        p = Point(FT(c[0]), FT(c[1]), FT(c[2]));
      }
      EXPECT_EQ(signed_volume(m), volume_by_rationals(m)) << bits << " bits";
    }
  }
}

// The sign of the volume (the outward test) is decided by doubles when the rounding errors
// cannot flip it, and exactly otherwise: large terms that cancel exactly, or up to a tiny rest,
// at scales down to the subnormal range.
TEST(Volume, SignAgreesWithTheExactSum) {
  for (int spread : {0, 40, 150}) {
    for (unsigned seed = 1; seed <= 3; ++seed) {
      const Mesh m = random_double_triangles(seed * 10 + unsigned(spread), spread, 500);
      EXPECT_EQ(signed_volume_sign(m), CGAL::sign(volume_by_rationals(m))) << "spread " << spread;
    }
  }
  for (const double scale : {1.0, 0x1p-340, 0x1p-500, 0x1p300}) {
    for (const double rest : {0.0, 0x1p-60, -0x1p-60}) {
      // Big triangles and their reverses cancel exactly; one small triangle is what remains.
      Mesh m = random_double_triangles(99, 20, 200);
      const std::size_t n = m.triangles.size();
      for (std::size_t i = 0; i < n; ++i)
        m.triangles.push_back({m.triangles[i][0], m.triangles[i][2], m.triangles[i][1]});
      const VertexIndex o = VertexIndex(m.points.size());
      m.points.insert(m.points.end(), {Point(1, 0, 0), Point(0, 1, 0), Point(0, 0, rest)});
      m.triangles.push_back({o, o + 1, o + 2});
      for (Point& p : m.points) p = Point(p.x() * scale, p.y() * scale, p.z() * scale);
      const CGAL::Sign expected = CGAL::sign(volume_by_rationals(m));
      EXPECT_EQ(expected, CGAL::sign(rest)) << "scale " << scale << " rest " << rest;
      EXPECT_EQ(signed_volume_sign(m), expected) << "scale " << scale << " rest " << rest;
    }
  }
}

TEST(DoubleMesh, RoundTripIsLosslessForDoubles) {
  Mesh m = unit_cube();
  m.points[0] = Point(0.1, -2.5e-7, 3.0);
  Mesh back = from_double(to_double(m));
  ASSERT_EQ(back.points.size(), m.points.size());
  for (std::size_t i = 0; i < m.points.size(); ++i) EXPECT_EQ(back.points[i], m.points[i]);
  EXPECT_EQ(back.triangles, m.triangles);
}

// parallel_points keeps the order of make(i) across its blocks (n spans several blocks and a
// partial last one).
TEST(ParallelPoints, AreMadeInOrderAcrossBlocks) {
  for (const std::size_t n :
       {std::size_t(0), std::size_t(1), std::size_t(4096), std::size_t(4097), std::size_t(10000)}) {
    const std::vector<Point> points =
        parallel_points(n, [](std::size_t i) { return Point(FT(int(i)) / 3, int(i % 7), -1); });
    ASSERT_EQ(points.size(), n);
    for (std::size_t i = 0; i < n; ++i)
      ASSERT_EQ(points[i], Point(FT(int(i)) / 3, int(i % 7), -1)) << i;
  }
}

TEST(UnionFind, JoinsInAnyOrderGiveTheSetsOfThePairs) {
  std::mt19937 random(7);
  for (int round = 0; round < 20; ++round) {
    const std::uint32_t n = 200;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    for (int k = 0; k < 150; ++k) pairs.emplace_back(random() % n, random() % n);
    UnionFind sets(n);
    for (const auto& [a, b] : pairs) sets.join(a, b);
    // The same sets by repeated relabelling until nothing changes (no union-find).
    std::vector<std::uint32_t> label(n);
    for (std::uint32_t i = 0; i < n; ++i) label[i] = i;
    for (bool changed = true; changed;) {
      changed = false;
      for (const auto& [a, b] : pairs) {
        const std::uint32_t least = std::min(label[a], label[b]);
        for (std::uint32_t i = 0; i < n; ++i)
          if ((label[i] == label[a] || label[i] == label[b]) && label[i] != least) {
            label[i] = least;
            changed = true;
          }
      }
    }
    for (std::uint32_t i = 0; i < n; ++i)
      for (std::uint32_t j = 0; j < n; ++j)
        ASSERT_EQ(sets.find(i) == sets.find(j), label[i] == label[j]) << i << " " << j;
  }
}
