// SPDX-License-Identifier: GPL-3.0-or-later
// Step 2: candidate triangle pairs. When the meshes are of comparable size, a tree on each and
// one traversal of both together, which prunes the parts of either mesh far from the other at
// once; when one mesh is much smaller (a coarse box against a fine sphere), a pair of a coarse
// facet and a fine one whose boxes overlap is kept only when the coarse facet's plane may cross
// the fine one's box (a coarse facet's box holds many fine triangles its plane does not reach:
// they are not worth the exact tests of step 3), found by the seed's tree on the coarse mesh
// queried with the fine boxes, or by the fine mesh's tree queried with the coarse boxes. Boxes and
// planes are taken along the axes OperandTrees::use_frame sets (a turned CAD part's own:
// box_frame.h).
#include <CGAL/FPU.h>
#include <CGAL/Interval_nt.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <optional>

#include "boolean/boolean_internal.h"
#include "containers/id_pairs.h"
#include "tree/box_tree.h"

namespace morphex::detail {
namespace {

using Interval = CGAL::Interval_nt<false>;  // the caller rounds upward

// A triangle's plane n . x = d on intervals enclosing the exact one.
struct IntervalPlane {
  Interval n[3], d;
};

IntervalPlane plane_of(const ApproxPoint& a, const ApproxPoint& b, const ApproxPoint& c) {
  const auto n = CGAL::cross_product(b - a, c - a);
  return {{n.x(), n.y(), n.z()}, n.x() * a.x() + n.y() * a.y() + n.z() * a.z()};
}

// The plane may meet the box: its signed distance at the box's centre, against the box's
// half-extent measured along the normal, does not put the whole box on one side.
bool plane_may_cross(const IntervalPlane& p, const FloatBox& box) {
  Interval at_centre = -p.d, reach = 0;
  for (int k = 0; k < 3; ++k) {
    const Interval lo(box.lo[k]), hi(box.hi[k]);
    at_centre += p.n[k] * ((lo + hi) / 2);
    reach += CGAL::abs(p.n[k]) * ((hi - lo) / 2);
  }
  return !(at_centre.inf() > reach.sup() || at_centre.sup() < -reach.sup());
}

}  // namespace

std::vector<FloatBox> OperandTrees::vertex_boxes(int side, const Mesh& mesh,
                                                 const BoxFrame& frame) const {
  return boxes_in_frame(frame, *points_, points_->vertex(side, 0), mesh.num_vertices());
}

const TriangleTree& OperandTrees::of(int side, const Mesh& mesh) {
  if (!tree_[side])
    tree_[side] = std::make_shared<const TriangleTree>(mesh, vertex_boxes(side, mesh, BoxFrame{}));
  return *tree_[side];
}

bool OperandTrees::has_pairs_tree(int side) const {
  return frame_.world ? tree_[side] != nullptr : framed_[side].has_value();
}

const TriangleTree& OperandTrees::for_pairs(int side, const Mesh& mesh) {
  if (frame_.world) return of(side, mesh);
  if (!framed_[side]) framed_[side].emplace(mesh, vertex_boxes(side, mesh, frame_));
  return *framed_[side];
}

std::vector<FloatBox> OperandTrees::triangle_boxes_of(int side, const Mesh& mesh) const {
  return triangle_boxes(mesh, vertex_boxes(side, mesh, frame_));
}

ApproxPoint OperandTrees::corner(int side, VertexIndex v) const {
  return point_in_frame(frame_, points_->approx(points_->vertex(side, v)));
}

Pairs candidate_pairs(const Mesh& a, const Mesh& b, OperandTrees& trees) {
  if (a.empty() || b.empty()) return {};
  const std::size_t na = a.num_triangles(), nb = b.num_triangles();
  if (na * nb <= 4096) {
    // Small operands (the pieces of a morphology step): every pair of boxes, no trees.
    auto boxes = [](const Mesh& m) {
      std::vector<FloatBox> out(m.num_triangles());
      for (std::size_t t = 0; t < out.size(); ++t)
        for (VertexIndex v : m.triangles[t]) out[t] += FloatBox::of(m.points[v]);
      return out;
    };
    const std::vector<FloatBox> box_a = boxes(a), box_b = boxes(b);
    Pairs pairs;
    for (std::uint32_t i = 0; i < na; ++i)
      for (std::uint32_t j = 0; j < nb; ++j)
        if (box_a[i].overlaps(box_b[j])) pairs.emplace_back(i, j);
    return pairs;
  }
  if (std::max(na, nb) < 8 * std::min(na, nb)) {
    // Both trees at once: the upper levels of a tree are built sequentially.
    tbb::parallel_invoke([&] { trees.for_pairs(0, a); }, [&] { trees.for_pairs(1, b); });
    return TriangleTree::overlapping_pairs(trees.for_pairs(0, a), trees.for_pairs(1, b));
  }
  // The coarse operand's facets, each with its plane, against the fine operand's tree.
  const bool a_coarse = na < nb;
  const int coarse_side = a_coarse ? 0 : 1, fine_side = 1 - coarse_side;
  const Mesh &coarse = a_coarse ? a : b, &fine = a_coarse ? b : a;
  // The coarse facets query the fine tree when it exists (the input check built it) or when the
  // coarse tree is deep enough that a query per fine facet costs more than building the fine tree.
  // With a handful of coarse facets, building the fine tree costs more than it saves; with a
  // thousand or more it pays (docs/benchmarks.md has the measurements behind the threshold).
  const bool from_coarse = trees.has_pairs_tree(fine_side) || coarse.num_triangles() >= 1024;
  // The planes as the trees' frame sees them (a linear map takes a plane to a plane).
  std::vector<IntervalPlane> planes(coarse.num_triangles());
  {
    const CGAL::Protect_FPU_rounding<true> upward;
    for (std::uint32_t t = 0; t < planes.size(); ++t) {
      const Triangle& f = coarse.triangles[t];
      planes[t] = plane_of(trees.corner(coarse_side, f[0]), trees.corner(coarse_side, f[1]),
                           trees.corner(coarse_side, f[2]));
    }
  }
  // One side's boxes query the other side's tree, in blocks (coarse boxes hold many fine facets),
  // each block's pairs in its own vector, concatenated in block order.
  const TriangleTree& tree =
      from_coarse ? trees.for_pairs(fine_side, fine) : trees.for_pairs(coarse_side, coarse);
  const std::vector<FloatBox> queries = from_coarse ? trees.triangle_boxes_of(coarse_side, coarse)
                                                    : trees.triangle_boxes_of(fine_side, fine);
  const std::uint32_t block_size = from_coarse ? 64 : 1024;
  const auto nq = std::uint32_t(queries.size());
  std::vector<Pairs> found((nq + block_size - 1) / block_size);
  tbb::parallel_for(std::uint32_t(0), std::uint32_t(found.size()), [&](std::uint32_t block) {
    const CGAL::Protect_FPU_rounding<true> upward;
    for (std::uint32_t q = block * block_size; q < std::min(nq, (block + 1) * block_size); ++q)
      tree.for_each_overlap(queries[q], [&](std::uint32_t t) {
        const std::uint32_t c = from_coarse ? q : t, f = from_coarse ? t : q;
        if (plane_may_cross(planes[c], from_coarse ? tree.float_box(t) : queries[q]))
          found[block].push_back(a_coarse ? std::make_pair(c, f) : std::make_pair(f, c));
      });
  });
  Pairs pairs;
  for (const Pairs& f : found) pairs.insert(pairs.end(), f.begin(), f.end());
  sort_id_pairs(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace morphex::detail
