// SPDX-License-Identifier: GPL-3.0-or-later
#include "morphex/check.h"

#include <tbb/parallel_for.h>

#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <sstream>
#include <unordered_map>

#include "morphex/spatial.h"
#include "union_find.h"

namespace morphex {

namespace {
using detail::UnionFind;

using EdgeKey = std::uint64_t;
EdgeKey key(VertexIndex a, VertexIndex b) {
  return (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
}

}  // namespace

MeshReport check_mesh(const Mesh& mesh, const CheckOptions& options) {
  MeshReport r;
  r.vertices = mesh.num_vertices();
  r.triangles = mesh.num_triangles();
  const std::size_t nf = mesh.num_triangles();
  for (const Point& p : mesh.points) r.bbox += p.bbox();

  // Edges by vertex index: how many faces use them, in which direction.
  struct EdgeUse {
    std::uint32_t forward = 0, backward = 0;  // forward: min -> max
    std::uint32_t faces[2];
  };
  std::unordered_map<EdgeKey, EdgeUse> edges;
  edges.reserve(nf * 2);
  UnionFind components(nf);
  for (std::uint32_t f = 0; f < nf; ++f) {
    const Triangle& t = mesh.triangles[f];
    const bool repeated = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    if (repeated || CGAL::collinear(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]])) {
      if (!r.first_degenerate_face) r.first_degenerate_face = f;
      ++r.degenerate_faces;
    }
    for (int k = 0; k < 3; ++k) {
      const VertexIndex a = t[k], b = t[(k + 1) % 3];
      EdgeUse& use = edges[key(a, b)];
      const std::uint32_t count = use.forward + use.backward;
      if (count < 2) use.faces[count] = f;
      (a < b ? use.forward : use.backward) += 1;
      if (count > 0) components.join(f, use.faces[0]);
    }
  }
  std::vector<bool> on_bad_edge;
  for (const auto& [k, use] : edges) {
    const std::uint32_t count = use.forward + use.backward;
    if (count == 1) {
      ++r.border_edges;
      const VertexIndex v = VertexIndex(k >> 32);
      if (!r.first_border_vertex || v < *r.first_border_vertex) r.first_border_vertex = v;
    } else if (count > 2) {
      ++r.non_manifold_edges;
    } else if (use.forward != 1) {
      r.consistently_oriented = false;
      if (!r.first_misoriented_face || use.faces[0] < *r.first_misoriented_face)
        r.first_misoriented_face = use.faces[0];
    }
  }

  // Non-manifold vertices: the faces around a vertex must form one fan through manifold edges.
  {
    std::vector<std::vector<std::uint32_t>> corners(mesh.num_vertices());
    for (std::uint32_t f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) corners[mesh.triangles[f][k]].push_back(f);
    for (VertexIndex v = 0; v < mesh.num_vertices(); ++v) {
      const auto& faces = corners[v];
      if (faces.size() < 2) continue;
      std::map<std::uint32_t, std::uint32_t> local;
      for (std::uint32_t i = 0; i < faces.size(); ++i) local[faces[i]] = i;
      UnionFind fan(faces.size());
      for (std::uint32_t f : faces)
        for (int k = 0; k < 3; ++k) {
          const Triangle& t = mesh.triangles[f];
          if (t[k] != v && t[(k + 1) % 3] != v) continue;
          const auto it = edges.find(key(t[k], t[(k + 1) % 3]));
          if (it == edges.end() || it->second.forward + it->second.backward != 2) continue;
          const auto& use = it->second;
          if (local.count(use.faces[0]) && local.count(use.faces[1]))
            fan.join(local[use.faces[0]], local[use.faces[1]]);
        }
      std::size_t fans = 0;
      for (std::uint32_t i = 0; i < faces.size(); ++i) fans += fan.find(i) == i;
      if (fans > 1) {
        ++r.non_manifold_vertices;
        if (!r.first_non_manifold_vertex) r.first_non_manifold_vertex = v;
      }
    }
  }

  // Components, and per component the Euler characteristic and exact volume.
  std::vector<std::uint32_t> component_of(nf);
  std::map<std::uint32_t, std::uint32_t> component_index;
  for (std::uint32_t f = 0; f < nf; ++f) {
    const std::uint32_t root = components.find(f);
    auto [it, inserted] = component_index.emplace(root, std::uint32_t(component_index.size()));
    component_of[f] = it->second;
  }
  r.components = component_index.size();
  std::vector<Mesh> shells(r.components);
  {
    std::vector<std::unordered_map<VertexIndex, VertexIndex>> remap(r.components);
    for (std::uint32_t f = 0; f < nf; ++f) {
      Mesh& shell = shells[component_of[f]];
      auto& map = remap[component_of[f]];
      Triangle t;
      for (int k = 0; k < 3; ++k) {
        auto [it, inserted] = map.emplace(mesh.triangles[f][k], VertexIndex(shell.points.size()));
        if (inserted) shell.points.push_back(mesh.points[mesh.triangles[f][k]]);
        t[k] = it->second;
      }
      shell.triangles.push_back(t);
    }
  }
  if (options.volume) r.volume = signed_volume(mesh);
  const auto volume_sign = [&](const Mesh& m) {
    return options.volume && &m == &mesh ? CGAL::sign(r.volume) : signed_volume_sign(m);
  };
  const bool manifold = r.closed() && r.non_manifold_edges == 0 && r.non_manifold_vertices == 0;
  if (manifold) {
    long genus = 0;
    for (const Mesh& s : shells) {
      const long chi =
          long(s.points.size()) - long(s.triangles.size() * 3 / 2) + long(s.triangles.size());
      genus += (2 - chi) / 2;
    }
    r.genus = genus;
  } else {
    r.genus = -1;
  }

  // Self-intersections, with the tree for candidate pairs.
  if (options.self_intersections && nf > 1) {
    // Triangles are tested in parallel, each against its later neighbours; the counts and the
    // first pair (smallest i, then the tree's order) do not depend on the thread count.
    const TriangleTree tree(mesh);
    std::vector<std::uint32_t> hits(nf, 0), first_j(nf, 0);
    tbb::parallel_for(std::uint32_t(0), std::uint32_t(nf), [&](std::uint32_t i) {
      tree.for_each_overlap(tree.box(i), [&](std::uint32_t j) {
        if (j <= i || !triangles_intersect_improperly(mesh, i, j)) return;
        if (hits[i]++ == 0) first_j[i] = j;
      });
    });
    for (std::uint32_t i = 0; i < nf; ++i) {
      if (hits[i] == 0) continue;
      if (!r.first_self_intersection) r.first_self_intersection = std::make_pair(i, first_j[i]);
      r.self_intersections += hits[i];
    }
  }

  // Outward: a shell nested in an even number of others bounds material (positive volume), in an
  // odd number a cavity (negative). Only meaningful for closed, consistently oriented meshes.
  if (r.closed() && r.consistently_oriented && r.self_intersections == 0 &&
      r.degenerate_faces == 0) {
    std::vector<TriangleTree> trees;
    trees.reserve(shells.size());
    for (const Mesh& s : shells) trees.emplace_back(s);
    for (std::size_t c = 0; c < shells.size(); ++c) {
      int depth = 0;
      for (std::size_t o = 0; o < shells.size() && shells.size() > 1; ++o) {
        if (o == c) continue;
        // a vertex of shell c that is not on shell o (touching shells share positions)
        for (const Point& p : shells[c].points) {
          try {
            depth += winding_number(shells[o], trees[o], p) != 0;
            break;
          } catch (const std::domain_error&) {
            continue;
          }
        }
      }
      // One shell is the whole mesh, whose volume may already be known.
      const auto sign = volume_sign(shells.size() == 1 ? mesh : shells[c]);
      if (sign != (depth % 2 == 0 ? CGAL::POSITIVE : CGAL::NEGATIVE)) r.outward = false;
    }
  } else {
    r.outward = r.closed() && r.consistently_oriented && volume_sign(mesh) == CGAL::POSITIVE;
  }
  if (nf == 0) r.outward = true;
  return r;
}

std::string describe_problems(const MeshReport& r) {
  std::ostringstream out;
  if (r.border_edges > 0)
    out << "mesh is not closed: " << r.border_edges << " border edges, first at vertex "
        << *r.first_border_vertex;
  else if (r.non_manifold_edges > 0)
    out << "mesh has " << r.non_manifold_edges << " non-manifold edges";
  else if (r.degenerate_faces > 0)
    out << "mesh has " << r.degenerate_faces << " degenerate faces, first is face "
        << *r.first_degenerate_face;
  else if (!r.consistently_oriented)
    out << "mesh is not consistently oriented, first at face " << *r.first_misoriented_face;
  else if (r.non_manifold_vertices > 0)
    out << "mesh has " << r.non_manifold_vertices << " non-manifold vertices, first is vertex "
        << *r.first_non_manifold_vertex;
  else if (r.self_intersections > 0)
    out << "mesh self-intersects: " << r.self_intersections << " pairs of faces, first faces "
        << r.first_self_intersection->first << " and " << r.first_self_intersection->second;
  else if (!r.outward)
    out << "mesh is oriented inward (its faces must be counter-clockwise seen from outside)";
  return out.str();
}

}  // namespace morphex
