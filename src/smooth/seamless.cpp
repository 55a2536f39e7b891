#include "igm/smooth/seamless.h"

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

#include "../core/parallel.h"

#include "igm/core/error.h"
#include "igm/core/union_find.h"

namespace igm {

namespace {

// R^k (x, y) for R the rotation by +90 degrees: (x, y) -> (-y, x).
template <class T>
void rotate(int k, const T& x, const T& y, T& rx, T& ry) {
  switch (k & 3) {
    case 0:
      rx = x;
      ry = y;
      break;
    case 1:
      rx = -y;
      ry = x;
      break;
    case 2:
      rx = -x;
      ry = -y;
      break;
    default:
      rx = y;
      ry = -x;
      break;
  }
}

// Half-open quadrant of a nonzero vector from the exact signs of its coordinates (certify/README.md
// check 4): Q0: x > 0, y >= 0; Q1: x <= 0, y > 0; Q2: x < 0, y <= 0; Q3: x >= 0, y < 0.
int quadrant(Sign sx, Sign sy) {
  if (sx == Sign::Positive && sy != Sign::Negative) return 0;
  if (sx != Sign::Positive && sy == Sign::Positive) return 1;
  if (sx == Sign::Negative && sy != Sign::Positive) return 2;
  return 3;
}

// Exact comparison of two coordinates.
Sign order(const Rational& a, const Rational& b) { return compare(a, b); }
Sign order(double a, double b) {
  return a < b ? Sign::Negative : (a > b ? Sign::Positive : Sign::Zero);
}

// Quadrant of b - a, exactly (comparisons only).
template <class P>
int quadrant(const P& a, const P& b) {
  return quadrant(order(b.x, a.x), order(b.y, a.y));
}

// Both overloads of angle_indices: per corner of a positive triangle (v, a, b), its wedge from
// v->a to v->b crosses (q_b - q_a) mod 4 quadrant boundaries (at most 2: its angle is below pi).
// The corners' crossings are counted in parallel (exact comparisons, core/parallel.h), then added
// up per vertex (integers: in any order the same).
template <class P>
std::vector<int> indices(const TriMesh& m, const std::vector<std::array<P, 3>>& uv) {
  std::vector<signed char> crossings(m.num_halfedges());
  parallel::for_each_index(m.num_halfedges(), 4096, [&](std::int64_t c) {
    const std::array<P, 3>& t = uv[c / 3];
    const P& v = t[c % 3];
    crossings[c] = static_cast<signed char>(
        (quadrant(v, t[TriMesh::prev(static_cast<int>(c)) % 3]) - quadrant(v, t[TriMesh::next(static_cast<int>(c)) % 3]) + 4) & 3);
  });
  std::vector<int> index(m.num_vertices(), 0);
  for (int c = 0; c < m.num_halfedges(); ++c) index[m.origin(c)] += crossings[c];
  return index;
}

std::string vertex_name(int v) { return "vertex " + std::to_string(v); }

[[noreturn]] void invalid(const std::string& what, std::vector<std::int64_t> elements) {
  throw Error(ErrorKind::InvalidArgument, "not a valid IGM: " + what, std::move(elements));
}

// The transition across half-edge h (face A = face(h), a -> b) to its twin's face B, or throws.
// k is tried first where the double approximations of the edge vectors agree best, then the
// others, each decided exactly: R^k uv_A(a) + t = uv_B(a) and R^k uv_A(b) + t = uv_B(b) for one
// integer t.
GridMotion edge_transition(const TriMesh& m, const std::vector<std::array<Point2q, 3>>& uv, int h) {
  const int ht = m.twin(h);
  const Point2q& a_A = uv[h / 3][h % 3];
  const Point2q& b_A = uv[h / 3][TriMesh::next(h) % 3];
  const Point2q& b_B = uv[ht / 3][ht % 3];
  const Point2q& a_B = uv[ht / 3][TriMesh::next(ht) % 3];
  if (a_A.x == a_B.x && a_A.y == a_B.y && b_A.x == b_B.x && b_A.y == b_B.y) return {};  // one chart
  const double ex = approximate(b_A.x) - approximate(a_A.x),
               ey = approximate(b_A.y) - approximate(a_A.y);
  const double fx = approximate(b_B.x) - approximate(a_B.x),
               fy = approximate(b_B.y) - approximate(a_B.y);
  int first = 0;
  double best = -HUGE_VAL;
  for (int k = 0; k < 4; ++k) {
    double rx = 0, ry = 0;
    rotate(k, ex, ey, rx, ry);
    if (rx * fx + ry * fy > best) best = rx * fx + ry * fy, first = k;
  }
  for (int i = 0; i < 4; ++i) {  // four candidates
    const int k = (first + i) & 3;
    Rational rx, ry;
    rotate(k, a_A.x, a_A.y, rx, ry);
    Rational tx = a_B.x - rx, ty = a_B.y - ry;
    rotate(k, b_A.x, b_A.y, rx, ry);
    if (tx != b_B.x - rx || ty != b_B.y - ry) continue;
    if (tx.get_den() != 1 || ty.get_den() != 1) break;  // k is unique for a nonzero edge vector
    return GridMotion{k, tx.get_num(), ty.get_num()};
  }
  const int u = m.origin(h), w = m.target(h);
  invalid("the edge (" + std::to_string(std::min(u, w)) + ", " + std::to_string(std::max(u, w)) +
              ") has no rigid transition R^k x + t with integer t",
          {std::min(u, w), std::max(u, w)});
}

// The integer isoline through both ends of half-edge h, whose UVs in face(h)'s chart are a and b:
// the same integer u (axis 0) or else the same integer v (axis 1); nothing if neither.
std::optional<BoundaryIsoline> isoline_through(int h, const Point2q& a, const Point2q& b) {
  if (a.x == b.x && a.x.get_den() == 1) return BoundaryIsoline{h, 0, a.x.get_num()};
  if (a.y == b.y && a.y.get_den() == 1) return BoundaryIsoline{h, 1, a.y.get_num()};
  return std::nullopt;
}

// The integer isoline of boundary half-edge h (u or v constant and integer along it, in its
// face's chart), or throws naming the edge's vertices.
BoundaryIsoline boundary_isoline(const TriMesh& m, const std::vector<std::array<Point2q, 3>>& uv,
                                 int h) {
  if (auto e = isoline_through(h, uv[h / 3][h % 3], uv[h / 3][TriMesh::next(h) % 3])) return std::move(*e);
  const int u = m.origin(h), w = m.target(h);
  invalid("the boundary edge (" + std::to_string(std::min(u, w)) + ", " +
              std::to_string(std::max(u, w)) +
              ") lies on no integer isoline (u or v constant and integer along it)",
          {std::min(u, w), std::max(u, w)});
}

// Components (vertices joined by edges), boundary loops (the boundary half-edge leaving the
// target of one is the next one of its loop: each boundary vertex has one) and the total genus.
// Pre: every vertex used, one fan per vertex (seamless_structure checked both). Cost O(F).
void count_topology(SeamlessStructure& s) {
  const TriMesh& m = s.mesh;
  const int nv = m.num_vertices(), nh = m.num_halfedges();
  UnionFind sets(static_cast<std::size_t>(nv));
  int components = nv, boundary_halfedges = 0;
  for (int h = 0; h < nh; ++h) {
    if (sets.unite(m.origin(h), m.target(h))) --components;
    boundary_halfedges += m.twin(h) < 0;
  }
  std::vector<char> seen(nh, 0);
  int loops = 0;
  for (const BoundaryIsoline& e : s.boundary_edges) {  // bound: boundary half-edges, each seen once
    if (seen[e.halfedge]) continue;
    ++loops;
    for (int h = e.halfedge; !seen[h]; h = m.vertex_halfedge(m.target(h))) seen[h] = 1;
  }
  // chi = V - E + F with E = (3F + boundary half-edges) / 2; genus = sum (2 - chi_i - b_i) / 2
  const int nf = m.num_faces();
  const int chi = nv - (3 * nf + boundary_halfedges) / 2 + nf;
  s.components = components;
  s.boundary_loops = loops;
  s.genus = (2 * components - chi - loops) / 2;
}

}  // namespace

Point2q apply(const GridMotion& m, const Point2q& p) {
  Point2q r;
  rotate(m.k, p.x, p.y, r.x, r.y);
  r.x += m.tx;
  r.y += m.ty;
  return r;
}

GridMotion compose(const GridMotion& a, const GridMotion& b) {
  GridMotion r;
  r.k = (a.k + b.k) & 3;
  rotate(a.k, b.tx, b.ty, r.tx, r.ty);
  r.tx += a.tx;
  r.ty += a.ty;
  return r;
}

GridMotion inverse(const GridMotion& m) {
  // x = R^-k (y - t) = R^-k y - R^-k t
  GridMotion r;
  r.k = (4 - m.k) & 3;
  rotate(r.k, m.tx, m.ty, r.tx, r.ty);
  r.tx = -r.tx;
  r.ty = -r.ty;
  return r;
}

std::vector<int> angle_indices(const TriMesh& mesh,
                               const std::vector<std::array<Point2q, 3>>& corner_uv) {
  return indices(mesh, corner_uv);
}

std::vector<int> angle_indices(const TriMesh& mesh,
                               const std::vector<std::array<Vec2d, 3>>& corner_uv) {
  return indices(mesh, corner_uv);
}

SeamlessStructure seamless_structure(const IgmMesh& igm) {
  const std::size_t nf = igm.triangles.size();
  if (igm.corner_uv.size() != nf)
    invalid(std::to_string(nf) + " triangles but " + std::to_string(igm.corner_uv.size()) +
                " UV triples",
            {});
  if (igm.positions.size() > static_cast<std::size_t>(INT32_MAX))
    throw Error(ErrorKind::TooLarge, "too many vertices for 32-bit ids");
  const int nv = static_cast<int>(igm.positions.size());
  for (std::size_t f = 0; f < nf; ++f) {
    const auto& t = igm.triangles[f];
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
      invalid("face " + std::to_string(f) + " repeats a vertex", {static_cast<std::int64_t>(f)});
  }
  SeamlessStructure s;
  s.mesh = TriMesh::from_triangles(nv, igm.triangles, /*allow_boundary=*/true);
  const TriMesh& m = s.mesh;
  const auto& uv = igm.corner_uv;
  for (std::size_t f = 0; f < nf; ++f)
    if (orient2d(uv[f][0], uv[f][1], uv[f][2]) != Sign::Positive)
      invalid("the UV triangle of face " + std::to_string(f) + " is not strictly positive",
              {static_cast<std::int64_t>(f)});

  const int nh = m.num_halfedges();
  s.transition.resize(nh);
  s.boundary.assign(nv, 0);
  for (int h = 0; h < nh; ++h) {
    if (m.twin(h) < 0) {
      s.boundary_edges.push_back(boundary_isoline(m, uv, h));
      s.boundary[m.origin(h)] = 1;
      continue;
    }
    if (h > m.twin(h)) continue;
    s.transition[h] = edge_transition(m, uv, h);
    s.transition[m.twin(h)] = inverse(s.transition[h]);
  }

  s.angle_index = angle_indices(m, uv);
  s.reference_corner.assign(nv, -1);
  s.isoline_axis.assign(nv, -1);
  s.vertex_uv.resize(nv);
  s.corner_motion.resize(nh);
  std::vector<char> reached(nh, 0);
  for (int v = 0; v < nv; ++v) {
    const int h0 = m.vertex_halfedge(v);  // at a boundary vertex: its outgoing boundary half-edge
    if (h0 < 0) invalid(vertex_name(v) + " is used by no face", {v});
    s.reference_corner[v] = h0;
    s.vertex_uv[v] = uv[h0 / 3][h0 % 3];
    // Walk the fan from h0: at most nh steps (each corner is visited once, then the walk is back
    // at h0, stops at a corner seen before, or leaves the fan across its incoming boundary edge).
    int h = h0;
    bool open_end = false;
    GridMotion motion;  // identity at h0
    for (int steps = 0; steps <= nh; ++steps) {
      reached[h] = 1;
      s.corner_motion[h] = motion;
      const int across = TriMesh::prev(h);  // the edge (b, v) into the next corner's face
      if (m.twin(across) < 0) {
        open_end = true;
        break;
      }
      if (!s.transition[across].is_identity()) motion = compose(s.transition[across], motion);
      h = m.twin(across);
      if (h == h0 || reached[h]) break;
    }
    const bool boundary = s.boundary[v] != 0;
    if (boundary ? !open_end : (open_end || h != h0))
      throw Error(ErrorKind::NonManifoldVertex, "the fan of " + vertex_name(v) + " does not close",
                  {v});
    const int index = s.angle_index[v];
    if (index <= 0)
      invalid(vertex_name(v) + " has the angle index " + std::to_string(index) + " <= 0", {v});
    if (!boundary && index == 4 && !motion.is_identity())
      invalid("the transitions around the regular " + vertex_name(v) +
                  " do not compose to the identity",
              {v});
    if (s.is_cone(v) && (s.vertex_uv[v].x.get_den() != 1 || s.vertex_uv[v].y.get_den() != 1))
      invalid(std::string(boundary ? "the boundary corner " : "the cone ") + vertex_name(v) +
                  " (angle " + std::to_string(index) + " pi/2) is not at an integer point",
              {v});
    if (boundary && !s.is_cone(v))  // the isoline of its outgoing boundary edge, in this chart
      s.isoline_axis[v] = static_cast<signed char>(boundary_isoline(m, uv, h0).axis);
  }
  for (int h = 0; h < nh; ++h)
    if (!reached[h])
      throw Error(ErrorKind::NonManifoldVertex,
                  "the faces around " + vertex_name(m.origin(h)) + " form more than one fan",
                  {m.origin(h)});
  count_topology(s);
  return s;
}

void hold_isoline_edges(SeamlessStructure& s, const std::vector<std::pair<int, int>>& edges) {
  const TriMesh& m = s.mesh;
  const int nv = m.num_vertices();
  s.fixed_axes.assign(nv, 0);
  s.isoline_edges.clear();
  for (const auto& [a, b] : edges) {
    const std::string name = "the edge " + std::to_string(a) + "-" + std::to_string(b);
    if (a < 0 || a >= nv || b < 0 || b >= nv)
      throw Error(ErrorKind::InvalidArgument, "hold_isoline_edges: " + name + " has a vertex out of range", {a, b});
    int h = m.find_halfedge(a, b);
    if (h < 0) h = m.find_halfedge(b, a);
    if (h < 0) throw Error(ErrorKind::InvalidArgument, "hold_isoline_edges: " + name + " is not an edge of the map", {a, b});
    const int n = TriMesh::next(h);
    std::optional<BoundaryIsoline> e = isoline_through(h, apply(s.corner_motion[h], s.vertex_uv[m.origin(h)]),
                                                       apply(s.corner_motion[n], s.vertex_uv[m.origin(n)]));
    if (!e) throw Error(ErrorKind::InvalidArgument, "hold_isoline_edges: " + name + " is not on an integer isoline", {a, b});
    const int axis = e->axis;
    s.isoline_edges.push_back(std::move(*e));
    for (const int c : {h, n}) {  // the fixed coordinate in the end's reference chart
      const int own = s.corner_motion[c].k % 2 == 0 ? axis : 1 - axis;
      s.fixed_axes[m.origin(c)] |= static_cast<std::uint8_t>(1u << own);
    }
  }
}

}  // namespace igm
