// SPDX-License-Identifier: GPL-3.0-or-later
// Flat regions for the self-intersection check: coplanar patches whose triangles provably meet
// one another only at their common edges and vertices, so that their pairs need no test.
//
// Why: a flat face triangulated with long thin facets (a fan from one vertex, as CAD exporters
// write caps and plates) has triangles whose boxes all overlap one another and the features near
// the face, so that a box traversal meets a quadratic number of pairs. A patch is instead proved
// embedded in its plane as a whole: the triangles turn one way, every vertex star wraps once
// (interior) or less than once (border), and the border is one simple closed polygon. A locally
// injective map of a disc whose border is simple is injective, so no two triangles of the patch
// overlap. Triangles outside the patch are then tested against it only when they meet its plane
// elsewhere than in its own vertices and edges.
#pragma once

#include <CGAL/Bbox_3.h>

#include <array>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "check/check_planes.h"
#include "exact/point_table.h"
#include "morphex/mesh.h"
#include "tree/box_frame.h"

namespace morphex::detail {

// For each edge of the mesh used by exactly two faces (by vertex index), its key and the faces.
using ManifoldEdges = std::vector<std::pair<std::uint64_t, std::array<std::uint32_t, 2>>>;

// A group of triangles proved to meet one another only at their common edges and vertices:
// a flat patch, or (not flat) triangles of one vertex star that a coordinate projection maps
// onto a fan without overlap (a cone's side: long thin facets meeting at its apex).
struct PlanarPatch {
  // Flat: its triangles lie in one plane. NearlyFlat (add_near_flat_patches): they lie in the
  // slab below. Star (add_proved_stars): the triangles of one vertex star.
  enum class Kind { Flat, NearlyFlat, Star };
  Kind kind = Kind::Flat;
  std::array<PointId, 3> plane;          // flat: a triangle of the patch, spanning its plane
  std::vector<std::uint32_t> triangles;  // mesh triangle indices
  std::vector<PointId> vertices;         // its positions, sorted
  std::vector<std::uint64_t> edges;      // its edges (min << 32 | max over positions), sorted
  CGAL::Bbox_3 box;
  // NearlyFlat: every vertex's height normal . x lies in [low, high] (bounds from interval
  // arithmetic, so exact), and whatever stays outside that slab cannot meet the patch.
  std::array<double, 3> normal{};
  double low = 0, high = 0;
  int dropped = 2;  // the coordinate axis closest to `normal`
};

struct PlanarPatches {
  std::vector<PlanarPatch> patches;
  std::vector<std::int32_t> patch_of;  // by triangle: its verified patch, or -1
};

// Patches of at least `min_triangles` non-degenerate triangles joined across manifold edges
// where they lie in one plane on either side of the edge (positions as given by `position`),
// kept when proved embedded.
PlanarPatches verified_planar_patches(const Mesh& mesh, const PointTable& table,
                                      const FacePlanes& planes,
                                      const std::vector<PointId>& position,
                                      const std::vector<std::uint8_t>& degenerate,
                                      const ManifoldEdges& manifold, std::size_t min_triangles);

// Patches of at least `min_triangles` triangles outside `groups`, joined across manifold edges
// where their normals differ by less than about a thousandth of a radian, kept when proved
// embedded along a coordinate axis as flat patches are (the proof needs no flatness: an injective
// projection of the patch means no two of its triangles meet elsewhere than at common features).
// Such patches are the flat faces of a mesh after a rounded rotation: long thin facets that are
// no longer exactly coplanar. Appended as Kind::NearlyFlat.
void add_near_flat_patches(const Mesh& mesh, const PointTable& table, const FacePlanes& planes,
                           const std::vector<PointId>& position,
                           const std::vector<std::uint8_t>& degenerate,
                           const ManifoldEdges& manifold, std::size_t min_triangles,
                           PlanarPatches& groups);

// A triangle's corners as intervals in the coordinates its boxes are taken in: along the
// coordinate axes, or along the axes of a turned part (box_frame.h). The slab tests below hold
// in any of them: a linear map keeps a triangle's part, its slices and its projections apart
// from a box apart. The caller rounds upward.
using ApproxCorners = std::array<ApproxPoint, 3>;
ApproxCorners corners_in(const PointTable& table, const BoxFrame& frame,
                         const std::array<PointId, 3>& t);
// The axis of `frame` to see the slab patch along: the one closest to its normal.
int dropped_in(const BoxFrame& frame, const PlanarPatch& patch);

// The part of triangle t (by positions) inside the slab of `patch` (NearlyFlat) lies in the
// returned box, taken along `frame`; nullopt when t lies strictly outside the slab. The caller
// rounds upward.
std::optional<CGAL::Bbox_3> part_in_slab(const PointTable& table, const PlanarPatch& patch,
                                         const std::array<PointId, 3>& t, const BoxFrame& frame);

// A triangle seen along the axis `dropped` (its corners in any coordinates): the lines of its
// edges that tell its inside (those whose third corner is certainly on one side), in interval
// arithmetic, with the corner of a box each line reaches first. The caller rounds upward.
struct EdgeLines {
  struct Line {
    CGAL::Interval_nt<false> ex, ey, x, y;  // the edge's direction and first corner
    bool positive;                          // the inside is where the side is positive
    int u_first, u_last, v_first, v_last;   // the box corners to test
  };
  int u, v;  // the coordinates seen
  int count = 0;
  Line line[3];
};
EdgeLines edge_lines(const ApproxCorners& t, int dropped);

// Seen along the lines' axis, the triangle of `lines` and the box `part` (in the same
// coordinates) are certainly apart (a line through an edge has the box strictly on its outer side):
// then they do not meet. The caller rounds upward.
bool apart_along_axis(const EdgeLines& lines, const CGAL::Bbox_3& part);

// (q - p) x (r - p) for triangle t = (p, q, r), in doubles from the lower ends of the corners'
// intervals: a rough quantity (to group faces, to count slices), never a decision.
std::array<double, 3> rough_cross(const PointTable& table, const std::array<PointId, 3>& t);

// How many pieces to box triangle t in: 1, or for a long thin triangle lying diagonally up to
// 16 (its box is then far larger than itself, and a box traversal pairs it with everything
// near it). A degenerate triangle gets 1.
int pieces_for(const ApproxCorners& t);
// Boxes that together hold triangle t: its box (pieces = 1), or the boxes of `pieces` slices
// across its longest extent. The caller rounds upward.
void add_pieces(const ApproxCorners& t, int pieces, std::vector<CGAL::Bbox_3>& out);

// Vertex stars of at least `min_triangles` triangles outside `groups` whose projection along
// a coordinate axis is one fan turning one way and wrapping at most once: then no two of them
// meet beyond their common vertex and edges. Their triangles outside earlier groups are appended
// as groups of Kind::Star (`edges`, `vertices` and `plane` unused).
void add_proved_stars(const Mesh& mesh, const PointTable& table,
                      const std::vector<PointId>& position,
                      const std::vector<std::uint8_t>& degenerate, std::size_t min_triangles,
                      PlanarPatches& groups);

// Triangle t (by positions) meets the patch's plane at most in one vertex or one edge of the
// patch: then it meets no triangle of the patch improperly. `plane_side` is the patch's plane's
// (PointTable::PlaneSides over patch.plane: one per patch, for its many candidates).
bool meets_patch_only_at_its_features(const PointTable::PlaneSides& plane_side,
                                      const PlanarPatch& patch, const std::array<PointId, 3>& t);

// Closed segments pq and rs of one plane, seen along `dropped`, meet.
bool segments_meet_2(const PointTable& table, int dropped, PointId p, PointId q, PointId r,
                     PointId s);
// x is in the closed triangle t of its plane, seen along `dropped`.
bool inside_2(const PointTable& table, int dropped, const std::array<PointId, 3>& t, PointId x);

}  // namespace morphex::detail
