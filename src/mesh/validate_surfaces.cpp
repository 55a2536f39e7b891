#include "igm/mesh/validate_surfaces.h"

#include <algorithm>
#include <map>
#include <string>
#include <utility>

#include "igm/core/error.h"
#include "igm/core/union_find.h"
#include "validate_internal.h"

namespace igm {

namespace {

using validate_internal::Analysis;
using validate_internal::Mode;

constexpr std::size_t kMaxNamed = 5;       // items named in a message
constexpr std::size_t kMaxElements = 100;  // ids kept in an error

std::string plural(std::size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// Per loop of c, the triangle whose half-edge runs from the loop's first vertex to its second.
// Cost O(F log L).
std::vector<int> loop_triangles(const SurfaceComponent& c) {
  std::map<std::pair<int, int>, std::size_t> first_edge;
  for (std::size_t l = 0; l < c.boundary_loops.size(); ++l) {
    const auto& loop = c.boundary_loops[l];
    first_edge[{loop[0], loop[1 % loop.size()]}] = l;
  }
  std::vector<int> tri(c.boundary_loops.size(), -1);
  for (std::size_t t = 0; t < c.triangles.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      const auto it = first_edge.find({c.triangles[t][i], c.triangles[t][(i + 1) % 3]});
      if (it != first_edge.end()) tri[it->second] = static_cast<int>(t);
    }
  return tri;
}

// igm::Error(Boundary) for the loops of `components` (at least one), one input face per loop.
[[noreturn]] void throw_boundary(const std::vector<SurfaceComponent>& components,
                                 const std::string& why) {
  std::vector<std::int64_t> faces;
  std::string named;
  std::size_t loops = 0, edges = 0, shown = 0;
  for (const SurfaceComponent& c : components) {
    const std::vector<int> tri = loop_triangles(c);
    for (std::size_t l = 0; l < c.boundary_loops.size(); ++l, ++loops) {
      const auto& loop = c.boundary_loops[l];
      edges += loop.size();
      const std::int64_t f = c.input_face[static_cast<std::size_t>(tri[l])];
      if (faces.size() < kMaxElements) faces.push_back(f);
      if (shown++ < kMaxNamed)
        named += std::string(named.empty() ? "" : "; ") + "a loop of " +
                 plural(loop.size(), "edge", "edges") + " through edge (" +
                 std::to_string(c.input_vertex[loop[0]]) + ", " +
                 std::to_string(c.input_vertex[loop[1 % loop.size()]]) + ") of face " +
                 std::to_string(f);
    }
  }
  if (shown > kMaxNamed) named += "; ...";
  throw Error(ErrorKind::Boundary,
              "the surface is not closed" + why + ": " +
                  plural(loops, "boundary loop", "boundary loops") + " (" +
                  plural(edges, "edge", "edges") + " with one face): " + named,
              std::move(faces));
}

}  // namespace

SurfaceSet validate_surfaces(const PolygonSoup& soup, const SurfaceOptions& options) {
  const Analysis a = validate_internal::analyze(
      soup, options.base, options.split_nonmanifold ? Mode::SplitSurfaces : Mode::Surfaces);
  for (const MeshProblem& p : a.report.problems)  // checked below, after the cuts
    if (p.kind != ErrorKind::Boundary && p.kind != ErrorKind::SeveralComponents)
      throw Error(p.kind, p.message, p.elements);
  const std::size_t nv = soup.positions.size(), T = a.tris.size();
  if (!options.base.drop_unreferenced && a.report.unreferenced_vertices > 0) {
    std::vector<std::int64_t> unused;
    std::vector<char> used(nv, 0);
    for (const auto& t : a.tris)
      for (int v : t) used[static_cast<std::size_t>(v)] = 1;
    for (std::size_t v = 0; v < nv && unused.size() < kMaxElements; ++v)
      if (!used[v]) unused.push_back(static_cast<std::int64_t>(v));
    std::string list;
    for (std::size_t i = 0; i < unused.size() && i < kMaxNamed; ++i)
      list += (i ? ", " : "") + std::to_string(unused[i]);
    throw Error(
        ErrorKind::SeveralComponents,
        plural(static_cast<std::size_t>(a.report.unreferenced_vertices), "unreferenced vertex",
               "unreferenced vertices") +
            " (drop_unreferenced is off) would be components without faces: vertex " + list +
            (a.report.unreferenced_vertices > static_cast<std::int64_t>(kMaxNamed) ? ", ..." : ""),
        std::move(unused));
  }
  const auto origin = [&](std::size_t h) { return a.tris[h / 3][h % 3]; };

  // Vertices: one per corner class (fan), ordered by (input vertex, first corner): counting sort
  // of the classes, met in corner order, by input vertex.
  std::vector<int> class_vertex(3 * T, -1);  // class representative -> global vertex
  std::vector<int> first_corner;             // classes in corner order: their first corner
  for (std::size_t h = 0; h < 3 * T; ++h)
    if (class_vertex[static_cast<std::size_t>(a.corner_class[h])] < 0) {
      class_vertex[static_cast<std::size_t>(a.corner_class[h])] = 0;
      first_corner.push_back(static_cast<int>(h));
    }
  std::vector<int> start(nv + 1, 0);
  for (int h : first_corner) ++start[static_cast<std::size_t>(origin(h)) + 1];
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<int> vertex_corner(first_corner.size());  // global vertex -> its first corner
  for (int h : first_corner) {
    const int g = start[static_cast<std::size_t>(origin(h))]++;
    vertex_corner[static_cast<std::size_t>(g)] = h;
    class_vertex[static_cast<std::size_t>(a.corner_class[static_cast<std::size_t>(h)])] = g;
  }
  const auto vertex = [&](std::size_t h) {
    return class_vertex[static_cast<std::size_t>(a.corner_class[h])];
  };

  // A cut edge whose pieces still share both end vertices cannot be separated by these cuts.
  for (std::size_t i = 0; i < a.pieces.size();) {  // one round per cut edge
    std::size_t j = i;
    while (j < a.pieces.size() && a.pieces[j].group == a.pieces[i].group) ++j;
    std::vector<std::pair<int, int>> ends;
    for (std::size_t k = i; k < j; ++k) {
      const std::size_t h = static_cast<std::size_t>(a.pieces[k].h1),
                        n = h % 3 == 2 ? h - 2 : h + 1;
      ends.push_back(std::minmax(vertex(h), vertex(n)));
    }
    std::sort(ends.begin(), ends.end());
    if (std::adjacent_find(ends.begin(), ends.end()) != ends.end()) {
      const std::size_t h = static_cast<std::size_t>(a.pieces[i].h1),
                        n = h % 3 == 2 ? h - 2 : h + 1;
      std::vector<std::int64_t> faces;
      for (std::size_t k = i; k < j; ++k) {
        faces.push_back(a.tri_face[static_cast<std::size_t>(a.pieces[k].h1) / 3]);
        if (a.pieces[k].h2 >= 0)
          faces.push_back(a.tri_face[static_cast<std::size_t>(a.pieces[k].h2) / 3]);
      }
      throw Error(ErrorKind::NonManifoldEdge,
                  "split_nonmanifold cannot cut edge (" +
                      std::to_string(std::min(origin(h), origin(n))) + ", " +
                      std::to_string(std::max(origin(h), origin(n))) +
                      "): two of its pieces join the same two fans at both ends",
                  std::move(faces));
    }
    i = j;
  }

  // Components: triangles joined through paired edges, numbered by their first triangle.
  UnionFind joined(T);
  for (std::size_t h = 0; h < 3 * T; ++h)
    if (a.twin[h] > static_cast<int>(h)) joined.unite(static_cast<int>(h / 3), a.twin[h] / 3);
  std::vector<int> root_component(T, -1), tri_component(T), local_tri(T);
  SurfaceSet out;
  out.warnings = a.report.warnings;
  for (std::size_t t = 0; t < T; ++t) {
    int& c = root_component[static_cast<std::size_t>(joined.find(static_cast<int>(t)))];
    if (c < 0) {
      c = static_cast<int>(out.components.size());
      out.components.emplace_back();
    }
    tri_component[t] = c;
    local_tri[t] = static_cast<int>(out.components[static_cast<std::size_t>(c)].input_face.size());
    out.components[static_cast<std::size_t>(c)].input_face.push_back(a.tri_face[t]);
  }
  std::vector<int> local(vertex_corner.size());  // global vertex -> local vertex of its component
  for (std::size_t g = 0; g < vertex_corner.size(); ++g) {
    const std::size_t h = static_cast<std::size_t>(vertex_corner[g]);
    SurfaceComponent& c = out.components[static_cast<std::size_t>(tri_component[h / 3])];
    local[g] = static_cast<int>(c.positions.size());
    c.positions.push_back(soup.positions[static_cast<std::size_t>(origin(h))]);
    c.input_vertex.push_back(origin(h));
  }

  // Triangles (flipped where the orientation repair says) and the boundary half-edges: a
  // pre-flip half-edge 3t+i is the final half-edge 3t+i, or 3t+2-i when t is flipped.
  std::vector<std::vector<int>> out_boundary(out.components.size());  // local vertex -> half-edge
  for (std::size_t t = 0; t < T; ++t) {
    SurfaceComponent& c = out.components[static_cast<std::size_t>(tri_component[t])];
    std::array<int, 3> v{};
    for (std::size_t i = 0; i < 3; ++i) v[i] = local[static_cast<std::size_t>(vertex(3 * t + i))];
    if (a.flip[t]) std::swap(v[1], v[2]);
    c.triangles.push_back(v);
    auto& ob = out_boundary[static_cast<std::size_t>(tri_component[t])];
    for (std::size_t i = 0; i < 3; ++i)
      if (a.twin[3 * t + (a.flip[t] ? 2 - i : i)] < 0) {
        if (ob.empty()) ob.assign(c.positions.size(), -1);
        int& slot = ob[static_cast<std::size_t>(v[i])];
        if (slot >= 0)
          throw Error(ErrorKind::Internal,
                      "validate_surfaces: two boundary half-edges leave vertex " +
                          std::to_string(c.input_vertex[static_cast<std::size_t>(v[i])]),
                      {c.input_vertex[static_cast<std::size_t>(v[i])]});
        slot = 3 * local_tri[t] + static_cast<int>(i);
      }
  }

  // Loops, genus, Euler characteristic per component.
  for (std::size_t ci = 0; ci < out.components.size(); ++ci) {
    SurfaceComponent& c = out.components[ci];
    const auto& ob = out_boundary[ci];
    std::size_t boundary_halfedges = 0;
    std::vector<char> seen(ob.size(), 0);
    for (std::size_t v = 0; v < ob.size(); ++v) {
      if (ob[v] < 0 || seen[v]) continue;
      std::vector<int> loop;
      int u = static_cast<int>(v);
      // At most V steps: each visits an unseen vertex with an outgoing boundary half-edge.
      while (!seen[static_cast<std::size_t>(u)]) {
        seen[static_cast<std::size_t>(u)] = 1;
        loop.push_back(u);
        const int h = ob[static_cast<std::size_t>(u)];
        if (h < 0) break;
        u = c.triangles[static_cast<std::size_t>(h / 3)][static_cast<std::size_t>((h % 3 + 1) % 3)];
      }
      if (u != static_cast<int>(v) || ob[static_cast<std::size_t>(loop.back())] < 0)
        throw Error(ErrorKind::Internal, "validate_surfaces: a boundary path through vertex " +
                                             std::to_string(c.input_vertex[v]) + " does not close");
      boundary_halfedges += loop.size();
      c.boundary_loops.push_back(std::move(loop));
    }
    const auto V = static_cast<std::int64_t>(c.positions.size()),
               F = static_cast<std::int64_t>(c.triangles.size());
    const std::int64_t twice_e = 3 * F + static_cast<std::int64_t>(boundary_halfedges);
    const std::int64_t chi = V - twice_e / 2 + F;
    const std::int64_t twice_genus = 2 - chi - static_cast<std::int64_t>(c.boundary_loops.size());
    if (twice_e % 2 != 0 || twice_genus % 2 != 0 || twice_genus < 0)
      throw Error(ErrorKind::Internal,
                  "validate_surfaces: component of face " + std::to_string(c.input_face[0]) +
                      " has Euler characteristic " + std::to_string(chi) + " with " +
                      std::to_string(c.boundary_loops.size()) + " boundary loops");
    c.euler_characteristic = chi;
    c.genus = static_cast<int>(twice_genus / 2);
  }

  if (!options.allow_boundary)
    for (const SurfaceComponent& c : out.components)
      if (!c.boundary_loops.empty()) throw_boundary(out.components, " (allow_boundary is off)");
  if (!options.allow_components && out.components.size() > 1) {
    std::vector<std::int64_t> first;
    std::string named;
    for (std::size_t i = 0; i < out.components.size(); ++i) {
      const SurfaceComponent& c = out.components[i];
      if (first.size() < kMaxElements) first.push_back(c.input_face[0]);
      if (i < kMaxNamed)
        named += std::string(i ? "; " : "") + plural(c.triangles.size(), "triangle", "triangles") +
                 " from face " + std::to_string(c.input_face[0]);
    }
    if (out.components.size() > kMaxNamed) named += "; ...";
    throw Error(ErrorKind::SeveralComponents,
                "the mesh has " + std::to_string(out.components.size()) +
                    " connected components (allow_components is off): " + named,
                std::move(first));
  }
  return out;
}

std::string split_nonmanifold_hint(const PolygonSoup& soup, const SurfaceOptions& options, const Error& refused,
                                   const std::string& option) {
  if (options.split_nonmanifold ||
      (refused.kind() != ErrorKind::NonManifoldEdge && refused.kind() != ErrorKind::NonManifoldVertex))
    return "";
  SurfaceOptions split = options;
  split.split_nonmanifold = true;
  SurfaceSet set;
  try {
    set = validate_surfaces(soup, split);
  } catch (const Error& e) {
    return option + " would cut its non-manifold vertices and edges apart, but then: " + e.what();
  }
  // The surfaces by (genus, loops), the commonest first few.
  std::map<std::pair<int, std::size_t>, std::size_t> kinds;
  for (const SurfaceComponent& c : set.components) ++kinds[{c.genus, c.boundary_loops.size()}];
  std::string list;
  std::size_t shown = 0;
  for (const auto& [topology, n] : kinds) {
    if (shown++ == kMaxNamed) {
      list += ", ...";
      break;
    }
    if (!list.empty()) list += ", ";
    list += std::to_string(n) + " of genus " + std::to_string(topology.first) + " with " +
            plural(topology.second, "boundary loop", "boundary loops");
  }
  return option + " cuts its non-manifold vertices and edges apart: " +
         plural(set.components.size(), "surface", "surfaces") + " (" + list + "), all valid input";
}

ValidMesh to_valid_mesh(const SurfaceComponent& component, std::vector<std::string> warnings) {
  if (!component.boundary_loops.empty()) throw_boundary({component}, "");
  ValidMesh m;
  m.mesh =
      TriMesh::from_triangles(static_cast<int>(component.positions.size()), component.triangles);
  const std::string broken = m.mesh.check_invariants();
  if (!broken.empty())
    throw Error(ErrorKind::Internal, "to_valid_mesh: the mesh breaks an invariant: " + broken);
  m.positions = component.positions;
  m.input_vertex = component.input_vertex;
  m.input_face = component.input_face;
  m.warnings = std::move(warnings);
  m.genus = component.genus;
  return m;
}

}  // namespace igm
