// SPDX-License-Identifier: GPL-3.0-or-later
// stress [--seed S] [--count N] [--out DIR]: randomized exact Booleans and morphology.
// Random solids (boxes on a 1/4 grid, cubes, tetrahedra, octahedra, icospheres, L-shapes, cube
// pairs sharing only an edge or a vertex, whose contact is separated, and the results of earlier
// cases, as morphology chains them) under random rational rigid motions, chosen so that coplanar
// faces, shared edges and vertices and nesting are frequent. Every result must be a valid solid and
// satisfy the exact identities
//   vol(A u B) + vol(A n B) = vol(A) + vol(B),   vol(A - B) = vol(A) - vol(A n B);
// the two written as one mesh must give the same solids through repair and winding_solid (its
// union; {w >= 2}, the intersection; with B reversed, the difference); every 20th case also checks
// that an opening is inside A and a closing contains it (by a cube, an octahedron or a ball), and
// every 40th, halfway between, the same by a zonoball. A
// failing case is written to DIR as exact OFF files with a line saying how to replay it; exit
// code 1.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "bench_harness.h"
#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/internal/huge_pages.h"
#include "morphex/internal/stopwatch.h"
#include "morphex/io.h"
#include "morphex/morphology.h"
#include "morphex/repair.h"
#include "morphex/shapes.h"
#include "morphex/solid.h"
#include "morphex/structuring_element.h"
#include "morphex/winding.h"

using namespace morphex;

namespace {

class RandomSolids {
 public:
  explicit RandomSolids(std::uint64_t seed) : rng_(seed) {}

  int pick(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  FT grid(int lo, int hi) { return FT(pick(lo, hi)) / 4; }  // quarters: contacts are frequent

  // A solid of the cases so far, or a new shape. Results (of Booleans, openings and closings)
  // are what morphology feeds to the next Boolean (separated non-manifold features, coincident
  // vertices, merged coplanar regions), so a quarter of the operands are earlier results, moved
  // again.
  Mesh operand() {
    if (!results_.empty() && pick(0, 3) == 0)
      return results_[std::size_t(pick(0, int(results_.size()) - 1))];
    return shape();
  }

  // Keeps a result as a later operand: small ones only (chains stay fast), the last kKept.
  void remember(const Mesh& result) {
    constexpr std::size_t kKept = 64, kMaxTriangles = 1500;
    if (result.empty() || result.num_triangles() > kMaxTriangles) return;
    if (results_.size() < kKept)
      results_.push_back(result);
    else
      results_[next_++ % kKept] = result;
  }

  Mesh shape() {
    switch (pick(0, 7)) {
      case 0: {
        const FT x = grid(-4, 0), y = grid(-4, 0), z = grid(-4, 0);
        return make_box(Point(x, y, z), Point(x + grid(1, 8), y + grid(1, 8), z + grid(1, 8)));
      }
      case 1:
        return make_cube(grid(1, 4));
      case 2:
        return transformed(make_tetrahedron(), Transformation(CGAL::SCALING, grid(2, 8)));
      case 3:
        return make_octahedron(grid(1, 6));
      case 4:
        return make_icosphere(1, FT(1));
      case 5:
        return compute_boolean(check_solid(make_box(Point(0, 0, 0), Point(2, 1, 1))),
                               check_solid(make_box(Point(0, 0, 0), Point(1, 2, 1))),
                               BooleanOp::Union)
            .solid.mesh();
      default: {
        // Two cubes sharing only an edge or only a vertex: a solid whose non-manifold feature is
        // separated into coincident vertices (and edges).
        const FT s = grid(2, 4), z = pick(6, 7) == 6 ? FT(0) : s;
        return compute_boolean(check_solid(make_box(Point(0, 0, 0), Point(s, s, s))),
                               check_solid(make_box(Point(s, s, z), Point(2 * s, 2 * s, z + s))),
                               BooleanOp::Union)
            .solid.mesh();
      }
    }
  }

  // Half of the motions keep the axes (faces stay coplanar or touching on the grid); the others
  // rotate by a small rational quaternion, sometimes a quarter turn.
  Mesh moved(const Mesh& m) {
    Mesh out = m;
    const int kind = pick(0, 3);
    if (kind == 1) out = transformed(out, quaternion_rotation(1, 0, 0, 1));  // 90 degrees about z
    if (kind >= 2)
      out =
          transformed(out, quaternion_rotation(pick(-3, 3), pick(-3, 3), pick(-3, 3), pick(1, 3)));
    out = translated(out, Vector(grid(-4, 4), grid(-4, 4), grid(-4, 4)));
    make_exact(out);
    return out;
  }

 private:
  std::mt19937_64 rng_;
  std::vector<Mesh> results_;
  std::size_t next_ = 0;
};

std::string problem_with(const Mesh& m) {
  const MeshReport r = check_mesh(m);
  return r.valid_solid() ? "" : describe_problems(r);
}

}  // namespace

int main(int argc, char** argv) {
  morphex::use_huge_page_malloc(argv);  // first: it may restart the process
  bench::Harness harness(
      "stress: randomized exact Booleans and morphology, checked by exact "
      "volume identities");
  CLI::App& app = harness.app();
  std::uint64_t seed = 1;
  long count = 1000;
  std::string out_dir = "stress-failures";
  app.add_option("--seed", seed, "Seed of the random cases")->capture_default_str();
  app.add_option("--count", count, "Number of cases")->capture_default_str();
  app.add_option("--out", out_dir, "Where failing cases are written (exact OFF)")
      ->capture_default_str();
  if (const std::optional<int> stop = harness.parse(argc, argv)) return *stop;
  const Stopwatch start;
  RandomSolids random(seed);
  long failures = 0;
  for (long c = 0; c < count; ++c) {
    const Mesh am = random.moved(random.operand()), bm = random.moved(random.operand());
    std::string failure;
    Solid a, b;
    try {
      std::tie(a, b) = check_solids(am, "A", bm, "B");
    } catch (const InvalidSolid& e) {
      failure = std::string("an operand is not a valid solid: ") + e.what();
    }
    BooleanResult r[3];
    const BooleanOp ops[3] = {BooleanOp::Union, BooleanOp::Intersection, BooleanOp::Difference};
    for (int k = 0; k < 3 && failure.empty(); ++k) {
      r[k] = compute_boolean(a, b, ops[k]);
      if (const std::string p = problem_with(r[k].solid); !p.empty())
        failure = std::string(to_string(ops[k])) + " is not a valid solid: " + p;
    }
    if (failure.empty()) {
      const FT va = signed_volume(a), vb = signed_volume(b), vu = signed_volume(r[0].solid),
               vi = signed_volume(r[1].solid), vd = signed_volume(r[2].solid);
      if (vu + vi != va + vb)
        failure = "vol(A u B) + vol(A n B) != vol(A) + vol(B)";
      else if (vd != va - vi)
        failure = "vol(A - B) != vol(A) - vol(A n B)";
      for (const BooleanResult& result : r) random.remember(result.solid.mesh());
    }
    if (failure.empty()) {
      // The two solids written as one mesh: its repair is their union, and its winding regions
      // give the intersection (covered twice) and, with B reversed, the difference.
      try {
        const Mesh both = concatenate(a, b);
        WindingOptions twice;
        twice.threshold = 2;
        const RepairResult joined = repair_mesh(both);
        const Mesh common = winding_solid(both, {}, twice);
        const Mesh minus = winding_solid(concatenate(a, reversed(b)));
        if (const std::string p =
                problem_with(joined.solid) + problem_with(common) + problem_with(minus);
            !p.empty())
          failure = "a winding solid of A and B as one mesh is not a valid solid: " + p;
        else if (signed_volume(joined.solid) != signed_volume(r[0].solid))
          failure = "repair of A and B as one mesh != A u B";
        else if (signed_volume(common) != signed_volume(r[1].solid))
          failure = "{w >= 2} of A and B as one mesh != A n B";
        else if (signed_volume(minus) != signed_volume(r[2].solid))
          failure = "{w >= 1} of A and reversed B != A - B";
      } catch (const std::exception& e) {
        failure = std::string("repair of A and B as one mesh failed: ") + e.what();
      }
    }
    if (failure.empty() && (c % 20 == 0 || c % 40 == 10)) {
      // Cubes (segment sweeps), octahedra and balls (convolution pieces, their arrangement or
      // the union tree) in turn; between them, zonoballs (seven segment sweeps, not along axes).
      static const char* const kElements[3] = {"cube:r=1/8", "octahedron:r=1/8",
                                               "ball:r=1/8,level=0"};
      const StructuringElement se = parse_structuring_element(
          c % 20 == 0 ? kElements[(c / 20) % 3] : "zonoball:r=1/8,level=0");
      const Solid opened = opening(a, se), closed = closing(a, se);
      const BooleanResult outside = compute_boolean(opened, a, BooleanOp::Difference);
      const BooleanResult missing = compute_boolean(a, closed, BooleanOp::Difference);
      if (const std::string p = problem_with(opened) + problem_with(closed); !p.empty())
        failure = "opening or closing is not a valid solid: " + p;
      else if (signed_volume(outside.solid) != 0 || signed_volume(missing.solid) != 0)
        failure = "opening not inside A or closing not containing A";
      else
        for (const Solid* result : {&opened, &closed}) random.remember(result->mesh());
    }
    if (!failure.empty()) {
      ++failures;
      std::filesystem::create_directories(out_dir);
      const std::string stem = out_dir + "/case-" + std::to_string(seed) + "-" + std::to_string(c);
      WriteOptions exact;
      exact.exact = true;
      write_mesh(am, stem + "-a.off", exact);
      write_mesh(bm, stem + "-b.off", exact);
      std::ofstream(stem + ".txt")
          << failure << "\nreplay: morphex bool union|intersection|"
          << "difference " << stem << "-a.off " << stem << "-b.off -o r.off\n";
      std::cerr << "case " << c << " (seed " << seed << "): " << failure << " -> " << stem
                << "-*\n";
    }
  }
  const double seconds = start.seconds();
  std::cout << count << " cases (seed " << seed << "), " << failures << " failed, " << seconds
            << " s\n";
  return failures == 0 ? 0 : 1;
}
