// SPDX-License-Identifier: GPL-3.0-or-later
// Collinearity of points of one input facet decided by how they were made, for the
// triangulations of step 5 (a cut facet) and of the coplanar merge (a region in a facet's plane).
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "exact/point_table.h"

namespace morphex::detail {

// Each point of the facet lies on a line or plane of the other side's input points: the edge
// that crosses the facet, or the facet that the point's own edge crosses (an input point, on
// itself). When the three points' lines and planes span one plane, other than the facet's, the
// points lie on its line with the facet's plane. A flat face of the other mesh made of many
// facets puts rows of such points on a facet, exactly collinear: each of their orientations
// would otherwise need their exact coordinates. A triangulation asks about the same rows again
// and again, so the last plane found is kept with the input points known on it.
// One per triangulation (not thread-safe).
class FacetLines {
 public:
  FacetLines(const PointTable& table, const std::array<PointId, 3>& facet)
      : table_(table), facet_(facet) {}
  // Whether p, q and r are collinear by their recipes; false when that is not known (not that
  // they are not collinear).
  bool collinear(PointId p, PointId q, PointId r);

 private:
  // The input points spanning what p, q and r lie on, sorted and distinct; empty when a point's
  // recipe tells nothing (a crossing of a line seen along an axis lies on its edge only).
  std::vector<PointId> span(PointId p, PointId q, PointId r) const;
  // Whether every point of `span` lies on the kept plane, as far as the kept list tells or its
  // linear form decides (the list is updated).
  bool on_kept_plane(const std::vector<PointId>& span);

  const PointTable& table_;
  const std::array<PointId, 3> facet_;
  std::optional<PointTable::PlaneSides> plane_;  // the last plane found, never the facet's
  std::vector<PointId> on_;                      // input points known on it (a few dozen)
};

}  // namespace morphex::detail
