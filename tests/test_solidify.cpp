// SPDX-License-Identifier: GPL-3.0-or-later
// solidify (morphex/solidify.h, issue 43): each kind of damage real collections hold, on small
// generated meshes, gives a valid solid close to (or exactly) the undamaged one; valid solids
// come back unchanged.
#include <gtest/gtest.h>

#include <random>

#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/shapes.h"
#include "morphex/solidify.h"

using namespace morphex;

namespace {

const Mesh& sphere() {
  static const Mesh m = make_icosphere(3, FT(1));  // 1280 faces
  return m;
}

// The solidified mesh: a valid solid, and its exact volume.
FT solid_volume(const Mesh& damaged, SolidifyReport* report = nullptr) {
  const SolidifyResult r = solidify(damaged);
  const MeshReport check = check_mesh(r.solid);
  EXPECT_TRUE(check.valid_solid()) << describe_problems(check) << " (" << describe(r.report) << ")";
  if (report) *report = r.report;
  return check.volume;
}

double ratio(const FT& a, const FT& b) {
  return CGAL::to_double(a / b);
}

// Every face with its own three vertices, as STL stores a mesh.
Mesh unwelded(const Mesh& m) {
  Mesh out;
  for (const Triangle& t : m.triangles) {
    const VertexIndex v = VertexIndex(out.points.size());
    for (const VertexIndex c : t) out.points.push_back(m.points[c]);
    out.triangles.push_back({v, v + 1, v + 2});
  }
  return out;
}

}  // namespace

TEST(Solidify, ValidSolidsAreUnchanged) {
  const SolidifyResult r = solidify(sphere());
  EXPECT_FALSE(r.report.changed);
  EXPECT_EQ(describe(r.report), "unchanged");
  EXPECT_EQ(r.solid.mesh().points, sphere().points);
  EXPECT_EQ(r.solid.mesh().triangles, sphere().triangles);
}

TEST(Solidify, FlippedFacesAreTurnedBack) {
  Mesh m = sphere();
  std::mt19937 random(1);
  for (Triangle& t : m.triangles)
    if (random() % 10 == 0) std::swap(t[1], t[2]);
  SolidifyReport report;
  EXPECT_EQ(solid_volume(m, &report), signed_volume(sphere()));  // exactly: no point moved
  EXPECT_EQ(report.method, "soup");
}

TEST(Solidify, InwardMeshesAreTurned) {
  EXPECT_EQ(solid_volume(reversed(sphere())), signed_volume(sphere()));
}

TEST(Solidify, SoupsAndDuplicatedFacesGiveTheSameSolid) {
  EXPECT_EQ(solid_volume(unwelded(sphere())), signed_volume(sphere()));
  Mesh doubled = sphere();
  for (std::size_t f = 0; f < sphere().num_triangles(); f += 7)
    doubled.triangles.push_back(sphere().triangles[f]);
  EXPECT_EQ(solid_volume(doubled), signed_volume(sphere()));
}

TEST(Solidify, HolesAreFilled) {
  Mesh m = sphere();
  // Two patches: the faces around two opposite vertices.
  std::vector<Triangle> kept;
  for (const Triangle& t : m.triangles) {
    const bool around = std::find(t.begin(), t.end(), VertexIndex(0)) != t.end() ||
                        std::find(t.begin(), t.end(), VertexIndex(5)) != t.end();
    if (!around) kept.push_back(t);
  }
  ASSERT_LT(kept.size(), m.triangles.size());
  m.triangles = kept;
  SolidifyReport report;
  EXPECT_NEAR(ratio(solid_volume(m, &report), signed_volume(sphere())), 1.0, 0.01);
  EXPECT_EQ(report.filled_holes, 2u);
}

TEST(Solidify, CracksAreWelded) {
  // The soup with every vertex of the upper half moved by 1e-7 of the diagonal: the two halves
  // no longer share their vertices along the equator.
  Mesh m = unwelded(sphere());
  const FT shift = FT(1) / FT(1e7);
  for (const Triangle& t : m.triangles)
    if (m.points[t[0]].z() + m.points[t[1]].z() + m.points[t[2]].z() > 0)
      for (const VertexIndex v : t)
        m.points[v] = Point(m.points[v].x() + shift, m.points[v].y(), m.points[v].z());
  SolidifyReport report;
  EXPECT_NEAR(ratio(solid_volume(m, &report), signed_volume(sphere())), 1.0, 1e-5);
  EXPECT_GT(report.welded_vertices, 0u);
}

TEST(Solidify, OverlappingPartsAreUnited) {
  const Mesh box =
      make_box(Point(FT(1) / 2, FT(-1) / 8, FT(-1) / 8), Point(2, FT(1) / 8, FT(1) / 8));
  const FT united = signed_volume(
      compute_boolean(check_solid(sphere()), check_solid(box), BooleanOp::Union).solid);
  EXPECT_EQ(solid_volume(concatenate(sphere(), box)), united);
  // The box turned inward as well, and the sphere's faces unwelded: the same union.
  SolidifyReport report;
  EXPECT_EQ(solid_volume(concatenate(unwelded(sphere()), reversed(box)), &report), united)
      << describe(report);
}

TEST(Solidify, SheetsBoundNoVolume) {
  const Mesh square = [] {
    Mesh m;
    m.points = {Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0), Point(0, 1, 0)};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    return m;
  }();
  try {
    solidify(square);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bounds no"), std::string::npos) << e.what();
  }
}

TEST(Solidify, AllDamageTogether) {
  Mesh m = unwelded(sphere());
  std::mt19937 random(7);
  std::vector<Triangle> kept;
  for (std::size_t f = 0; f < m.triangles.size(); ++f) {
    Triangle t = m.triangles[f];
    if (random() % 10 == 0) std::swap(t[1], t[2]);
    kept.push_back(t);
    if (f % 11 == 0) kept.push_back(t);  // duplicated
  }
  m.triangles = kept;
  const Mesh box =
      make_box(Point(FT(1) / 2, FT(-1) / 8, FT(-1) / 8), Point(2, FT(1) / 8, FT(1) / 8));
  const FT united = signed_volume(
      compute_boolean(check_solid(sphere()), check_solid(box), BooleanOp::Union).solid);
  EXPECT_EQ(solid_volume(concatenate(m, box)), united);
}
