// SPDX-License-Identifier: GPL-3.0-or-later
#include "morphex/collection.h"

#include <map>
#include <random>
#include <sstream>
#include <stdexcept>

#include "morphex/boolean.h"
#include "morphex/shapes.h"

namespace morphex {
namespace {

class Shapes {
 public:
  explicit Shapes(std::uint64_t seed) : rng_(seed) {}

  // A rational in [lo, hi] on a grid of 1/20, so proportions vary but stay exact.
  FT between(double lo, double hi) {
    std::uniform_int_distribution<int> pick(int(lo * 20), int(hi * 20));
    return FT(pick(rng_)) / 20;
  }

  Solid box(const FT& x0, const FT& y0, const FT& z0, const FT& x1, const FT& y1, const FT& z1) {
    return check_solid(make_box(Point(x0, y0, z0), Point(x1, y1, z1)));
  }

  Mesh unite(const std::vector<Solid>& parts) {
    Solid out = parts.front();
    for (std::size_t i = 1; i < parts.size(); ++i)
      out = compute_boolean(out, parts[i], BooleanOp::Union).solid;
    return out.mesh();
  }

  Mesh family(const std::string& name) {
    const FT t = between(0.3, 0.5);  // thickness
    if (name == "bar") return box(0, 0, 0, between(2.5, 3.5), between(0.4, 0.7), between(0.4, 0.7));
    if (name == "ell") {
      const FT a = between(1.5, 2.5), b = between(1.5, 2.5);
      return unite({box(0, 0, 0, a, t, t), box(0, 0, 0, t, b, t)});
    }
    if (name == "tee") {
      const FT a = between(2, 3), b = between(1.5, 2.5);
      return unite({box(-a / 2, b - t, 0, a / 2, b, t), box(-t / 2, 0, 0, t / 2, b, t)});
    }
    if (name == "plus") {
      const FT a = between(1, 1.5), b = between(1, 1.5);
      return unite({box(-a, -t / 2, 0, a, t / 2, t), box(-t / 2, -b, 0, t / 2, b, t)});
    }
    if (name == "frame") {
      const FT a = between(1.2, 2), b = between(1.2, 2);
      const BooleanResult r = compute_boolean(box(0, 0, 0, a, b, t), box(t, t, -1, a - t, b - t, 1),
                                              BooleanOp::Difference);
      return r.solid.mesh();
    }
    if (name == "steps") {
      const FT w = between(0.6, 1), d = between(0.4, 0.6);
      return unite({box(0, 0, 0, w, 3 * d, d), box(0, d, d, w, 3 * d, 2 * d),
                    box(0, 2 * d, 2 * d, w, 3 * d, 3 * d)});
    }
    throw InputError("", "unknown shape family '" + name + "'");
  }

  // A random rotation, exactly orthogonal (a rational quaternion), a scale and a shift.
  Mesh posed(const Mesh& m) {
    std::uniform_int_distribution<int> q(-16, 16);
    FT a, b, c, d, n;
    do {
      a = q(rng_), b = q(rng_), c = q(rng_), d = q(rng_);
      n = a * a + b * b + c * c + d * d;
    } while (n == 0);
    const Transformation rotation = quaternion_rotation(a, b, c, d);
    const FT s = between(0.5, 2);
    Mesh out = transformed(m, Transformation(CGAL::SCALING, s) * rotation);
    out = translated(out, Vector(between(-5, 5), between(-5, 5), between(-5, 5)));
    make_exact(out);
    return out;
  }

 private:
  std::mt19937_64 rng_;
};

}  // namespace

std::vector<std::string> collection_families() {
  return {"bar", "ell", "tee", "plus", "frame", "steps"};
}

std::vector<LabelledMesh> make_collection(int per_family, std::uint64_t seed,
                                          const std::vector<std::string>& families) {
  Shapes shapes(seed);
  std::vector<LabelledMesh> out;
  for (const std::string& family : families.empty() ? collection_families() : families)
    for (int k = 0; k < per_family; ++k)
      out.push_back(
          {family + "-" + std::to_string(k), family, shapes.posed(shapes.family(family))});
  return out;
}

std::string to_cla(const std::vector<LabelledMesh>& meshes) {
  std::map<std::string, std::vector<std::string>> by_label;
  for (const LabelledMesh& m : meshes) by_label[m.label].push_back(m.name);
  std::ostringstream out;
  out << "PSB 1\n" << by_label.size() << ' ' << meshes.size() << "\n";
  for (const auto& [label, names] : by_label) {
    out << "\n" << label << " 0 " << names.size() << "\n";
    for (const std::string& n : names) out << n << "\n";
  }
  return out.str();
}

}  // namespace morphex
