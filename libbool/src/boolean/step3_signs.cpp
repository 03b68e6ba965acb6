// SPDX-License-Identifier: GPL-3.0-or-later
// Step 3, signs: each candidate pair's corners classified against the other triangle's plane, and
// the pairs whose triangles do not meet marked separated.
//
// The signs are (point, facet plane) questions that neighbouring pairs share. Most are decided
// without exact arithmetic: a corner shared by both triangles is on the plane; interval normals
// decide points clearly off it; in a labelled soup, a vertex is on the planes its faces carry. The
// rest (coplanar pieces in morphology) are gathered, deduplicated and grouped by plane, and each
// is evaluated exactly once, with the plane's exact equation computed once per group.
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>

#include "boolean/segments_internal.h"
#include "exact/triangle_overlap.h"

namespace morphex::detail {

namespace {

constexpr std::int8_t kUndecided = 2;

// A question: the plane of facet (side, index), and the point.
using Question = std::uint64_t;
Question question(std::uint32_t side, std::uint32_t facet, PointId point) {
  return (std::uint64_t((side << 31) | facet) << 32) | point;
}

// Labelled soups: the planes through each vertex are those of its faces. An intersection point of
// an earlier operation lies on the planes that made it; a translate, on their translates.
class PlaneLabels {
 public:
  explicit PlaneLabels(const PairContext& c) : planes_(c.options.planes) {
    if (!planes_) return;
    const Mesh& soup = *c.meshes[0];
    const std::size_t n = c.table.num_inputs();
    start_.assign(n + 1, 0);
    for (const Triangle& t : soup.triangles)
      for (VertexIndex v : t) ++start_[c.rep[v] + 1];
    for (std::size_t v = 0; v < n; ++v) start_[v + 1] += start_[v];
    at_.resize(start_.back());
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::uint32_t f = 0; f < soup.triangles.size(); ++f)
      for (VertexIndex v : soup.triangles[f]) at_[fill[c.rep[v]]++] = (*planes_)[f];
  }

  bool known() const { return planes_ != nullptr; }
  bool same_plane(std::uint32_t fa, std::uint32_t fb) const {
    return planes_ && (*planes_)[fa] == (*planes_)[fb];
  }
  // Whether `vertex` lies on the plane of `facet` by its faces' labels (false: unknown).
  bool on_plane(PointId vertex, std::uint32_t facet) const {
    if (!planes_ || vertex + 1 >= start_.size()) return false;
    const auto first = at_.begin() + start_[vertex], last = at_.begin() + start_[vertex + 1];
    return std::find(first, last, (*planes_)[facet]) != last;
  }

 private:
  const std::vector<std::uint32_t>* planes_;
  std::vector<std::uint32_t> start_, at_;
};

// The signs intervals, shared corners and labels decide; true if they show t entirely on one
// side of the other's plane.
bool decide_cheaply(const PairContext& c, const PlaneLabels& labels, const Corners& t,
                    const Corners& other, std::uint32_t other_facet, const ApproxVector& normal,
                    std::int8_t (&out)[3]) {
  for (int i = 0; i < 3; ++i) {
    const auto o = t[i] == other[0] || t[i] == other[1] || t[i] == other[2]
                       ? CGAL::make_uncertain(CGAL::ZERO)
                       : c.table.side_filter(normal, other[0], t[i]);
    out[i] = o.is_certain()                       ? std::int8_t(o.make_certain())
             : labels.on_plane(t[i], other_facet) ? std::int8_t(0)
                                                  : kUndecided;
  }
  return out[0] != 0 && out[0] != kUndecided && out[0] == out[1] && out[1] == out[2];
}

// The undecided questions, sorted and distinct, with their exact answers.
struct ExactAnswers {
  std::vector<Question> questions;
  std::vector<std::int8_t> answers;

  std::int8_t operator()(Question q) const {
    return answers[std::lower_bound(questions.begin(), questions.end(), q) - questions.begin()];
  }
};

ExactAnswers answer_exactly(const PairContext& c, const std::vector<PairSigns>& signs) {
  ExactAnswers out;
  std::vector<Question>& questions = out.questions;
  for (std::size_t k = 0; k < signs.size(); ++k) {
    if (signs[k].separated) continue;
    const Corners ta = c.corners_a(k), tb = c.corners_b(k);
    for (int i = 0; i < 3; ++i) {
      if (signs[k].a[i] == kUndecided)
        questions.push_back(question(c.b_side(), c.pairs[k].second, ta[i]));
      if (signs[k].b[i] == kUndecided) questions.push_back(question(0, c.pairs[k].first, tb[i]));
    }
  }
  tbb::parallel_sort(questions.begin(), questions.end());
  questions.erase(std::unique(questions.begin(), questions.end()), questions.end());
  // Questions come sorted by plane: each plane's exact equation is computed once for its group.
  out.answers.resize(questions.size());
  std::vector<std::size_t> groups;
  for (std::size_t i = 0; i < questions.size(); ++i)
    if (i == 0 || (questions[i] >> 32) != (questions[i - 1] >> 32)) groups.push_back(i);
  groups.push_back(questions.size());
  tbb::parallel_for(std::size_t(0), groups.size() - 1, [&](std::size_t g) {
    const std::uint32_t plane = std::uint32_t(questions[groups[g]] >> 32);
    const std::uint32_t side = plane >> 31, facet = plane & 0x7fffffffu;
    const Corners f = c.corners(c.options.soup ? 0 : int(side), facet);
    const PointTable::PlaneSides sides(c.table, {f[0], f[1], f[2]});
    for (std::size_t i = groups[g]; i < groups[g + 1]; ++i)
      out.answers[i] = std::int8_t(sides.exact(PointId(questions[i])));
  });
  return out;
}

bool shares(const Corners& t, PointId p) {
  return p == t[0] || p == t[1] || p == t[2];
}

// In a soup, neighbouring triangles share corners. They meet only there when the other corners
// of one lie strictly on one side of the other's plane; the corners need no cut.
bool meet_at_corners(const PointTable& table, const Corners& ta, const Corners& tb,
                     const PairSigns& s) {
  auto beyond = [](const Corners& t, const Corners& other, const std::int8_t(&x)[3]) {
    int side = 0;
    bool shared = false;
    for (int i = 0; i < 3; ++i) {
      if (shares(other, t[i])) {
        shared = true;
        continue;
      }
      if (x[i] == 0 || (side != 0 && x[i] != side)) return false;
      side = x[i];
    }
    return shared && side != 0;
  };
  if (beyond(ta, tb, s.a) || beyond(tb, ta, s.b)) return true;
  // Coplanar neighbours: apart when the line of an edge of one through a common corner has the
  // other strictly on its far side (the one with the edge lies on its near closed side).
  for (int i = 0; i < 3; ++i)
    if (s.a[i] != 0 || s.b[i] != 0) return false;
  const int dropped = table.dominant_axis(ta[0], ta[1], ta[2]);
  for (const auto& [own, other] : {std::pair(&ta, &tb), std::pair(&tb, &ta)})
    for (int e = 0; e < 3; ++e) {
      const PointId x = (*own)[e], y = (*own)[(e + 1) % 3], z = (*own)[(e + 2) % 3];
      if (!shares(*other, x) && !shares(*other, y)) continue;
      const CGAL::Sign near = table.orientation_2(dropped, x, y, z);
      bool apart = true;
      for (PointId w : *other)
        if (w != x && w != y && table.orientation_2(dropped, x, y, w) != -near) apart = false;
      if (apart) return true;
    }
  return false;
}

bool one_side(const std::int8_t (&x)[3]) {
  return x[0] != 0 && x[0] == x[1] && x[1] == x[2];
}

}  // namespace

std::vector<PairSigns> pair_signs(const PairContext& c, const FacetNormals& normals) {
  const PlaneLabels labels(c);
  const std::size_t np = c.pairs.size();
  std::vector<PairSigns> signs(np);
  for_each_upward(np, [&](std::size_t k) {
    const auto [ia, ib] = c.pairs[k];
    PairSigns& s = signs[k];
    if (labels.same_plane(ia, ib)) {
      // Known to lie in one plane: every sign is zero, with no question asked.
      for (int i = 0; i < 3; ++i) s.a[i] = s.b[i] = 0;
      s.separated = false;
      return;
    }
    const Corners ta = c.corners_a(k), tb = c.corners_b(k);
    s.separated = decide_cheaply(c, labels, ta, tb, ib, normals.of(1, ib), s.a) ||
                  decide_cheaply(c, labels, tb, ta, ia, normals.of(0, ia), s.b);
  });

  // Settle the undecided signs, then test the triangles that straddle each other's planes.
  const ExactAnswers answer = answer_exactly(c, signs);
  const TriangleOverlap overlap(c.table);
  for_each_upward(np, [&](std::size_t k) {
    PairSigns& s = signs[k];
    if (s.separated) return;
    const auto [ia, ib] = c.pairs[k];
    const Corners ta = c.corners_a(k), tb = c.corners_b(k);
    for (int i = 0; i < 3; ++i) {
      if (s.a[i] == kUndecided) s.a[i] = answer(question(c.b_side(), ib, ta[i]));
      if (s.b[i] == kUndecided) s.b[i] = answer(question(0, ia, tb[i]));
    }
    s.separated =
        one_side(s.a) || one_side(s.b) || (c.options.soup && meet_at_corners(c.table, ta, tb, s));
    if (s.separated) return;
    s.coplanar = s.a[0] == 0 && s.a[1] == 0 && s.a[2] == 0;
    s.separated = !s.coplanar && !overlap(ta, tb, s.a, s.b);
  });
  return signs;
}

}  // namespace morphex::detail
