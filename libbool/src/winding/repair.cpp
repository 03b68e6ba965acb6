// SPDX-License-Identifier: GPL-3.0-or-later
// repair_mesh: merged vertices, repeated faces, the closed-chain test and the orientation, then
// winding_solid (morphex/repair.h).
#include "morphex/repair.h"
#include "morphex/internal/solid_access.h"
#include "morphex/progress.h"

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <iomanip>
#include <sstream>
#include <string>

#include "exact/point_index.h"
#include "morphex/check.h"
#include "morphex/internal/union_find.h"
#include "morphex/shapes.h"
#include "morphex/winding.h"

namespace morphex {
namespace {

// Faces joined through shared vertices.
std::size_t component_count(const Mesh& m) {
  UnionFind sets(m.points.size());
  for (const Triangle& t : m.triangles) {
    sets.join(t[0], t[1]);
    sets.join(t[0], t[2]);
  }
  std::vector<std::uint8_t> root(m.points.size(), 0);
  std::size_t count = 0;
  for (const Triangle& t : m.triangles) {
    const std::uint32_t r = sets.find(t[0]);
    count += root[r] == 0;
    root[r] = 1;
  }
  return count;
}

// The mesh over distinct positions, each face once when `once` (a face repeated with the same
// orientation is usually an error of the file, not a second shell: only the first is kept).
// `face_of` maps each input face to its face in the result (a repeated face to its first copy).
Mesh merged(const Mesh& mesh, bool once, RepairReport& r, std::vector<std::uint32_t>& face_of) {
  Mesh out;
  std::vector<VertexIndex> id(mesh.points.size());
  {
    detail::PointIndex index(out.points);
    index.reserve(mesh.points.size());
    for (std::size_t v = 0; v < mesh.points.size(); ++v) id[v] = index.id(mesh.points[v]);
  }
  r.merged_vertices = mesh.points.size() - out.points.size();
  std::vector<std::pair<Triangle, std::uint32_t>> keyed;  // (rotated to its least corner, face)
  keyed.reserve(mesh.triangles.size());
  for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f) {
    Triangle t = {id[mesh.triangles[f][0]], id[mesh.triangles[f][1]], id[mesh.triangles[f][2]]};
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    keyed.emplace_back(t, f);
  }
  tbb::parallel_sort(keyed.begin(), keyed.end());
  std::vector<std::uint32_t> first(mesh.triangles.size());  // the first copy of each face
  for (std::size_t i = 0; i < keyed.size(); ++i)
    first[keyed[i].second] = i > 0 && keyed[i].first == keyed[i - 1].first
                                 ? first[keyed[i - 1].second]
                                 : keyed[i].second;
  face_of.assign(mesh.triangles.size(), 0);
  for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f) {
    if (once && first[f] != f) {
      ++r.duplicate_faces;
      face_of[f] = face_of[first[f]];  // the least index of equal faces is the first copy
      continue;
    }
    face_of[f] = std::uint32_t(out.triangles.size());
    out.triangles.push_back(
        {id[mesh.triangles[f][0]], id[mesh.triangles[f][1]], id[mesh.triangles[f][2]]});
  }
  return out;
}

// Every edge run as often one way as the other (empty), or the error that names the first one
// that is not.
std::string open_chain(const Mesh& m) {
  struct Use {
    std::uint64_t edge;  // (min, max)
    std::uint32_t face;
    bool forward;  // min -> max
    bool operator<(const Use& o) const { return edge != o.edge ? edge < o.edge : face < o.face; }
  };
  std::vector<Use> uses;
  uses.reserve(3 * m.triangles.size());
  for (std::uint32_t f = 0; f < m.triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const VertexIndex a = m.triangles[f][k], b = m.triangles[f][(k + 1) % 3];
      if (a == b) continue;  // an edge of no length bounds nothing
      uses.push_back({(std::uint64_t(std::min(a, b)) << 32) | std::max(a, b), f, a < b});
    }
  tbb::parallel_sort(uses.begin(), uses.end());
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    int net = 0;
    bool one_way = true;
    for (; j < uses.size() && uses[j].edge == uses[i].edge; ++j) {
      net += uses[j].forward ? 1 : -1;
      one_way = one_way && uses[j].forward == uses[i].forward;
    }
    if (net != 0) {
      const VertexIndex a = VertexIndex(uses[i].edge >> 32), b = VertexIndex(uses[i].edge);
      std::ostringstream message;
      if (one_way && j - i >= 2)
        message << "mesh is not consistently oriented: faces " << uses[i].face << " and "
                << uses[i + 1].face << " both run the edge between vertices " << a << " and " << b
                << " the same way (one of them is turned)";
      else
        message << "mesh is not closed: the edge between vertices " << a << " and " << b
                << " of face " << uses[i].face
                << (j - i == 1 ? " has no face on its other side"
                               : " has more faces on one side than on the other");
      message << " (vertices and faces numbered after merging equal vertices and faces)";
      return message.str();
    }
    i = j;
  }
  return {};
}

// Refuses, before the arrangement is built, a mesh whose arrangement would exceed the budget
// (RepairOptions::budget).
void require_budget(const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs,
                    std::size_t faces, std::size_t input_faces, double budget) {
  if (budget <= 0) return;
  std::vector<std::uint32_t> degree(faces, 0);
  for (const auto& [i, j] : pairs) ++degree[i], ++degree[j];
  double work = 0;
  for (const std::uint32_t d : degree) work += double(d) * double(d);
  const double limit = std::max(budget * double(input_faces), kRepairMinimumWork);
  if (work <= limit) return;
  std::ostringstream message;
  message << "repair would exceed its budget: " << pairs.size() << " pairs of its " << input_faces
          << " faces cross or touch, an arrangement of work " << std::scientific
          << std::setprecision(2) << work << " (the sum over faces of the squared number of "
          << "faces each meets) above the budget " << limit << " (" << std::defaultfloat
          << std::setprecision(6) << budget
          << " per input face): raise it with `morphex repair --budget`, `morphex index "
          << "--repair-budget` or the repair stage's \"budget\" (0: no bound)";
  throw InputError("", message.str());
}

}  // namespace

RepairResult repair_mesh(const Mesh& mesh, const RepairOptions& options) {
  RepairResult result;
  RepairReport& r = result.report;
  r.input_faces = mesh.num_triangles();
  if (mesh.empty()) throw InputError("", "mesh has no faces");
  r.components_in = component_count(mesh);
  // One check says whether there is anything to do, and lists the pairs of faces that meet
  // improperly: the arrangement intersects only those.
  CheckOptions check = kValidityOnly;
  check.list_self_intersections = true;
  ProgressSteps steps;
  steps.next(0.15, "checking");
  const MeshReport report = check_mesh(mesh, check);
  if (report.valid_solid()) {
    result.solid = detail::trusted_solid(mesh);  // the check just said so
    r.output_faces = mesh.num_triangles();
    r.components_out = r.components_in;
    return result;
  }
  std::vector<std::uint32_t> face_of;
  Mesh chain = merged(mesh, true, r, face_of);
  if (const std::string problem = open_chain(chain); !problem.empty()) {
    // Repeated faces may instead be where two shells coincide (a solid and a copy triangulated
    // partly alike): keeping every face then closes the chain, and the winding counts both.
    RepairReport all = r;
    all.duplicate_faces = 0;
    std::vector<std::uint32_t> face_of_all;
    Mesh every = merged(mesh, false, all, face_of_all);
    if (r.duplicate_faces == 0 || !open_chain(every).empty()) throw InputError("", problem);
    chain = std::move(every);
    face_of = std::move(face_of_all);
    r = all;
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  pairs.reserve(report.self_intersecting_pairs.size());
  for (const auto& [i, j] : report.self_intersecting_pairs)
    if (face_of[i] != face_of[j])
      pairs.emplace_back(std::min(face_of[i], face_of[j]), std::max(face_of[i], face_of[j]));
  require_budget(pairs, chain.num_triangles(), mesh.num_triangles(), options.budget);
  switch (signed_volume_sign(chain)) {
    case CGAL::ZERO:
      throw InputError("", "mesh bounds no volume (its signed volume is zero)");
    case CGAL::NEGATIVE:
      chain = reversed(chain);
      r.reversed = true;
      break;
    default:
      break;
  }
  WindingOptions winding;
  winding.merge_coplanar = options.merge_coplanar;
  winding.pairs = &pairs;
  WindingStats stats;
  steps.next(1, "");  // the arrangement names its own steps
  Mesh solid = winding_solid(chain, {}, winding, &stats);
  if (solid.empty()) throw InputError("", "mesh bounds no region of positive winding number");
  r.degenerate_faces = stats.degenerate_faces;
  r.cancelled_faces = stats.cancelled_faces;
  r.intersecting_pairs = stats.intersecting_pairs;
  r.output_faces = solid.num_triangles();
  r.components_out = component_count(solid);
  r.changed = true;
  result.solid = detail::trusted_solid(std::move(solid));  // the arrangement's region is one
  return result;
}

}  // namespace morphex
