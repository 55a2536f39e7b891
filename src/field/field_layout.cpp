#include "igm/field/field_layout.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>

#include <ClpSimplex.hpp>
#include <CoinPackedMatrix.hpp>

#include "igm/core/error.h"
#include "igm/core/union_find.h"
#include "igm/exact/intersect.h"
#include "igm/layout/polygon_pattern.h"
#include "igm/layout/quantize.h"
#include "igm/mesh/scale.h"
#include "../core/parallel.h"
#include "motorcycle_internal.h"

namespace igm {

namespace {

using field_detail::FieldFrames;
using field_detail::TraceReuse;
using field_detail::trace_motorcycles_reusing;

std::string str(std::int64_t x) { return std::to_string(x); }

Point2q corner_q(int c) {
  if (c == 1) return {Rational(1), Rational(0)};
  if (c == 2) return {Rational(0), Rational(1)};
  return {Rational(0), Rational(0)};
}

// A trace point in the barycentric plane (w1, w2) of face f (it must lie in f's closure).
Point2q plane_point(const TriMesh& mesh, const TracePoint& q, int f) { return field_detail::point_in_face(mesh, q, f); }

struct ArcEnd {
  int node = -1;  // refined vertex
  int ray = -1;   // in the node's numbering
};

struct Arc {
  std::vector<int> vertices;
  ArcEnd start, end;
  int curve = -1;  // the traced curve it is a piece of (-1: a piece of a boundary loop)
};

// The layout under construction for one trace graph.
// One input face's triangulation problem (Builder::triangulate_face: the local points, the
// boundary and the chords in local ids) and its answer (triangles in local ids, or the error), kept
// from one round of build_field_layout to the next: a face whose problem is the same (most of them:
// a round changes a few curves) takes the answer without the exact predicates again.
struct FaceTriangulation {
  bool known = false;
  std::vector<Point2q> pos;
  std::vector<int> boundary;
  std::vector<std::vector<int>> chords;
  std::vector<std::array<int, 3>> triangles;
  std::string error;
};

class Builder {
 public:
  // `cache` (may be null): per input face, the last triangulation made (FaceTriangulation).
  Builder(const TriMesh& mesh, const std::vector<Vec3d>& positions, const FieldFrames& frames, const TraceGraph& g,
          std::vector<FaceTriangulation>* cache = nullptr, bool polygon_patterns = true)
      : mesh_(mesh), positions_(positions), frames_(frames), g_(g), cache_(cache), polygon_patterns_(polygon_patterns) {}

  // Builds everything; "" or the reason it failed. non_disk: a seed vertex per patch that is not
  // a disk (when that is the only problem).
  std::string build(SurfaceLayout& out, FieldLayoutStats& stats, std::vector<int>& seeds) {
    std::string stuck;
    for (int c = 0; c < static_cast<int>(g_.curves.size()); ++c) {
      const TraceCurve& cur = g_.curves[c];
      if (cur.end != CurveEnd::Bound && cur.end != CurveEnd::Stuck) continue;
      blame(c);
      if (stuck.empty())
        stuck = "curve " + str(c) + " ended without meeting another curve (" + to_string(cur.end) + ") at point " +
                str(cur.points.back());
    }
    if (!stuck.empty()) return stuck;
    if (std::string e = make_vertices(); !e.empty()) return e;
    if (std::string e = triangulate(); !e.empty()) return e;
    if (std::string e = make_arcs(); !e.empty()) return e;
    if (std::string e = make_patches(out, stats, seeds); !e.empty()) return e;
    return "";
  }

  // The rays whose curves made the layout fail: (start vertex, ray).
  const std::vector<std::pair<int, int>>& culprits() const { return culprits_; }

  // The input vertices at the patch corners whose angle was not a quarter or a half turn (a
  // refined vertex inside an input face or edge gives that element's vertices), ascending.
  std::vector<int> bad_angle_vertices() const {
    std::vector<int> out;
    for (int v : bad_angle_nodes_) {
      if (v < mesh_.num_vertices()) {
        out.push_back(v);
      } else if (static_cast<std::size_t>(v) < locations_.size()) {
        for (int u : locations_[v].v)
          if (u >= 0) out.push_back(u);
      }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  // Blames the curves that end on the boundary of one of `patches` (T-junctions and corners
  // made by a curve's end), the longest first, at most `limit` of them.
  void blame_patches(const SurfaceLayout& layout, const std::vector<int>& patches, int limit) {
    std::vector<char> node_on(layout.locations.size(), 0);
    for (int p : patches)
      for (const auto& side : layout.patches[p].sides)
        for (const ArcUse& u : side)
          for (int v : {layout.arcs[u.arc].vertices.front(), layout.arcs[u.arc].vertices.back()}) node_on[v] = 1;
    std::vector<std::pair<double, int>> cand;
    for (int c = 0; c < static_cast<int>(g_.curves.size()); ++c) {
      const TraceCurve& cur = g_.curves[c];
      if (cur.end != CurveEnd::Curve) continue;
      if (node_on[point_vertex_[cur.points.back()]]) cand.push_back({-cur.length, c});
    }
    std::sort(cand.begin(), cand.end());
    for (int k = 0; k < static_cast<int>(cand.size()) && k < limit; ++k) blame(cand[k].second);
  }

 private:
  void blame(int c) {
    const TraceCurve& cur = g_.curves[c];
    const TracePoint& q = g_.points[cur.points.front()];
    if (q.kind == TracePoint::Kind::Vertex && cur.ray_forward.front() >= 0)
      culprits_.push_back({q.element, cur.ray_forward.front()});
  }

  // ---- refined vertices ----
  std::string make_vertices() {
    const int nv = mesh_.num_vertices();
    point_vertex_.assign(g_.points.size(), -1);
    locations_.reserve(nv + g_.points.size());
    for (int v = 0; v < nv; ++v) locations_.push_back(SurfacePoint::vertex(v));
    for (std::size_t p = 0; p < g_.points.size(); ++p) {
      const TracePoint& q = g_.points[p];
      if (q.kind == TracePoint::Kind::Vertex) {
        point_vertex_[p] = q.element;
        continue;
      }
      point_vertex_[p] = static_cast<int>(locations_.size());
      if (q.kind == TracePoint::Kind::Edge) {
        locations_.push_back(lerp(SurfacePoint::vertex(mesh_.origin(q.element)), SurfacePoint::vertex(mesh_.target(q.element)), q.t));
        edge_points_[q.element].push_back(static_cast<int>(p));
      } else {
        const auto fv = mesh_.face_vertices(q.element);
        locations_.push_back(barycentric_point(SurfacePoint::vertex(fv[0]), SurfacePoint::vertex(fv[1]),
                                               SurfacePoint::vertex(fv[2]), q.w));
        face_points_[q.element].push_back(static_cast<int>(p));
      }
    }
    for (auto& [ce, pts] : edge_points_)
      std::sort(pts.begin(), pts.end(), [&](int a, int b) { return g_.points[a].t < g_.points[b].t; });
    return "";
  }

  // ---- per input face: the chords of its segments, the convex cells, their triangles ----
  std::string triangulate() {
    // Chords per face: maximal runs of a curve's segments inside one face (one straight piece
    // with the T-junctions on it).
    std::unordered_map<int, std::vector<std::vector<int>>> chords;
    for (const TraceCurve& cur : g_.curves) {
      const int ns = static_cast<int>(cur.segment_face.size());
      for (int i = 0; i < ns;) {
        const int f = cur.segment_face[i];
        int j = i;
        while (j < ns && cur.segment_face[j] == f) ++j;
        if (f >= 0) chords[f].emplace_back(cur.points.begin() + i, cur.points.begin() + j + 1);
        i = j;
      }
    }
    const int nf = mesh_.num_faces();
    // Busy faces: with a chord, a point inside, or a point on one of their edges.
    std::vector<char> busy(static_cast<std::size_t>(nf), 0);
    for (const auto& entry : chords) busy[entry.first] = 1;
    for (const auto& entry : face_points_) busy[entry.first] = 1;
    for (const auto& entry : edge_points_) {
      busy[TriMesh::face(entry.first)] = 1;
      if (const int t = mesh_.twin(entry.first); t >= 0) busy[TriMesh::face(t)] = 1;
    }
    // The busy faces are independent (each writes its own triangles and its own memo entry):
    // triangulated in parallel, then every face's triangles appended in face order, and the
    // first failure in face order reported (the same output for any thread count).
    std::vector<int> busy_faces;
    for (int f = 0; f < nf; ++f)
      if (busy[f]) busy_faces.push_back(f);
    struct FaceOut {
      std::vector<std::array<int, 3>> triangles;
      std::string error;
    };
    std::vector<FaceOut> done(busy_faces.size());
    const std::vector<std::vector<int>> none;
    parallel::for_each_index(static_cast<std::int64_t>(busy_faces.size()), 64, [&](std::int64_t i) {
      const int f = busy_faces[static_cast<std::size_t>(i)];
      const auto it = chords.find(f);
      done[i].error = triangulate_face(f, it != chords.end() ? it->second : none, done[i].triangles);
    });
    triangles_.reserve(triangles_.size() + nf + 2 * busy_faces.size());
    for (int f = 0, k = 0; f < nf; ++f) {
      if (!busy[f]) {
        triangles_.push_back(mesh_.face_vertices(f));
        continue;
      }
      FaceOut& o = done[k++];
      triangles_.insert(triangles_.end(), o.triangles.begin(), o.triangles.end());
      if (!o.error.empty()) return o.error;
      std::vector<std::array<int, 3>>().swap(o.triangles);
    }
    return "";
  }

  int canonical(int h) const {
    const int t = mesh_.twin(h);
    return t >= 0 && t < h ? t : h;
  }

  // Appends face f's triangles (refined ids) to `tris`; "" or why it failed. Reads the
  // builder's points and writes only `tris` and f's memo entry: safe in parallel over faces.
  std::string triangulate_face(int f, const std::vector<std::vector<int>>& face_chords,
                               std::vector<std::array<int, 3>>& tris) const {
    const auto fv = mesh_.face_vertices(f);
    // Local vertices: refined ids and plane positions.
    std::vector<int> rid;
    std::vector<Point2q> pos;
    std::unordered_map<int, int> local;  // refined id -> local
    auto add = [&](int refined, const Point2q& p) {
      auto [it, fresh] = local.emplace(refined, static_cast<int>(rid.size()));
      if (fresh) rid.push_back(refined), pos.push_back(p);
      return it->second;
    };
    std::vector<int> boundary;
    for (int i = 0; i < 3; ++i) {
      boundary.push_back(add(fv[i], corner_q(i)));
      const int h = 3 * f + i, ce = canonical(h);
      auto it = edge_points_.find(ce);
      if (it == edge_points_.end()) continue;
      std::vector<int> pts = it->second;
      if (ce != h) std::reverse(pts.begin(), pts.end());
      for (int p : pts) boundary.push_back(add(point_vertex_[p], plane_point(mesh_, g_.points[p], f)));
    }
    std::vector<std::vector<int>> pending;
    for (const auto& ch : face_chords) {
      std::vector<int> lc;
      for (int p : ch) lc.push_back(add(point_vertex_[p], plane_point(mesh_, g_.points[p], f)));
      pending.push_back(std::move(lc));
    }
    FaceTriangulation* memo = cache_ && static_cast<int>(cache_->size()) > f ? &(*cache_)[f] : nullptr;
    if (memo && memo->known && memo->boundary == boundary && memo->chords == pending && same_points(memo->pos, pos)) {
      for (const auto& t : memo->triangles) tris.push_back({rid[t[0]], rid[t[1]], rid[t[2]]});
      return memo->error;
    }
    const std::size_t first_triangle = tris.size();
    std::string error = solve_face(f, pos, rid, boundary, pending, face_chords.size(), tris);
    if (memo) {
      memo->known = true;
      memo->pos = pos;
      memo->boundary = boundary;
      memo->chords = std::move(pending);
      memo->triangles.clear();
      for (std::size_t k = first_triangle; k < tris.size(); ++k) {
        std::array<int, 3> t{};
        for (int i = 0; i < 3; ++i) t[i] = local.at(tris[k][i]);
        memo->triangles.push_back(t);
      }
      memo->error = error;
    }
    return error;
  }

  static bool same_points(const std::vector<Point2q>& a, const std::vector<Point2q>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (!(a[i].x == b[i].x) || !(a[i].y == b[i].y)) return false;
    return true;
  }

  // The cells of face f cut by its chords, triangulated (appended to tris in refined ids).
  std::string solve_face(int f, const std::vector<Point2q>& pos, const std::vector<int>& rid, const std::vector<int>& boundary,
                         std::vector<std::vector<int>> pending, std::size_t num_chords,
                         std::vector<std::array<int, 3>>& tris) const {
    std::vector<std::vector<int>> cells{boundary};
    // Curves that end at one point inside the face, none passing through it: two of them merged
    // head-on there (they run on from it in opposite directions) and are one chord through it
    // (any others then end on that chord). The pair joined is the straightest at the point.
    const int n_boundary_local = static_cast<int>(boundary.size());
    for (std::size_t guard = 0; guard <= pending.size(); ++guard) {
      std::map<int, std::vector<std::pair<std::size_t, int>>> ends;  // point -> (chord, 0 front / 1 back)
      std::set<int> through;
      for (std::size_t a = 0; a < pending.size(); ++a) {
        ends[pending[a].front()].push_back({a, 0});
        ends[pending[a].back()].push_back({a, 1});
        for (std::size_t k = 1; k + 1 < pending[a].size(); ++k) through.insert(pending[a][k]);
      }
      bool joined = false;
      for (const auto& entry : ends) {
        const int x = entry.first;  // a plain local: lambdas below capture it (clang 14)
        const auto& list = entry.second;
        if (x < n_boundary_local || list.size() < 2 || through.count(x)) continue;
        // The straightest pair: the most negative dot product of the two directions leaving x.
        auto away = [&](const std::pair<std::size_t, int>& e) {
          const auto& ch = pending[e.first];
          const int y = e.second == 0 ? ch[1] : ch[ch.size() - 2];
          return std::array<double, 2>{to_double(pos[y].x - pos[x].x), to_double(pos[y].y - pos[x].y)};
        };
        std::size_t best_a = 0, best_b = 1;
        double best = 2;
        for (std::size_t p = 0; p < list.size(); ++p)
          for (std::size_t q = p + 1; q < list.size(); ++q) {
            if (list[p].first == list[q].first) continue;
            const auto da = away(list[p]), db = away(list[q]);
            const double la = std::sqrt(da[0] * da[0] + da[1] * da[1]), lb = std::sqrt(db[0] * db[0] + db[1] * db[1]);
            const double c = (da[0] * db[0] + da[1] * db[1]) / (la * lb);
            if (c < best) best = c, best_a = p, best_b = q;
          }
        if (best > 1) continue;
        const auto ea = list[best_a], eb = list[best_b];
        std::vector<int> J(pending[ea.first]);
        if (ea.second == 0) std::reverse(J.begin(), J.end());  // J ends at x
        std::vector<int> B(pending[eb.first]);
        if (eb.second == 1) std::reverse(B.begin(), B.end());  // B starts at x
        J.insert(J.end(), B.begin() + 1, B.end());
        const std::size_t lo = std::min(ea.first, eb.first), hi = std::max(ea.first, eb.first);
        pending[lo] = std::move(J);
        pending.erase(pending.begin() + static_cast<long>(hi));
        joined = true;
        break;
      }
      if (!joined) break;
    }
    // Insert chords whose two ends lie on one cell with the chord inside it, until none is left.
    for (std::size_t guard = 0; !pending.empty() && guard <= num_chords; ++guard) {
      bool progress = false;
      for (std::size_t k = 0; k < pending.size();) {
        if (insert_chord(cells, pending[k], pos)) {
          pending.erase(pending.begin() + static_cast<long>(k));
          progress = true;
        } else {
          ++k;
        }
      }
      if (!progress) break;
    }
    if (!pending.empty()) {
      return "face " + str(f) + ": curve pieces that do not cut it into cells";
    }
    for (const auto& cell : cells)
      if (!clip_cell(cell, pos, rid, tris)) return "face " + str(f) + ": a cell that cannot be triangulated";
    return "";
  }

  // Whether the polyline `chord` (local ids, ends on the cell's boundary) runs inside simple cell
  // `cell` (counter-clockwise): it leaves its first end into the cell's angle there, enters its
  // last end from inside the angle there, and crosses no edge of the cell. Exact.
  static bool chord_inside(const std::vector<int>& cell, std::size_t i, std::size_t j, const std::vector<int>& chord,
                           const std::vector<Point2q>& pos) {
    const std::size_t n = cell.size();
    auto into = [&](std::size_t at, int toward) {  // the segment from cell[at] to `toward` enters the cell
      const Point2q &p = pos[cell[(at + n - 1) % n]], &u = pos[cell[at]], &q = pos[cell[(at + 1) % n]], &x = pos[toward];
      const Sign in_prev = orient2d(p, u, x), in_next = orient2d(u, q, x);
      if (orient2d(p, u, q) != Sign::Negative) return in_prev == Sign::Positive && in_next == Sign::Positive;
      return in_prev == Sign::Positive || in_next == Sign::Positive;  // a reflex corner
    };
    if (!into(i, chord[1]) || !into(j, chord[chord.size() - 2])) return false;
    for (std::size_t k = 0; k + 1 < chord.size(); ++k)
      for (std::size_t e = 0; e < n; ++e) {
        const int a = cell[e], b = cell[(e + 1) % n];
        const SegmentRelation rel = classify(pos[chord[k]], pos[chord[k + 1]], pos[a], pos[b]);
        if (rel == SegmentRelation::Disjoint) continue;
        if (rel != SegmentRelation::Touching) return false;
        // Touching only at the chord's own ends on the boundary.
        const bool at_end = (k == 0 && (a == chord[0] || b == chord[0])) ||
                            (k + 2 == chord.size() && (a == chord.back() || b == chord.back()));
        if (!at_end) return false;
      }
    return true;
  }

  static bool insert_chord(std::vector<std::vector<int>>& cells, const std::vector<int>& chord,
                           const std::vector<Point2q>& pos) {
    const int u = chord.front(), w = chord.back();
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const auto& cell = cells[c];
      const std::size_t n = cell.size();
      for (std::size_t i = 0; i < n; ++i) {
        if (cell[i] != u) continue;
        for (std::size_t j = 0; j < n; ++j) {
          if (cell[j] != w || j == i || !chord_inside(cell, i, j, chord, pos)) continue;
          std::vector<int> a, b;
          for (std::size_t k = i;; k = (k + 1) % n) {
            a.push_back(cell[k]);
            if (k == j) break;
          }
          for (std::size_t k = chord.size() - 2; k >= 1; --k) a.push_back(chord[k]);
          for (std::size_t k = j;; k = (k + 1) % n) {
            b.push_back(cell[k]);
            if (k == i) break;
          }
          for (std::size_t k = 1; k + 1 < chord.size(); ++k) b.push_back(chord[k]);
          cells[c] = std::move(a);
          cells.push_back(std::move(b));
          return true;
        }
      }
    }
    return false;
  }

  // Triangulates a simple cell (counter-clockwise; collinear vertices and, where curves were
  // merged or snapped, slightly reflex corners allowed) by clipping ears: strictly convex corners
  // whose triangle holds no other vertex of the cell (exact).
  static bool clip_cell(std::vector<int> cell, const std::vector<Point2q>& pos, const std::vector<int>& rid,
                        std::vector<std::array<int, 3>>& tris) {
    for (std::size_t guard = 0; cell.size() > 3 && guard < 4 * pos.size() + 8; ++guard) {
      const std::size_t n = cell.size();
      bool clipped = false;
      for (std::size_t i = 0; i < n && !clipped; ++i) {
        const int a = cell[(i + n - 1) % n], b = cell[i], c = cell[(i + 1) % n];
        if (orient2d(pos[a], pos[b], pos[c]) != Sign::Positive) continue;
        bool clear = true;
        for (std::size_t k = 0; k < n && clear; ++k) {
          const int x = cell[k];
          if (x == a || x == b || x == c) continue;
          // In the closed triangle: on the cut or inside.
          clear = !(orient2d(pos[a], pos[b], pos[x]) != Sign::Negative && orient2d(pos[b], pos[c], pos[x]) != Sign::Negative &&
                    orient2d(pos[c], pos[a], pos[x]) != Sign::Negative);
        }
        if (!clear) continue;
        tris.push_back({rid[a], rid[b], rid[c]});
        cell.erase(cell.begin() + static_cast<long>(i));
        clipped = true;
      }
      if (!clipped) return false;
    }
    if (cell.size() != 3 || orient2d(pos[cell[0]], pos[cell[1]], pos[cell[2]]) != Sign::Positive) return false;
    tris.push_back({rid[cell[0]], rid[cell[1]], rid[cell[2]]});
    return true;
  }

  // ---- arcs ----
  int boundary_direction(int ce) const {
    const int f = TriMesh::face(ce);
    return frames_.nearest_direction(f, frames_.edge_vector(ce));
  }
  // A ray of a curve at trace point p in the node numbering used for arcs: boundary edge points
  // become linear (0 ahead along the boundary, 1 inwards, 2 behind).
  int node_ray(int p, int ray) const {
    const TracePoint& q = g_.points[p];
    if (ray < 0) return ray;
    if (q.kind == TracePoint::Kind::Edge && mesh_.twin(q.element) < 0) return ((ray - boundary_direction(q.element)) % 4 + 4) % 4;
    return ray;
  }

  std::string make_arcs() {
    const int nv = static_cast<int>(locations_.size());
    // from_triangles throws for a non-manifold edge; the checks after it are the layout's own.
    refined_ = TriMesh::from_triangles(nv, triangles_, /*allow_boundary=*/true);
    // The half-edges leaving each vertex, in increasing order (a counting sort by origin).
    const int nh = refined_.num_halfedges();
    out_start_.assign(static_cast<std::size_t>(nv) + 1, 0);
    for (int h = 0; h < nh; ++h) ++out_start_[refined_.origin(h) + 1];
    for (int v = 0; v < nv; ++v) out_start_[v + 1] += out_start_[v];
    out_.resize(nh);
    {
      std::vector<int> fill(out_start_.begin(), out_start_.end() - 1);
      for (int h = 0; h < nh; ++h) out_[fill[refined_.origin(h)]++] = h;
    }
    arc_of_he_.assign(nh, -1);
    // Nodes: curve ends, and boundary vertices whose angle is not straight.
    node_rays_.assign(nv, 0);
    node_cyclic_.assign(nv, 1);
    is_node_.assign(nv, 0);
    for (const TraceCurve& cur : g_.curves)
      for (int p : {cur.points.front(), cur.points.back()}) mark_node(p);
    for (int v = 0; v < mesh_.num_vertices(); ++v) {
      if (g_.valence[v] < 0) continue;
      const int h = mesh_.vertex_halfedge(v);
      const bool boundary = h >= 0 && mesh_.twin(h) < 0;
      if (boundary && g_.valence[v] != 2) {
        is_node_[v] = 1;
        node_rays_[v] = g_.valence[v] + 1;
        node_cyclic_[v] = 0;
      }
    }
    // Curves cut at their nodes.
    for (int ci = 0; ci < static_cast<int>(g_.curves.size()); ++ci) {
      const TraceCurve& cur = g_.curves[ci];
      const int n = static_cast<int>(cur.points.size());
      int start = 0;
      for (int i = 1; i < n; ++i) {
        const int v = point_vertex_[cur.points[i]];
        if (!is_node_[v] && i + 1 < n) continue;
        Arc a;
        for (int k = start; k <= i; ++k) a.vertices.push_back(point_vertex_[cur.points[k]]);
        a.start = {point_vertex_[cur.points[start]], node_ray(cur.points[start], cur.ray_forward[start])};
        a.end = {v, node_ray(cur.points[i], cur.ray_back[i])};
        a.curve = ci;
        arcs_.push_back(std::move(a));
        start = i;
      }
    }
    // Boundary loops cut at their nodes (a loop without any gets its first vertex as one).
    std::vector<char> seen(refined_.num_halfedges(), 0);
    for (int h0 = 0; h0 < refined_.num_halfedges(); ++h0) {
      if (refined_.twin(h0) >= 0 || seen[h0]) continue;
      std::vector<int> loop;  // boundary half-edges in order
      for (int h = h0, guard = 0; guard <= refined_.num_halfedges(); ++guard) {
        seen[h] = 1;
        loop.push_back(h);
        // The next boundary half-edge leaves target(h): rotate around it.
        int x = TriMesh::next(h);
        for (int r = 0; r <= refined_.num_halfedges() && refined_.twin(x) >= 0; ++r) x = TriMesh::next(refined_.twin(x));
        if (x == h0) break;
        h = x;
      }
      std::size_t first = loop.size();
      for (std::size_t k = 0; k < loop.size() && first == loop.size(); ++k)
        if (is_node_[refined_.origin(loop[k])]) first = k;
      if (first == loop.size()) {
        first = 0;
        const int v = refined_.origin(loop[0]);
        is_node_[v] = 1;
        node_rays_[v] = 3;
        node_cyclic_[v] = 0;
      }
      std::rotate(loop.begin(), loop.begin() + static_cast<long>(first), loop.end());
      Arc a;
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const int h = loop[k];
        if (a.vertices.empty()) {
          a.vertices.push_back(refined_.origin(h));
          a.start = {refined_.origin(h), 0};
        }
        const int t = refined_.target(h);
        a.vertices.push_back(t);
        if (is_node_[t]) {
          a.end = {t, node_rays_[t] - 1};
          arcs_.push_back(std::move(a));
          a = Arc{};
        }
      }
    }
    // Every refined edge on at most one arc.
    for (int a = 0; a < static_cast<int>(arcs_.size()); ++a) {
      const auto& vs = arcs_[a].vertices;
      for (std::size_t k = 0; k + 1 < vs.size(); ++k) {
        const int h = halfedge(vs[k], vs[k + 1]);
        const int hb = halfedge(vs[k + 1], vs[k]);
        if (h < 0 && hb < 0) return "arc " + str(a) + ": consecutive vertices not joined by an edge";
        // from_triangles made at most one half-edge each way: these are the edge's half-edges.
        if ((h >= 0 && arc_of_he_[h] >= 0) || (hb >= 0 && arc_of_he_[hb] >= 0)) return "arc " + str(a) + ": an edge on two arcs";
        if (h >= 0) arc_of_he_[h] = a;
        if (hb >= 0) arc_of_he_[hb] = a;
      }
    }
    return "";
  }

  void mark_node(int p) {
    const int v = point_vertex_[p];
    is_node_[v] = 1;
    node_rays_[v] = g_.ray_count[p];
    node_cyclic_[v] = g_.ray_cyclic[p];
    const TracePoint& q = g_.points[p];
    if (q.kind == TracePoint::Kind::Edge && mesh_.twin(q.element) < 0) node_rays_[v] = 3;
  }

  // The refined half-edge from a to b, or -1 (works across the boundary, unlike a rotation).
  int halfedge(int a, int b) const {
    for (int i = out_start_[a]; i < out_start_[a + 1]; ++i)
      if (refined_.target(out_[i]) == b) return out_[i];
    return -1;
  }

  // ---- patches ----
  std::string make_patches(SurfaceLayout& out, FieldLayoutStats& stats, std::vector<int>& seeds) {
    const int nt = refined_.num_faces();
    auto on_arc = [&](int h) {
      return arc_of_he_[h] >= 0;
    };
    std::vector<int> patch(nt, -1);
    int np = 0;
    for (int t0 = 0; t0 < nt; ++t0) {
      if (patch[t0] >= 0) continue;
      std::vector<int> stack{t0};
      patch[t0] = np;
      while (!stack.empty()) {
        const int t = stack.back();
        stack.pop_back();
        for (int i = 0; i < 3; ++i) {
          const int h = 3 * t + i, tw = refined_.twin(h);
          if (tw < 0 || on_arc(h)) continue;
          const int u = TriMesh::face(tw);
          if (patch[u] < 0) patch[u] = np, stack.push_back(u);
        }
      }
      ++np;
    }
    std::vector<std::vector<int>> tris(np);
    for (int t = 0; t < nt; ++t) tris[patch[t]].push_back(t);
    std::vector<LayoutPatch> patches(np);
    std::string first_problem;
    int non_disk = 0, bad_corners = 0;
    std::vector<PolygonPatch> polygons;  // disks with 3, 5 or 6 corners: the k-quad pattern
    for (int p = 0; p < np; ++p) {
      std::string problem = patch_sides(p, tris[p], patch, on_arc, patches[p]);
      if (problem.empty()) continue;
      if (problem[0] == 'K') {
        polygons.push_back({p, std::move(polygon_sides_), std::move(polygon_turns_)});
        continue;
      }
      if (problem[0] == 'N') {
        ++non_disk;
        // A seed: the smallest input vertex inside the patch, away from every arc.
        int best = -1;
        for (int t : tris[p])
          for (int v : refined_.face_vertices(t))
            if (v < mesh_.num_vertices() && !is_node_[v] && !vertex_on_arc(v) && (best < 0 || v < best)) best = v;
        // None (a band one triangle wide between two curves, as between two creases): the
        // smallest input vertex of the patch that is not a node; its free rays cross the band.
        if (best < 0)
          for (int t : tris[p])
            for (int v : refined_.face_vertices(t))
              if (v < mesh_.num_vertices() && !is_node_[v] && (best < 0 || v < best)) best = v;
        if (best >= 0) seeds.push_back(best);
      } else {
        ++bad_corners;
      }
      if (first_problem.empty()) first_problem = "patch " + str(p) + ": " + problem.substr(2);
    }
    stats.non_disk_patches = non_disk;
    stats.bad_corner_patches = bad_corners;
    stats.patches = np;
    stats.arcs = static_cast<int>(arcs_.size());
    stats.nodes = static_cast<int>(std::count(is_node_.begin(), is_node_.end(), 1));
    stats.refined_vertices = static_cast<int>(locations_.size());
    stats.refined_triangles = nt;
    if (!first_problem.empty()) return first_problem;
    // The layout.
    out.num_input_vertices = mesh_.num_vertices();
    out.locations = std::move(locations_);
    out.positions.resize(out.locations.size());
    std::vector<Vec3d> input_positions = positions_;
    for (std::size_t v = 0; v < out.locations.size(); ++v) out.positions[v] = evaluate(out.locations[v], input_positions);
    out.triangles = triangles_;
    out.triangle_patch = patch;
    out.arcs.clear();
    for (const Arc& a : arcs_) {
      LayoutArc la;
      la.vertices = a.vertices;
      const int h = halfedge(a.vertices[0], a.vertices[1]);
      const int hb = halfedge(a.vertices[1], a.vertices[0]);
      la.patch[0] = h >= 0 ? patch[TriMesh::face(h)] : -1;
      la.patch[1] = hb >= 0 ? patch[TriMesh::face(hb)] : -1;
      out.arcs.push_back(std::move(la));
    }
    out.patches = std::move(patches);
    if (!polygons.empty()) {  // only with polygon_patterns_ (patch_sides)
      PolygonPatternStats ps;
      const std::string e = fill_polygon_patches(out, polygons, {}, &ps);
      stats.pattern_patches = ps.patterns;
      stats.reflex_cuts = ps.reflex_cuts;
      stats.pattern_vertices = ps.added_vertices;
      stats.patches = static_cast<int>(out.patches.size());
      stats.refined_vertices = static_cast<int>(out.locations.size());
      stats.refined_triangles = static_cast<int>(out.triangles.size());
      if (!e.empty()) {
        stats.bad_corner_patches = static_cast<int>(polygons.size());
        bad_angle_nodes_.insert(bad_angle_nodes_.end(), polygon_reflex_.begin(), polygon_reflex_.end());
        return "the k-quad pattern or reflex cut: " + e;
      }
    }
    int tj = 0;
    for (std::size_t p = 0; p < g_.points.size(); ++p)
      if (g_.points[p].kind != TracePoint::Kind::Vertex && is_node_[point_vertex_[p]]) ++tj;
    stats.t_junctions = tj;
    return "";
  }

  bool vertex_on_arc(int v) const {
    const int h0 = refined_.vertex_halfedge(v);
    if (h0 < 0) return false;
    if (refined_.twin(h0) < 0) return true;
    int h = h0;
    for (int guard = 0; guard <= refined_.num_halfedges(); ++guard) {
      if (arc_of_he_[h] >= 0) return true;
      h = refined_.next_around_origin(h);
      if (h < 0 || h == h0) break;
    }
    return false;
  }

  // The sides of patch p, or "N ..." (not a disk) / "C ..." (corners) with the reason.
  template <class OnArc>
  std::string patch_sides(int p, const std::vector<int>& tris, const std::vector<int>& patch, const OnArc& on_arc,
                          LayoutPatch& out) {
    // Boundary half-edges of the patch (the patch on their left).
    std::vector<int> bnd;
    for (int t : tris)
      for (int i = 0; i < 3; ++i) {
        const int h = 3 * t + i;
        if (refined_.twin(h) < 0 || on_arc(h)) bnd.push_back(h);
      }
    if (bnd.empty()) return "N: it has no boundary (a closed surface without curves)";
    // Euler characteristic of the patch cut along its boundary: wedges - edges + faces.
    UnionFind wedges(static_cast<int>(3 * tris.size()));
    // Per half-edge of the patch (its origin's corner): the local corner id. Only the patch's own
    // half-edges are read (across a non-arc edge is the same patch).
    std::vector<int>& corner_index = he_scratch_;
    corner_index.resize(static_cast<std::size_t>(refined_.num_halfedges()));
    for (std::size_t k = 0; k < tris.size(); ++k)
      for (int i = 0; i < 3; ++i) corner_index[3 * tris[k] + i] = static_cast<int>(3 * k + i);
    for (int t : tris)
      for (int i = 0; i < 3; ++i) {
        const int h = 3 * t + i, tw = refined_.twin(h);
        if (tw < 0 || on_arc(h)) continue;
        // Across h: corner at origin(h) in t joins the corner at origin(h) = target(tw) in tw's face.
        wedges.unite(corner_index[h], corner_index[TriMesh::next(tw)]);
        wedges.unite(corner_index[TriMesh::next(h)], corner_index[tw]);
      }
    std::int64_t V = 0;
    for (int k = 0; k < static_cast<int>(3 * tris.size()); ++k)
      if (wedges.find(k) == k) ++V;
    const std::int64_t F = static_cast<std::int64_t>(tris.size()), B = static_cast<std::int64_t>(bnd.size());
    const std::int64_t E = (3 * F + B) / 2;
    // Loops of boundary half-edges.
    // bnd's half-edges: the patch's own with no twin or on an arc; their index in bnd.
    std::vector<int>& bnd_index = he_scratch_;  // corner_index is not read below
    for (std::size_t k = 0; k < bnd.size(); ++k) bnd_index[bnd[k]] = static_cast<int>(k);
    auto in_bnd = [&](int x) { return patch[TriMesh::face(x)] == p && (refined_.twin(x) < 0 || on_arc(x)); };
    std::vector<int> next(bnd.size(), -1);
    for (std::size_t k = 0; k < bnd.size(); ++k) {
      int x = TriMesh::next(bnd[k]);
      for (int r = 0; r <= refined_.num_halfedges() && !in_bnd(x); ++r) {
        const int tw = refined_.twin(x);
        if (tw < 0) break;
        x = TriMesh::next(tw);
      }
      if (!in_bnd(x)) return "N: its boundary does not close";
      next[k] = bnd_index[x];
    }
    int loops = 0;
    std::vector<char> seen(bnd.size(), 0);
    for (std::size_t k = 0; k < bnd.size(); ++k) {
      if (seen[k]) continue;
      ++loops;
      for (int x = static_cast<int>(k); !seen[x]; x = next[x]) seen[x] = 1;
    }
    if (V - E + F != 1 || loops != 1)
      return "N: not a disk (Euler characteristic " + str(V - E + F) + ", " + str(loops) + " boundary loops)";
    // The loop as arc uses, from a node.
    std::vector<int> loop;
    int k0 = -1;
    for (std::size_t k = 0; k < bnd.size() && k0 < 0; ++k)
      if (is_node_[refined_.origin(bnd[k])]) k0 = static_cast<int>(k);
    if (k0 < 0) return "C: no node on its boundary";
    for (int x = k0;;) {
      loop.push_back(bnd[x]);
      x = next[x];
      if (x == k0) break;
    }
    std::vector<ArcUse> uses;
    for (std::size_t k = 0; k < loop.size();) {
      const int h = loop[k];
      const int a = arc_of_he_[h];
      if (a < 0) throw Error(ErrorKind::Internal, "field layout: a patch side off every arc");
      const auto& vs = arcs_[a].vertices;
      const bool forward = vs.size() >= 2 && vs[0] == refined_.origin(h) && vs[1] == refined_.target(h) &&
                           !(vs.front() == vs.back() && vs.size() == 2 && false);
      const std::size_t len = vs.size() - 1;
      // The use must run over the whole arc.
      for (std::size_t i = 0; i < len; ++i) {
        if (k + i >= loop.size()) return "C: the boundary ends inside an arc";
        const int x = loop[k + i];
        const int e0 = forward ? vs[i] : vs[len - i], e1 = forward ? vs[i + 1] : vs[len - i - 1];
        if (refined_.origin(x) != e0 || refined_.target(x) != e1) return "C: the boundary leaves arc " + str(a);
      }
      uses.push_back({a, forward});
      k += len;
    }
    // Quarter turns at each node between consecutive uses.
    const int nu = static_cast<int>(uses.size());
    std::vector<int> corners, turns, reflex_nodes;
    for (int k = 0; k < nu; ++k) {
      const ArcUse& in = uses[k];
      const ArcUse& outu = uses[(k + 1) % nu];
      const ArcEnd& ea = in.forward ? arcs_[in.arc].end : arcs_[in.arc].start;
      const ArcEnd& eb = outu.forward ? arcs_[outu.arc].start : arcs_[outu.arc].end;
      if (ea.node != eb.node) return "C: consecutive arcs do not meet at a node";
      const int n = node_rays_[ea.node];
      if (ea.ray < 0 || eb.ray < 0 || n <= 0) return "C: an arc end without a direction at vertex " + str(ea.node);
      int q = ea.ray - eb.ray;
      if (node_cyclic_[ea.node]) q = ((q % n) + n) % n;
      // The boundary comes back along the arc it arrived by (the node's only arc on this side: a
      // slit into the patch): the whole angle around the node.
      if (q == 0 && in.arc == outu.arc && in.forward != outu.forward && node_cyclic_[ea.node]) q = n;
      if (q == 0) {
        // Two arcs by one ray: the one that arrived there is to blame.
        const Arc& aa = arcs_[in.arc];
        const Arc& ab = arcs_[outu.arc];
        const bool a_arrives = in.forward ? true : false;   // arc `in` ends at the node when used forward
        const bool b_arrives = outu.forward ? false : true;  // arc `out` ends at the node when used backward
        if (a_arrives && aa.curve >= 0) blame(aa.curve);
        else if (b_arrives && ab.curve >= 0) blame(ab.curve);
        else if (aa.curve >= 0) blame(aa.curve);
      }
      if (q == 1 || (q == 3 && polygon_patterns_)) {
        corners.push_back((k + 1) % nu);
        turns.push_back(q);
        if (q == 3) reflex_nodes.push_back(ea.node);
      } else if (q != 2) {
        bad_angle_nodes_.push_back(ea.node);
        return "C: an angle of " + str(q) + " quarter turns at vertex " + str(ea.node);
      }
    }
    if (reflex_nodes.size() > 1) {
      bad_angle_nodes_.insert(bad_angle_nodes_.end(), reflex_nodes.begin(), reflex_nodes.end());
      return "C: an angle of 3 quarter turns at vertex " + str(reflex_nodes.front()) + " (and " +
             str(static_cast<std::int64_t>(reflex_nodes.size()) - 1) + " more)";
    }
    if (corners.size() != 4 || !reflex_nodes.empty()) {
      const int k = static_cast<int>(corners.size());
      if (!polygon_patterns_ || (reflex_nodes.empty() && (k < 3 || k > 6))) return "C: " + str(k) + " corners";
      // A k-gon, or a polygon with one reflex corner: its sides for the pattern or the cut
      // (layout/polygon_pattern.h), made once every patch is known.
      polygon_sides_.assign(static_cast<std::size_t>(k), {});
      for (int s = 0; s < k; ++s)
        for (int i = corners[s]; i != corners[(s + 1) % k]; i = (i + 1) % nu) polygon_sides_[s].push_back(uses[i]);
      polygon_turns_ = turns;
      polygon_reflex_.insert(polygon_reflex_.end(), reflex_nodes.begin(), reflex_nodes.end());
      return "K: " + str(k) + " corners";
    }
    for (int s = 0; s < 4; ++s) {
      out.sides[s].clear();
      for (int k = corners[s]; k != corners[(s + 1) % 4]; k = (k + 1) % nu) out.sides[s].push_back(uses[k]);
    }
    return "";
  }

  const TriMesh& mesh_;
  const std::vector<Vec3d>& positions_;
  const FieldFrames& frames_;
  const TraceGraph& g_;
  std::vector<int> point_vertex_;
  std::vector<SurfacePoint> locations_;
  std::map<int, std::vector<int>> edge_points_;  // canonical half-edge -> points by t
  std::map<int, std::vector<int>> face_points_;
  std::vector<std::array<int, 3>> triangles_;
  TriMesh refined_;
  std::vector<int> node_rays_;
  std::vector<char> node_cyclic_, is_node_;
  std::vector<Arc> arcs_;
  // patch_sides' answer for a disk of 3, 5 or 6 corners or with one reflex corner: its sides, the
  // turns at their first corners; and every such disk's reflex corner.
  std::vector<std::vector<ArcUse>> polygon_sides_;
  std::vector<int> polygon_turns_;
  std::vector<int> polygon_reflex_;
  std::vector<int> arc_of_he_;           // per refined half-edge: the arc on its edge, or -1
  std::vector<int> out_start_, out_;     // the refined half-edges leaving each vertex (CSR)
  std::vector<int> he_scratch_;          // patch_sides: per refined half-edge, a local index
  std::vector<FaceTriangulation>* cache_ = nullptr;
  bool polygon_patterns_ = true;
  std::vector<std::pair<int, int>> culprits_;
  std::vector<int> bad_angle_nodes_;  // patch_sides: the nodes of wrong angles met
};

// The patches whose side equations cannot all hold with arc lengths >= `minimum`: the rows with
// slack in the optimum of the elastic linear program (minimize the total slack of
// sum(side 0) - sum(side 2) = 0 and sum(side 1) - sum(side 3) = 0 over lengths >= minimum).
// Empty when the lengths can be chosen (the relaxation is feasible). Cost: one LP (Clp).
std::vector<int> contradicting_patches(const SurfaceLayout& L, const std::vector<int>& minimum, bool sides_at_least_one = false) {
  const int na = static_cast<int>(L.arcs.size()), np = static_cast<int>(L.patches.size());
  const int nrows = 2 * np + (sides_at_least_one ? 4 * np : 0), ncols = na + 2 * 2 * np;
  std::vector<int> rows, cols;
  std::vector<double> vals;
  for (int p = 0; p < np; ++p)
    for (int axis = 0; axis < 2; ++axis) {
      std::map<int, double> coef;
      for (const ArcUse& u : L.patches[p].sides[axis]) coef[u.arc] += 1;
      for (const ArcUse& u : L.patches[p].sides[axis + 2]) coef[u.arc] -= 1;
      const int r = 2 * p + axis;
      for (const auto& [a, c] : coef)
        if (c != 0) rows.push_back(r), cols.push_back(a), vals.push_back(c);
      rows.push_back(r), cols.push_back(na + 2 * r), vals.push_back(1);
      rows.push_back(r), cols.push_back(na + 2 * r + 1), vals.push_back(-1);
    }
  if (sides_at_least_one)
    for (int p = 0; p < np; ++p)
      for (int k = 0; k < 4; ++k) {
        std::map<int, double> coef;
        for (const ArcUse& u : L.patches[p].sides[k]) coef[u.arc] += 1;
        for (const auto& [a, c] : coef) rows.push_back(2 * np + 4 * p + k), cols.push_back(a), vals.push_back(c);
      }
  CoinPackedMatrix m(true, rows.data(), cols.data(), vals.data(), static_cast<CoinBigIndex>(vals.size()));
  m.setDimensions(nrows, ncols);
  std::vector<double> collb(ncols, 0), colub(ncols, 1e30), obj(ncols, 0), rowlb(nrows, 0), rowub(nrows, 0);
  for (int r = 2 * np; r < nrows; ++r) rowlb[r] = 1, rowub[r] = 1e30;
  for (int a = 0; a < na; ++a) collb[a] = minimum[a], obj[a] = 1e-6;
  for (int k = na; k < ncols; ++k) obj[k] = 1;
  ClpSimplex lp;
  lp.setLogLevel(0);
  lp.loadProblem(m, collb.data(), colub.data(), obj.data(), rowlb.data(), rowub.data());
  lp.primal();
  std::vector<int> out;
  if (!lp.isProvenOptimal()) return out;
  const double* x = lp.primalColumnSolution();
  for (int p = 0; p < np; ++p)
    for (int axis = 0; axis < 2; ++axis) {
      const int r = 2 * p + axis;
      if (x[na + 2 * r] + x[na + 2 * r + 1] > 1e-7) {
        out.push_back(p);
        break;
      }
    }
  return out;
}

// Whether vertex v, with the rays in `banned` left out, keeps every angle between consecutive
// traced rays at most two quarter turns (boundary rays 0 and k always count as traced).
bool keeps_small_angles(const TraceGraph& g, int v, const std::vector<std::pair<int, int>>& banned) {
  const int k = g.valence[v];
  if (k <= 0) return false;
  bool boundary = false;
  for (std::size_t p = 0; p < g.points.size(); ++p)
    if (g.points[p].kind == TracePoint::Kind::Vertex && g.points[p].element == v) boundary = !g.ray_cyclic[p];
  const int n = boundary ? k + 1 : k;
  std::vector<char> on(n, 1);
  for (const auto& [u, r] : banned)
    if (u == v && r >= 0 && r < n) on[r] = 0;
  if (boundary) on[0] = on[n - 1] = 1;
  std::vector<int> present;
  for (int r = 0; r < n; ++r)
    if (on[r]) present.push_back(r);
  if (present.empty()) return false;
  for (std::size_t i = 0; i + 1 < present.size(); ++i)
    if (present[i + 1] - present[i] > 2) return false;
  if (!boundary && present.front() + n - present.back() > 2) return false;
  return true;
}

}  // namespace

FieldLayoutResult build_field_layout(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                                     const std::vector<Vec3d>& face_direction, const FieldLayoutOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  if (static_cast<int>(positions.size()) != mesh.num_vertices() ||
      static_cast<int>(face_direction.size()) != mesh.num_faces())
    throw Error(ErrorKind::InvalidArgument, "build_field_layout: positions or face directions do not match the mesh");
  FieldLayoutResult r;
  const FieldFrames frames(mesh, scaled_positions(positions, unit_scale(positions)), face_direction);
  TraceOptions trace = options.trace;
  const int max_rounds = std::max(0, options.max_seed_rounds) + std::max(0, options.max_ban_rounds);
  TraceReuse reuse;  // the rounds differ in seeds and banned rays only
  std::vector<FaceTriangulation> triangulations(static_cast<std::size_t>(mesh.num_faces()));
  for (int round = 0; round <= max_rounds; ++round) {
    r.graph = trace_motorcycles_reusing(mesh, positions, face_direction, trace, frames, reuse);
    r.stats.trace = r.graph.stats;
    r.stats.rounds = round + 1;
    if (trace.stop_at_stuck_wall && !r.graph.stuck_walls.empty()) {
      r.failure = std::to_string(r.graph.stuck_walls.size()) + " feature walls could not be drawn (wall " +
                  std::to_string(r.graph.stuck_walls.front()) + ")";
      break;
    }
    std::vector<int> seeds;
    r.layout = SurfaceLayout{};
    r.stats.non_disk_patches = r.stats.bad_corner_patches = 0;
    r.contradicting_vertices.clear();
    r.bad_angle_vertices.clear();
    Builder b(mesh, positions, frames, r.graph, &triangulations, options.polygon_patterns);
    r.failure = b.build(r.layout, r.stats, seeds);
    r.bad_angle_vertices = b.bad_angle_vertices();
    if (r.failure.empty()) {
      // Lengths >= the minima must be able to satisfy every patch; where they cannot (a strip of
      // patches that would have to be longer than itself: spiralling curves), the curves ending on
      // the contradicting patches are left out and the graph traced again.
      const std::vector<int> bad = contradicting_patches(r.layout, minimum_arc_lengths(r.layout));
      if (bad.empty()) {
        r.ok = true;
        break;
      }
      r.stats.contradicting_patches = static_cast<int>(bad.size());
      r.failure = "the patches' side lengths contradict each other (" + std::to_string(bad.size()) + " patches, patch " +
                  std::to_string(bad.front()) + ")";
      b.blame_patches(r.layout, bad, 2);
      for (int p : bad)
        for (const auto& side : r.layout.patches[p].sides)
          for (const ArcUse& u : side)
            for (int v : r.layout.arcs[u.arc].vertices)
              if (v < mesh.num_vertices()) r.contradicting_vertices.push_back(v);
      std::sort(r.contradicting_vertices.begin(), r.contradicting_vertices.end());
      r.contradicting_vertices.erase(std::unique(r.contradicting_vertices.begin(), r.contradicting_vertices.end()),
                                     r.contradicting_vertices.end());
    }
    // Rays whose curves could not end well are left untraced, where their vertex keeps every
    // angle at most two quarter turns; then the graph is traced again.
    std::vector<std::pair<int, int>> bans;
    for (const auto& [v, k] : b.culprits()) {
      std::vector<std::pair<int, int>> trial = trace.banned_rays;
      trial.insert(trial.end(), bans.begin(), bans.end());
      trial.push_back({v, k});
      if (keeps_small_angles(r.graph, v, trial) && std::find(trial.begin(), trial.end() - 1, std::make_pair(v, k)) == trial.end() - 1)
        bans.push_back({v, k});
    }
    if (!bans.empty() && round < options.max_ban_rounds) {
      trace.banned_rays.insert(trace.banned_rays.end(), bans.begin(), bans.end());
      r.stats.banned_rays += static_cast<int>(bans.size());
      continue;
    }
    if (r.stats.bad_corner_patches > 0 || seeds.empty() || round >= options.max_seed_rounds) break;
    std::sort(seeds.begin(), seeds.end());
    seeds.erase(std::unique(seeds.begin(), seeds.end()), seeds.end());
    for (int s : seeds) trace.seeds.push_back(s);
    r.stats.seeds += static_cast<int>(seeds.size());
  }
  if (!r.ok) r.layout = SurfaceLayout{};
  r.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace igm
