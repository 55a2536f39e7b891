#include "igm/field/motorcycle.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <tuple>
#include <optional>
#include <queue>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "igm/core/error.h"
#include "igm/exact/intersect.h"
#include "igm/mesh/scale.h"
#include "motorcycle_internal.h"

namespace igm {

const char* to_string(CurveEnd end) {
  switch (end) {
    case CurveEnd::Curve: return "curve";
    case CurveEnd::Cone: return "cone";
    case CurveEnd::Boundary: return "boundary";
    case CurveEnd::Bound: return "bound";
    case CurveEnd::Stuck: return "stuck";
  }
  return "?";
}

namespace field_detail {

namespace {

double cross2(const Vec2d& a, const Vec2d& b) { return a.x * b.y - a.y * b.x; }
double dot2(const Vec2d& a, const Vec2d& b) { return a.x * b.x + a.y * b.y; }
Vec2d sub2(const Vec2d& a, const Vec2d& b) { return {a.x - b.x, a.y - b.y}; }
Vec3d sub3(const Vec3d& a, const Vec3d& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot3(const Vec3d& a, const Vec3d& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3d cross3(const Vec3d& a, const Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

}  // namespace

Vec2d rot90(const Vec2d& v, int k) {
  switch (((k % 4) + 4) % 4) {
    case 0: return v;
    case 1: return {-v.y, v.x};
    case 2: return {-v.x, -v.y};
    default: return {v.y, -v.x};
  }
}

FieldFrames::FieldFrames(const TriMesh& m, const std::vector<Vec3d>& positions, const std::vector<Vec3d>& face_direction)
    : mesh(m) {
  const int nf = mesh.num_faces();
  corner.resize(nf);
  dir.resize(nf);
  good.assign(nf, 0);
  origin.assign(nf, Vec3d{0, 0, 0});
  axis_x.assign(nf, Vec3d{1, 0, 0});
  axis_y.assign(nf, Vec3d{0, 1, 0});
  for (int f = 0; f < nf; ++f) {
    const auto fv = mesh.face_vertices(f);
    const Vec3d p0 = positions[fv[0]], e1 = sub3(positions[fv[1]], p0), e2 = sub3(positions[fv[2]], p0);
    const double l1 = std::sqrt(dot3(e1, e1));
    const Vec3d n = cross3(e1, e2);
    const double ln = std::sqrt(dot3(n, n));
    corner[f] = {Vec2d{0, 0}, Vec2d{0, 0}, Vec2d{0, 0}};
    dir[f] = {1, 0};
    if (!(l1 > 0) || !(ln > 0) || !std::isfinite(l1) || !std::isfinite(ln)) continue;
    const Vec3d x{e1.x / l1, e1.y / l1, e1.z / l1};
    const Vec3d nn{n.x / ln, n.y / ln, n.z / ln};
    const Vec3d y = cross3(nn, x);
    origin[f] = p0;
    axis_x[f] = x;
    axis_y[f] = y;
    corner[f][1] = {l1, 0};
    corner[f][2] = {dot3(e2, x), dot3(e2, y)};
    const Vec3d& d = face_direction[f];
    Vec2d u{dot3(d, x), dot3(d, y)};
    const double lu = std::sqrt(dot2(u, u));
    if (!(lu > 0) || !std::isfinite(lu) || !(corner[f][2].y > 0)) continue;
    dir[f] = {u.x / lu, u.y / lu};
    good[f] = 1;
  }
  shift.assign(mesh.num_halfedges(), 0);
  for (int h = 0; h < mesh.num_halfedges(); ++h) {
    const int t = mesh.twin(h);
    if (t < 0 || t < h) continue;
    const int f = TriMesh::face(h), g = TriMesh::face(t);
    if (!good[f] || !good[g]) continue;
    const int i = h % 3, j = t % 3;
    const Vec2d ef = sub2(corner[f][(i + 1) % 3], corner[f][i]);
    const Vec2d eg = sub2(corner[g][j], corner[g][(j + 1) % 3]);  // origin(h) -> target(h) in g
    // r: g-frame -> f-frame rotation, ef / eg as complex numbers.
    const double den = dot2(eg, eg);
    Vec2d r{(ef.x * eg.x + ef.y * eg.y) / den, (ef.y * eg.x - ef.x * eg.y) / den};
    const Vec2d ug{r.x * dir[g].x - r.y * dir[g].y, r.x * dir[g].y + r.y * dir[g].x};
    int best = 0;
    double best_dot = -2;
    for (int s = 0; s < 4; ++s) {
      const double d = dot2(ug, rot90(dir[f], s));
      if (d > best_dot) best_dot = d, best = s;
    }
    // direction j in f ~ r rot^(j - best) u_g: index j - best in g.
    shift[h] = (4 - best) % 4;
    shift[t] = best;
  }
}

Vec2d FieldFrames::direction(int f, int j) const { return rot90(dir[f], j); }

Vec2d FieldFrames::edge_vector(int h) const {
  const int f = TriMesh::face(h), i = h % 3;
  return sub2(corner[f][(i + 1) % 3], corner[f][i]);
}

VertexRays FieldFrames::vertex_rays(int v) const {
  VertexRays out;
  const int h0 = mesh.vertex_halfedge(v);
  if (h0 < 0) return out;
  // The fan, counter-clockwise; open fans start at the boundary half-edge leaving v.
  std::vector<int> fan;
  bool closed = false;
  for (int h = h0, guard = 0; guard <= mesh.num_halfedges(); ++guard) {
    fan.push_back(h);
    const int n = mesh.next_around_origin(h);
    if (n < 0) break;
    if (n == h0) {
      closed = true;
      break;
    }
    h = n;
  }
  for (int h : fan)
    if (!good[TriMesh::face(h)]) return out;  // a degenerate face: no rays (valence -1)
  out.boundary = !closed;
  struct Event {
    int sign;
    VertexRay ray;
  };
  std::vector<Event> events;
  const int nfan = static_cast<int>(fan.size());
  for (int i = 0; i < nfan; ++i) {
    const int h = fan[i], f = TriMesh::face(h), c = h % 3;
    const Vec2d A = sub2(corner[f][(c + 1) % 3], corner[f][c]);
    const Vec2d B = sub2(corner[f][(c + 2) % 3], corner[f][c]);
    // On an open fan the boundary-aligned directions at its two ends are the boundary rays.
    int skip_first = -1, skip_last = -1;
    if (out.boundary && i == 0) skip_first = nearest_direction(f, A);
    if (out.boundary && i == nfan - 1) skip_last = nearest_direction(f, B);
    int found[2] = {-1, -1}, nfound = 0;
    for (int j = 0; j < 4; ++j) {
      if (j == skip_first || j == skip_last) continue;
      const Vec2d w = direction(f, j);
      if (cross2(A, w) >= 0 && cross2(w, B) > 0 && nfound < 2) found[nfound++] = j;
    }
    if (nfound == 2 && cross2(direction(f, found[0]), direction(f, found[1])) < 0) std::swap(found[0], found[1]);
    for (int k = 0; k < nfound; ++k) events.push_back({+1, VertexRay{f, found[k], -1}});
    if (i == nfan - 1 && out.boundary) break;
    // The edge from v along B, shared with the next face of the fan.
    const int hn = fan[(i + 1) % nfan], g = TriMesh::face(hn);
    const int js = nearest_direction(f, B);
    const bool swept_f = cross2(direction(f, js), B) > 0;
    const int hp = TriMesh::prev(h);  // runs into v along B, in f
    const int jg = (js + shift[hp]) % 4;
    const bool sweeps_g = cross2(edge_vector(hn), direction(g, jg)) >= 0;
    if (!swept_f && !sweeps_g) events.push_back({+1, VertexRay{g, jg, hn}});
    if (swept_f && sweeps_g) events.push_back({-1, VertexRay{}});
  }
  // Cancel each negative crossing with an adjacent positive one (cyclically on a closed fan).
  for (std::size_t guard = 0; guard <= events.size(); ++guard) {
    const auto neg = std::find_if(events.begin(), events.end(), [](const Event& e) { return e.sign < 0; });
    if (neg == events.end()) break;
    const int n = static_cast<int>(events.size()), i = static_cast<int>(neg - events.begin());
    int partner = -1;
    const int before = closed ? (i + n - 1) % n : i - 1, after = closed ? (i + 1) % n : i + 1;
    if (before >= 0 && before != i && events[before].sign > 0) partner = before;
    else if (after < n && after != i && events[after].sign > 0) partner = after;
    if (partner < 0) return VertexRays{};  // no consistent set of rays
    events.erase(events.begin() + std::max(i, partner));
    events.erase(events.begin() + std::min(i, partner));
  }
  if (out.boundary) {
    const int f0 = TriMesh::face(fan.front()), fl = TriMesh::face(fan.back());
    out.rays.push_back(VertexRay{f0, nearest_direction(f0, edge_vector(fan.front())), fan.front()});
    for (const Event& e : events) out.rays.push_back(e.ray);
    const int hl = TriMesh::prev(fan.back());  // the boundary half-edge into v
    Vec2d back = edge_vector(hl);
    back = {-back.x, -back.y};
    out.rays.push_back(VertexRay{fl, nearest_direction(fl, back), -2});
    out.valence = static_cast<int>(events.size()) + 1;
  } else {
    for (const Event& e : events) out.rays.push_back(e.ray);
    out.valence = static_cast<int>(events.size());
  }
  return out;
}

int FieldFrames::nearest_direction(int f, const Vec2d& v) const {
  int best = 0;
  double best_dot = -1e300;
  for (int j = 0; j < 4; ++j) {
    const double d = dot2(direction(f, j), v);
    if (d > best_dot) best_dot = d, best = j;
  }
  return best;
}

std::optional<Point2q> point_in_face_if(const TriMesh& mesh, const TracePoint& q, int f) {
  std::array<Rational, 3> w{Rational(0), Rational(0), Rational(0)};
  switch (q.kind) {
    case TracePoint::Kind::Vertex: {
      const auto fv = mesh.face_vertices(f);
      for (int c = 0; c < 3; ++c)
        if (fv[c] == q.element) {
          w[c] = 1;
          return Point2q{w[1], w[2]};
        }
      return std::nullopt;
    }
    case TracePoint::Kind::Edge: {
      int h = q.element;
      Rational t = q.t;
      if (TriMesh::face(h) != f) {
        h = mesh.twin(h);
        t = 1 - t;
        if (h < 0 || TriMesh::face(h) != f) return std::nullopt;
      }
      w[h % 3] = 1 - t;
      w[(h % 3 + 1) % 3] = t;
      return Point2q{w[1], w[2]};
    }
    case TracePoint::Kind::Face:
      if (q.element != f) return std::nullopt;
      return Point2q{q.w[1], q.w[2]};
  }
  return std::nullopt;
}

Point2q point_in_face(const TriMesh& mesh, const TracePoint& q, int f) {
  if (std::optional<Point2q> p = point_in_face_if(mesh, q, f)) return std::move(*p);
  throw Error(ErrorKind::Internal, "trace: a point used in a face whose closure does not hold it", {f});
}

}  // namespace field_detail

namespace {

using field_detail::FieldFrames;
using field_detail::TraceReuse;
using field_detail::VertexRay;
using field_detail::VertexRays;

double cross2(const Vec2d& a, const Vec2d& b) { return a.x * b.y - a.y * b.x; }
double dot2(const Vec2d& a, const Vec2d& b) { return a.x * b.x + a.y * b.y; }
Vec2d sub2(const Vec2d& a, const Vec2d& b) { return {a.x - b.x, a.y - b.y}; }
Vec2d lerp2(const Vec2d& a, const Vec2d& b, double t) { return {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)}; }


bool same(const Point2q& a, const Point2q& b) { return a.x == b.x && a.y == b.y; }

// A segment of a curve inside a face, with its end points in the face's barycentric plane
// (coordinates (w1, w2) of face_vertices 1 and 2).
struct FaceSegment {
  int curve = -1, segment = -1;
  Point2q a, b;
  int dir = 0;  // the curve's field direction in the face
};

// A curve's walk along a mesh edge: parameter interval along the canonical half-edge.
struct EdgeWalk {
  int curve = -1, segment = -1;
  Rational t0, t1;  // t0 < t1
  int face = -1, dir = 0;  // the walk's direction: field direction `dir` of face `face`
};

struct Hit {  // a curve ending on the interior of another curve's segment
  int curve = -1, segment = -1, point = -1;
};

// Where a curve is: at a vertex about to leave by one of its rays, or inside a face that it
// entered through half-edge `he` (of that face) at local parameter `s` from origin(he).
struct Where {
  int vertex = -1, ray = -1;
  int face = -1, he = -1;
  Rational s;
  int dir = 0;     // in a face: the curve's field direction there
  int steer = -1;  // a vertex the curve heads straight for (taken into it), or -1: the field
};

// One step of a curve, decided in doubles from exact dyadic positions (the same in the solo
// pre-pass and in the motorcycle pass).
struct Advance {
  enum class Kind { Edge, Vertex, Walk, Slide, Stuck };
  Kind kind = Kind::Stuck;
  int he = -1;     // Edge: the half-edge of `face` it leaves by; Walk: the half-edge walked (v -> vertex);
                   // Slide: the entry half-edge, slid along from the entry point to `vertex`
  Rational t;      // Edge: dyadic parameter along he from origin(he), in (0,1)
  int vertex = -1;  // Vertex: the corner of `face` reached; Walk: the far end of the walked edge
  int face = -1, dir = 0;  // the segment's face and the curve's direction there (Walk: a face beside the edge)
  bool capture = false;    // Vertex reached by the capture rule (not by rounding)
  int alt_he = -1;         // Vertex: the edge exit to take instead when the vertex cannot be entered
  Rational alt_t;
};

enum class State { Active, Done };

struct Runner {
  Where where;
  State state = State::Done;
  int target = -1, target_ray = -1;  // a paired curve: the cone it connects to, by that ray
  int partner = -1;                  // the (not started) curve reserved for the other end, or -1
};

class Tracer {
 public:
  // `frames` (those of the scaled positions) and `reuse` (TraceReuse) may be null.
  Tracer(const TriMesh& mesh, const std::vector<Vec3d>& positions, const std::vector<Vec3d>& face_direction,
         const TraceOptions& options, const FieldFrames* frames = nullptr, TraceReuse* reuse = nullptr)
      : mesh_(mesh),
        scale_(unit_scale(positions)),
        positions_(scaled_positions(positions, scale_)),
        own_frames_(frames ? nullptr : std::make_unique<FieldFrames>(mesh, positions_, face_direction)),
        frames_(frames ? *frames : *own_frames_),
        options_(options),
        reuse_(reuse) {
    // Hostile coordinates (1e-300, 1e300): every length in units scaled by a power of two.
    options_.snap_length *= scale_;
    bits_ = options.parameter_bits;
    max_segments_ = options.max_segments > 0 ? options.max_segments : 2 * mesh.num_faces() + 64;
    const int nv = mesh.num_vertices();
    if (reuse_ && static_cast<int>(reuse_->rays.size()) == nv && static_cast<int>(reuse_->rays_done.size()) == nv) {
      rays_ = std::move(reuse_->rays);
      rays_done_ = std::move(reuse_->rays_done);
    } else {
      rays_.resize(nv);
      rays_done_.assign(nv, 0);
    }
    vertex_point_.assign(nv, -1);
    on_curve_vertex_.assign(nv, 0);
    traced_.assign(nv, 0);
    banned_.insert(options.banned_rays.begin(), options.banned_rays.end());
    double sum = 0;
    for (int h = 0; h < mesh.num_halfedges(); ++h) {
      const Vec3d a = positions[mesh.origin(h)], b = positions[mesh.target(h)];
      sum += std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
    }
    mean_edge_ = mesh.num_halfedges() > 0 ? sum / mesh.num_halfedges() : 0;
  }

  const VertexRays& rays(int v) {
    if (!rays_done_[v]) rays_[v] = frames_.vertex_rays(v), rays_done_[v] = 1;
    return rays_[v];
  }

  TraceGraph run(const std::vector<int>& seeds) {
    const auto t0 = std::chrono::steady_clock::now();
    TraceGraph& g = graph_;
    const int nv = mesh_.num_vertices();
    g.valence.assign(nv, -1);
    for (int v = 0; v < nv; ++v) g.valence[v] = rays(v).valence;
    // Per vertex, the rays to trace from it as a seed (bit k: ray k): every ray of a seed the
    // caller gives, the rays draw_wall asks for at a wall's end or turn.
    std::vector<unsigned char> seed(nv, 0);
    for (int s : seeds) {
      if (s < 0 || s >= nv) throw Error(ErrorKind::InvalidArgument, "trace seed out of range", {s});
      seed[s] = 0xFF;
    }
    for (int i = 0; i < static_cast<int>(options_.walls.size()); ++i) draw_wall(i, options_.walls[i], seed);
    if (options_.stop_at_stuck_wall && !g.stuck_walls.empty()) return finish(t0);
    auto wall_ray = [&](int v, int k) { return vertex_point_[v] >= 0 && used_ray(vertex_point_[v], k, -1); };
    // The starting rays: every ray of a cone or seed, the interior rays of a boundary corner.
    std::vector<std::pair<int, int>> starts;
    for (int v = 0; v < nv; ++v) {
      const VertexRays& r = rays(v);
      if (r.valence < 0) continue;
      const bool corner = r.boundary ? r.valence != 2 : r.valence != 4;
      if (!corner && !seed[v]) continue;
      traced_[v] = 1;
      if (r.boundary) ++g.stats.boundary_corners;
      else if (corner) ++g.stats.cones;
      const int first = r.boundary ? 1 : 0, last = r.valence - 1;
      // The free rays; of a seed, those it asks for (`seed`), or every free one where none of
      // those is free (a wall's end whose continuing ray is banned by an earlier round or taken by
      // another wall).
      std::vector<int> free, asked;
      for (int k = first; k <= last; ++k)
        if (!banned_.count({v, k}) && !wall_ray(v, k)) {
          free.push_back(k);
          if (corner || ((seed[v] >> k) & 1)) asked.push_back(k);
        }
      for (int k : asked.empty() ? free : asked) starts.push_back({v, k});
    }
    // Vertices with traced rays, hashed by position for the steering.
    steer_length_ = options_.snap_length > 0 ? options_.snap_length : options_.snap_distance * mean_edge_;
    if (steer_length_ > 0)
      for (int v = 0; v < nv; ++v)
        if (traced_[v]) {
          const Vec3d& X = positions_[v];
          const long i = static_cast<long>(std::floor(X.x / steer_length_)), j = static_cast<long>(std::floor(X.y / steer_length_)),
                     k = static_cast<long>(std::floor(X.z / steer_length_));
          traced_hash_[cell_key(i, j, k)].push_back(v);
          // The cells whose 27-cell neighbourhood holds v: maybe_steer looks no further elsewhere.
          for (long a = i - 1; a <= i + 1; ++a)
            for (long b = j - 1; b <= j + 1; ++b)
              for (long c = k - 1; c <= k + 1; ++c) near_cells_.insert(cell_key(a, b, c));
        }
    // Pairs of rays that trace one separatrix between two of those vertices.
    // Every ray traced alone: the vertex and ray it is taken into, and in how many steps. A ray
    // taken into another is the same separatrix: pairs are made greedily, mutual claims first,
    // then by fewest steps (ties: lower ray), each ray in at most one pair.
    struct Claim {
      int mutual, steps;
      std::pair<int, int> a, b;
    };
    std::map<std::pair<int, int>, std::pair<std::pair<int, int>, int>> reach;
    if (reuse_ && (reuse_->solo_traced != traced_ || static_cast<int>(reuse_->solo.size()) != nv)) {
      reuse_->solo_traced = traced_;
      reuse_->solo.assign(nv, {});
    }
    for (const auto& s : starts) {
      TraceReuse::Solo memo;
      const TraceReuse::Solo* known = nullptr;
      if (reuse_)
        for (const auto& [k, m] : reuse_->solo[s.first])
          if (k == s.second) known = &m;
      if (!known) {
        const int steers = g.stats.steers;
        if (const auto x = solo(s.first, s.second)) {
          memo.reached = true;
          memo.vertex = x->first.first;
          memo.ray = x->first.second;
          memo.steps = x->second;
        }
        memo.steers = g.stats.steers - steers;
        if (reuse_) reuse_->solo[s.first].push_back({s.second, memo});
        known = &memo;
      } else {
        g.stats.steers += known->steers;
      }
      if (known->reached) reach[s] = {{known->vertex, known->ray}, known->steps};
    }
    std::vector<Claim> claims;
    for (const auto& [a, bx] : reach) {
      const auto& b = bx.first;
      if (a == b || wall_ray(b.first, b.second)) continue;
      auto it = reach.find(b);
      const bool mutual = it != reach.end() && it->second.first == a;
      if (mutual && b < a) continue;  // listed once, from its lower ray
      claims.push_back({mutual ? 0 : 1, bx.second, a, b});
    }
    std::sort(claims.begin(), claims.end(), [](const Claim& x, const Claim& y) {
      return std::tie(x.mutual, x.steps, x.a, x.b) < std::tie(y.mutual, y.steps, y.a, y.b);
    });
    std::map<std::pair<int, int>, std::pair<int, int>> target_of;  // the tracing ray -> its far end
    std::set<std::pair<int, int>> in_pair;
    for (const Claim& cl : claims) {
      if (in_pair.count(cl.a) || in_pair.count(cl.b)) continue;
      target_of[cl.a] = cl.b;
      in_pair.insert(cl.a);
      in_pair.insert(cl.b);
    }
    for (const auto& st : starts) {
      if (in_pair.count(st) && !target_of.count(st)) continue;  // reserved: its partner traces it
      const int c = start_curve(st.first, st.second);
      auto it = target_of.find(st);
      if (it != target_of.end()) {
        runners_[c].target = it->second.first;
        runners_[c].target_ray = it->second.second;
        reserved_.insert({vertex_point(it->second.first), it->second.second});
        ++g.stats.cone_pairs;
      }
    }
    // Motorcycles: the shortest active curve advances by one segment; ties by curve id.
    using Key = std::pair<double, int>;
    std::priority_queue<Key, std::vector<Key>, std::greater<Key>> queue;
    for (int c = 0; c < static_cast<int>(runners_.size()); ++c) queue.push({0.0, c});
    for (std::size_t guard = 0; !queue.empty(); ++guard) {
      const int c = queue.top().second;
      queue.pop();
      if (runners_[c].state == State::Done) continue;
      step(c);
      if (runners_[c].state != State::Done) queue.push({g.curves[c].length, c});
      finished_elsewhere_.push_back(c);
      for (const int d : finished_elsewhere_) {
        // A paired curve that did not reach its cone: the other end's ray is traced after all.
        const Runner& r = runners_[d];
        if (r.state != State::Done || r.target < 0) continue;
        const TraceCurve& cd = g.curves[d];
        const bool reached = cd.end == CurveEnd::Cone && graph_.points[cd.points.back()].kind == TracePoint::Kind::Vertex &&
                             graph_.points[cd.points.back()].element == r.target;
        const int pt = vertex_point(r.target);
        if (!reached && !used_ray(pt, r.target_ray, -1)) {
          const double length = cd.length;  // start_curve reallocates the curves (and runners)
          const int target = r.target, target_ray = r.target_ray;
          const int e = start_curve(target, target_ray);
          queue.push({length, e});
        }
        runners_[d].target = -1;  // handled once
      }
      finished_elsewhere_.clear();
    }
    apply_hits();
    return finish(t0);
  }

  // Drops curves that never left their start (a ray taken by a curve that arrived first) and the
  // points cut away with merged curves; the statistics; hands the rays to the reuse.
  TraceGraph finish(std::chrono::steady_clock::time_point t0) {
    TraceGraph& g = graph_;
    std::vector<TraceCurve> kept;
    for (TraceCurve& c : g.curves)
      if (c.points.size() >= 2) kept.push_back(std::move(c));
    g.curves = std::move(kept);
    compact_points();
    finish_stats();
    if (reuse_) {
      reuse_->rays = std::move(rays_);
      reuse_->rays_done = std::move(rays_done_);
    }
    g.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return std::move(graph_);
  }

 private:
  // ---------------------------------------------------------------- geometry (doubles) ----
  Vec2d point_in_face(const Where& w) const {
    const int i = w.he % 3;
    return lerp2(frames_.corner[w.face][i], frames_.corner[w.face][(i + 1) % 3], to_double(w.s));
  }
  int corner_of(int f, int v) const {
    const auto fv = mesh_.face_vertices(f);
    for (int c = 0; c < 3; ++c)
      if (fv[c] == v) return c;
    return -1;
  }
  // Whether the ray from P along unit w passes close enough to X to be taken into it.
  bool captures(const Vec2d& P, const Vec2d& w, const Vec2d& X) const {
    const Vec2d d = sub2(X, P);
    const double along = dot2(w, d);
    return along > 0 && std::fabs(cross2(w, d)) <= options_.capture_slope * along;
  }
  // The dyadic step count of parameter s (not clamped): 0 .. 2^bits at the ends.
  double grid(double s) const { return std::nearbyint(s * std::ldexp(1.0, bits_)); }
  Rational from_grid(double k) const {
    const double top = std::ldexp(1.0, bits_);
    if (!(k >= 1)) k = 1;
    if (k > top - 1) k = top - 1;
    return make_rational(Integer(static_cast<long>(k)), Integer(1) << bits_);
  }

  // The next step from `w`; `capture_ok(x)`: whether the curve may be taken into vertex x.
  template <class CaptureOk>
  Advance advance(const Where& w, const CaptureOk& capture_ok) {
    Advance a;
    if (w.vertex >= 0) {
      const VertexRays& vr = rays(w.vertex);
      if (w.ray < 0 || w.ray >= static_cast<int>(vr.rays.size())) return a;
      const VertexRay& ray = vr.rays[w.ray];
      if (ray.edge == -2) return a;
      if (ray.edge >= 0) {
        a.kind = Advance::Kind::Walk;
        a.he = ray.edge;
        a.vertex = mesh_.target(ray.edge);
        a.face = ray.face;
        a.dir = ray.dir;
        return a;
      }
      const int f = ray.face, ci = corner_of(f, w.vertex);
      if (ci < 0 || !frames_.good[f]) return a;
      const Vec2d P = frames_.corner[f][ci], P1 = frames_.corner[f][(ci + 1) % 3], P2 = frames_.corner[f][(ci + 2) % 3];
      const Vec2d dir = frames_.direction(f, ray.dir);
      a.face = f;
      a.dir = ray.dir;
      const auto fv = mesh_.face_vertices(f);
      for (int k : {1, 2}) {
        const int x = fv[(ci + k) % 3];
        if (capture_ok(x) && captures(P, dir, frames_.corner[f][(ci + k) % 3])) {
          // Taken into a neighbour of the start: along their edge.
          const int h = k == 1 ? 3 * f + ci : mesh_.twin(3 * f + (ci + 2) % 3);
          if (h < 0) continue;
          a.kind = Advance::Kind::Walk;
          a.he = h;
          a.vertex = x;
          a.capture = true;
          return a;
        }
      }
      const double den = cross2(sub2(P2, P1), dir);
      const double s = den != 0 ? cross2(sub2(P, P1), dir) / den : 0.5;
      const double k = grid(s);
      if (k <= 0 || k >= std::ldexp(1.0, bits_)) {
        // Along the edge to corner ci+1 (k <= 0) or ci+2: a walk.
        const int far = k <= 0 ? (ci + 1) % 3 : (ci + 2) % 3;
        int h = k <= 0 ? 3 * f + ci : mesh_.twin(3 * f + (ci + 2) % 3);
        if (h < 0) return Advance{};  // along the boundary
        a.kind = Advance::Kind::Walk;
        a.he = h;
        a.vertex = fv[far];
        return a;
      }
      a.kind = Advance::Kind::Edge;
      a.he = 3 * f + (ci + 1) % 3;
      a.t = from_grid(k);
      return a;
    }
    const int f = w.face, i = w.he % 3;
    if (!frames_.good[f]) return a;
    const Vec2d P = point_in_face(w);
    const Vec2d Pi = frames_.corner[f][i], Pj = frames_.corner[f][(i + 1) % 3], Pc = frames_.corner[f][(i + 2) % 3];
    const Vec2d dir = w.steer >= 0 ? steer_direction(f, P, w.steer, w.dir) : frames_.direction(f, w.dir);
    const Vec2d e = sub2(Pj, Pi);
    const int far = mesh_.face_vertices(f)[(i + 2) % 3];
    a.face = f;
    a.dir = w.dir;
    // Passing close to an end of the entry edge whose rays are traced: taken into it along the edge.
    for (const int k : {i, (i + 1) % 3}) {
      const int x = mesh_.face_vertices(f)[k];
      if (capture_ok(x) && captures(P, dir, frames_.corner[f][k])) {
        a.kind = Advance::Kind::Slide;
        a.he = w.he;
        a.vertex = x;
        a.capture = true;
        return a;
      }
    }
    if (cross2(e, dir) <= 0) {
      // The direction does not enter the face: the curve runs along the entry edge, to the end it
      // points to.
      a.kind = Advance::Kind::Slide;
      a.he = w.he;
      a.vertex = dot2(dir, e) > 0 ? mesh_.target(w.he) : mesh_.origin(w.he);
      return a;  // face and dir: the curve's (set above)
    }
    const bool left = cross2(dir, sub2(Pc, P)) >= 0;  // the far corner left of the ray: exit right of it
    a.he = left ? 3 * f + (i + 1) % 3 : 3 * f + (i + 2) % 3;
    const int k3 = a.he % 3;
    const Vec2d O = frames_.corner[f][k3], D = sub2(frames_.corner[f][(k3 + 1) % 3], O);
    const double den = cross2(D, dir);
    const double s = den != 0 ? cross2(sub2(P, O), dir) / den : 0.5;
    const double k = grid(s);
    a.t = from_grid(k);
    const bool rounds = (left && k >= std::ldexp(1.0, bits_)) || (!left && k <= 0);
    const bool capture = capture_ok(far) && captures(P, dir, Pc);
    if (rounds || capture) {
      // The curve reaches the far corner (by rounding onto it, or taken into it); the clamped
      // edge exit stays as the alternative.
      a.alt_he = a.he;
      a.alt_t = a.t;
      a.kind = Advance::Kind::Vertex;
      a.vertex = far;
      a.capture = capture;
      return a;
    }
    a.kind = Advance::Kind::Edge;
    return a;
  }

  // 3D position of a point of face f given in f's frame.
  Vec3d to_3d(int f, const Vec2d& p) const {
    const Vec3d& o = frames_.origin[f];
    const Vec3d &ax = frames_.axis_x[f], &ay = frames_.axis_y[f];
    return {o.x + p.x * ax.x + p.y * ay.x, o.y + p.x * ax.y + p.y * ay.y, o.z + p.x * ax.z + p.y * ay.z};
  }
  // The unit direction in face f from P towards vertex x (projected on the face plane); the field
  // direction dir where that is degenerate.
  Vec2d steer_direction(int f, const Vec2d& P, int x, int dir) const {
    const Vec3d p3 = to_3d(f, P), x3 = positions_[x];
    const Vec3d d{x3.x - p3.x, x3.y - p3.y, x3.z - p3.z};
    const Vec3d &ax = frames_.axis_x[f], &ay = frames_.axis_y[f];
    const Vec2d v{d.x * ax.x + d.y * ax.y + d.z * ax.z, d.x * ay.x + d.y * ay.y + d.z * ay.z};
    const double l = std::sqrt(dot2(v, v));
    if (!(l > 0) || !std::isfinite(l)) return frames_.direction(f, dir);
    return {v.x / l, v.y / l};
  }
  // A curve inside a face (not steering yet) within steer_length of a vertex `ok` accepts, ahead
  // of it within 45 degrees of its field direction, heads straight for the nearest such vertex.
  template <class Ok>
  void maybe_steer(Where& w, const Ok& ok) {
    if (w.face < 0 || w.steer >= 0 || !(steer_length_ > 0) || traced_hash_.empty()) return;
    const Vec2d P2 = point_in_face(w);
    const Vec3d P = to_3d(w.face, P2);
    const Vec2d d2 = frames_.direction(w.face, w.dir);
    const Vec3d &ax = frames_.axis_x[w.face], &ay = frames_.axis_y[w.face];
    const Vec3d d{d2.x * ax.x + d2.y * ay.x, d2.x * ax.y + d2.y * ay.y, d2.x * ax.z + d2.y * ay.z};
    const long cx = static_cast<long>(std::floor(P.x / steer_length_)), cy = static_cast<long>(std::floor(P.y / steer_length_)),
               cz = static_cast<long>(std::floor(P.z / steer_length_));
    if (!near_cells_.count(cell_key(cx, cy, cz))) return;  // no traced vertex in the 27 cells below
    int best = -1;
    double best_d = steer_length_;
    for (long i = cx - 1; i <= cx + 1; ++i)
      for (long j = cy - 1; j <= cy + 1; ++j)
        for (long k = cz - 1; k <= cz + 1; ++k) {
          auto it = traced_hash_.find(cell_key(i, j, k));
          if (it == traced_hash_.end()) continue;
          for (int x : it->second) {
            if (!ok(x)) continue;
            const Vec3d X = positions_[x];
            const Vec3d v{X.x - P.x, X.y - P.y, X.z - P.z};
            const double l = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
            if (!(l <= best_d) || !(l > 0)) continue;
            if (v.x * d.x + v.y * d.y + v.z * d.z < 0.7071 * l) continue;
            if (l == best_d && x > best) continue;
            best = x;
            best_d = l;
          }
        }
    if (best >= 0) w.steer = best, ++graph_.stats.steers;
  }
  static std::uint64_t cell_key(long i, long j, long k) {
    return (static_cast<std::uint64_t>(i & 0x1fffff) << 42) | (static_cast<std::uint64_t>(j & 0x1fffff) << 21) |
           static_cast<std::uint64_t>(k & 0x1fffff);
  }

  // The ray of vertex x nearest to the direction `d` given in face f (a face around x): d is
  // carried to each ray's face by unfolding the faces around x (the shorter way round).
  int nearest_ray(int x, int f, const Vec2d& d) {
    return nearest_free_ray(x, f, d, [](int) { return true; });
  }

  // The ray of x nearest to direction d (face f) if `free(ray)`, else the nearer free one of the
  // two rays on either side of d (so that the curves keep their order around x), else -1.
  template <class Free>
  int nearest_free_ray(int x, int f, const Vec2d& d, const Free& free) {
    const VertexRays& vr = rays(x);
    if (vr.rays.empty()) return -1;
    std::vector<int> fan;
    const int h0 = mesh_.vertex_halfedge(x);
    bool closed = false;
    for (int h = h0, guard = 0; h >= 0 && guard <= mesh_.num_halfedges(); ++guard) {
      fan.push_back(h);
      const int n = mesh_.next_around_origin(h);
      if (n == h0) {
        closed = true;
        break;
      }
      h = n;
    }
    const int nfan = static_cast<int>(fan.size());
    auto index_of = [&](int face) {
      for (int i = 0; i < nfan; ++i)
        if (TriMesh::face(fan[i]) == face) return i;
      return -1;
    };
    const int iq = index_of(f);
    if (iq < 0) return -1;
    // Rotation from the frame of fan face i to that of face i+1.
    auto step_rot = [&](int i) {
      const int fi = TriMesh::face(fan[i]), fj = TriMesh::face(fan[(i + 1) % nfan]);
      (void)fi;
      (void)fj;
      Vec2d ei = frames_.edge_vector(TriMesh::prev(fan[i]));
      ei = {-ei.x, -ei.y};
      const Vec2d ej = frames_.edge_vector(fan[(i + 1) % nfan]);
      const double li = std::sqrt(dot2(ei, ei)), lj = std::sqrt(dot2(ej, ej));
      const Vec2d a{ei.x / li, ei.y / li}, b{ej.x / lj, ej.y / lj};
      return Vec2d{b.x * a.x + b.y * a.y, b.y * a.x - b.x * a.y};  // b * conj(a)
    };
    const double ld = std::sqrt(dot2(d, d));
    const Vec2d u{d.x / ld, d.y / ld};
    int best = -1, ccw_best = -1, cw_best = -1;
    double best_dot = -3, ccw_dot = -3, cw_dot = -3;
    for (int k = 0; k < static_cast<int>(vr.rays.size()); ++k) {
      const VertexRay& ray = vr.rays[k];
      Vec2d rv;
      int rf = ray.face;
      if (ray.edge == -2) {
        rv = frames_.edge_vector(TriMesh::prev(fan.back()));
        rv = {-rv.x, -rv.y};
      } else if (ray.edge >= 0) {
        rv = frames_.edge_vector(ray.edge);
      } else {
        rv = frames_.direction(rf, ray.dir);
      }
      const int ir = index_of(rf);
      if (ir < 0) continue;
      Vec2d t = u;
      int ccw = closed ? ((ir - iq) % nfan + nfan) % nfan : ir - iq;
      if (closed && ccw > nfan / 2) ccw -= nfan;
      for (int s = 0; s < std::abs(ccw); ++s) {
        const int i = ccw > 0 ? (iq + s) % nfan : ((iq - s - 1) % nfan + nfan) % nfan;
        const Vec2d r = step_rot(i);
        t = ccw > 0 ? Vec2d{r.x * t.x - r.y * t.y, r.x * t.y + r.y * t.x} : Vec2d{r.x * t.x + r.y * t.y, r.x * t.y - r.y * t.x};
      }
      const double lr = std::sqrt(dot2(rv, rv));
      const Vec2d ru{rv.x / lr, rv.y / lr};
      const double dt = dot2(t, ru);
      if (dt > best_dot) best_dot = dt, best = k;
      if (cross2(t, ru) >= 0) {
        if (dt > ccw_dot) ccw_dot = dt, ccw_best = k;
      } else if (dt > cw_dot) {
        cw_dot = dt, cw_best = k;
      }
    }
    // Only the ray the field points along: another one would put a quarter turn into the curve.
    (void)ccw_best;
    (void)cw_best;
    if (best >= 0 && free(best)) return best;
    return -1;
  }

  // Arrival at vertex x by the segment of a curve with direction `dir` in face f: x's ray back.
  int arrival_ray(int x, int f, int dir) { return nearest_ray(x, f, frames_.direction(f, dir + 2)); }

  // The solo pre-pass: the ray traced alone (no other curve) until it is taken into a vertex whose
  // rays are traced; that vertex and ray, or nothing (boundary, bound, stuck).
  std::optional<std::pair<std::pair<int, int>, int>> solo(int v, int k) {
    Where w;
    w.vertex = v;
    w.ray = k;
    const int bound = std::min(max_segments_, 64 + 8 * static_cast<int>(std::sqrt(static_cast<double>(mesh_.num_faces()))));
    for (int steps = 0; steps < bound; ++steps) {
      const int from = w.vertex;
      maybe_steer(w, [&](int x) { return traced_[x] && x != v; });
      const Advance a = advance(w, [&](int x) { return traced_[x] && x != from && (w.steer < 0 || x == w.steer); });
      int x = -1, ra = -1;
      switch (a.kind) {
        case Advance::Kind::Stuck: return std::nullopt;
        case Advance::Kind::Edge: {
          const int tw = mesh_.twin(a.he);
          if (tw < 0) return std::nullopt;
          const int steer = w.steer;
          w = Where{};
          w.face = TriMesh::face(tw);
          w.he = tw;
          w.s = 1 - a.t;
          w.dir = (a.dir + frames_.shift[a.he]) % 4;
          w.steer = steer;
          continue;
        }
        case Advance::Kind::Vertex:
          x = a.vertex;
          ra = arrival_ray(x, a.face, a.dir);
          break;
        case Advance::Kind::Walk:
          x = a.vertex;
          ra = walk_arrival(a);
          break;
        case Advance::Kind::Slide:
          x = a.vertex;
          ra = arrival_ray(x, a.face, a.dir);
          break;
      }
      if (ra < 0) return std::nullopt;
      const VertexRays& rx = rays(x);
      if (traced_[x]) {
        if (rx.boundary && (ra == 0 || ra == static_cast<int>(rx.rays.size()) - 1)) return std::nullopt;
        return std::make_pair(std::make_pair(x, ra), steps);
      }
      if (rx.boundary || rx.valence != 4) return std::nullopt;
      w = Where{};
      w.vertex = x;
      w.ray = (ra + 2) % 4;
    }
    return std::nullopt;
  }

  // The ray of the far end b of a walk (v -> b) pointing back along it.
  int walk_arrival(const Advance& a) {
    const int tw = mesh_.twin(a.he);
    // The walk's direction in the face of tw (the face at b whose sector starts along b -> v).
    const int fh = TriMesh::face(a.he);
    int dir_h = a.dir;
    if (a.face != fh) dir_h = tw >= 0 && a.face == TriMesh::face(tw) ? (a.dir + frames_.shift[tw]) % 4 : a.dir;
    return nearest_ray(a.vertex, fh, frames_.direction(fh, dir_h + 2));
  }

  // ---------------------------------------------------------------- points ----
  int vertex_point(int v) {
    if (vertex_point_[v] >= 0) return vertex_point_[v];
    TracePoint p;
    p.kind = TracePoint::Kind::Vertex;
    p.element = v;
    vertex_point_[v] = add_point(std::move(p));
    return vertex_point_[v];
  }
  int add_point(TracePoint p) {
    const VertexRays* vr = p.kind == TracePoint::Kind::Vertex ? &rays(p.element) : nullptr;
    graph_.points.push_back(std::move(p));
    point_uses_.push_back(0);
    dead_.push_back(0);
    if (vr) {
      graph_.ray_count.push_back(static_cast<int>(vr->rays.size()));
      graph_.ray_cyclic.push_back(vr->boundary ? 0 : 1);
    } else {
      graph_.ray_count.push_back(4);
      const TracePoint& q = graph_.points.back();
      graph_.ray_cyclic.push_back(q.kind == TracePoint::Kind::Edge && mesh_.twin(q.element) < 0 ? 0 : 1);
    }
    return static_cast<int>(graph_.points.size()) - 1;
  }
  static int canonical(const TriMesh& m, int h) {
    const int t = m.twin(h);
    return t >= 0 && t < h ? t : h;
  }
  int find_edge_point(int ce, const Rational& t) const {
    auto it = edge_points_.find(ce);
    if (it == edge_points_.end()) return -1;
    for (int p : it->second)
      if (graph_.points[p].t == t) return p;
    return -1;
  }
  int edge_point(int ce, const Rational& t) {
    const int found = find_edge_point(ce, t);
    if (found >= 0) return found;
    TracePoint p;
    p.kind = TracePoint::Kind::Edge;
    p.element = ce;
    p.t = t;
    const int id = add_point(std::move(p));
    edge_points_[ce].push_back(id);
    return id;
  }
  Point2q bary(int p, int f) const { return field_detail::point_in_face(mesh_, graph_.points[p], f); }
  // The point at local parameter t along half-edge h, in the barycentric plane of face(h).
  static Point2q edge_bary(int h, const Rational& t) {
    std::array<Rational, 3> w{Rational(0), Rational(0), Rational(0)};
    w[h % 3] = 1 - t;
    w[(h % 3 + 1) % 3] = t;
    return {w[1], w[2]};
  }
  // The ray index, in point p's numbering, of field direction j of face f (p on an edge or in a face).
  int ray_of(int p, int f, int j) const {
    const TracePoint& q = graph_.points[p];
    j = ((j % 4) + 4) % 4;
    if (q.kind == TracePoint::Kind::Edge && TriMesh::face(q.element) != f) return (j + frames_.shift[mesh_.twin(q.element)]) % 4;
    return j;
  }
  Vec3d point_position(int p) const {
    const TracePoint& q = graph_.points[p];
    if (q.kind == TracePoint::Kind::Vertex) return positions_[q.element];
    if (q.kind == TracePoint::Kind::Edge) {
      const double t = to_double(q.t);
      const Vec3d a = positions_[mesh_.origin(q.element)], b = positions_[mesh_.target(q.element)];
      return {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z)};
    }
    const auto fv = mesh_.face_vertices(q.element);
    Vec3d r{0, 0, 0};
    for (int i = 0; i < 3; ++i) {
      const double w = to_double(q.w[i]);
      r.x += w * positions_[fv[i]].x, r.y += w * positions_[fv[i]].y, r.z += w * positions_[fv[i]].z;
    }
    return r;
  }
  int face_point(int f, const Point2q& x) {
    TracePoint p;
    p.kind = TracePoint::Kind::Face;
    p.element = f;
    p.w = {Rational(1 - x.x - x.y), x.x, x.y};
    return add_point(std::move(p));
  }

  // ---------------------------------------------------------------- curves ----
  int start_curve(int v, int k) {
    on_curve_vertex_[v] = 1;
    TraceCurve c;
    c.points.push_back(vertex_point(v));
    ++point_uses_[c.points.back()];
    point_curves_[c.points.back()].push_back(static_cast<int>(graph_.curves.size()));
    c.ray_back.push_back(-1);
    c.ray_forward.push_back(k);
    graph_.curves.push_back(std::move(c));
    Runner r;
    r.state = State::Active;
    r.where.vertex = v;
    r.where.ray = k;
    runners_.push_back(r);
    return static_cast<int>(runners_.size()) - 1;
  }
  void finish(int c, CurveEnd end) {
    graph_.curves[c].end = end;
    runners_[c].state = State::Done;
  }
  void add_segment(int c, int to, int face, int ray_back_at_to) {
    TraceCurve& cur = graph_.curves[c];
    const Vec3d a = point_position(cur.points.back()), b = point_position(to);
    cur.length += std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
    cur.points.push_back(to);
    ++point_uses_[to];
    point_curves_[to].push_back(c);
    cur.segment_face.push_back(face);
    cur.ray_back.push_back(ray_back_at_to);
    cur.ray_forward.push_back(-1);
    ++graph_.stats.segments;
  }
  void record_face_segment(int c, int f, int dir) {
    const TraceCurve& cur = graph_.curves[c];
    const int s = static_cast<int>(cur.segment_face.size()) - 1;
    FaceSegment fs;
    fs.curve = c;
    fs.segment = s;
    fs.a = bary(cur.points[s], f);
    fs.b = bary(cur.points[s + 1], f);
    fs.dir = dir;
    face_segments_[f].push_back(std::move(fs));
  }
  bool used_ray(int p, int k, int c) const {
    auto it = vertex_rays_used_.find(p);
    if (it == vertex_rays_used_.end()) return false;
    for (const auto& [ray, curve] : it->second)
      if (ray == k && curve != c) return true;
    return false;
  }
  void use_ray(int p, int k, int c) { vertex_rays_used_[p].push_back({k, c}); }

  // The earliest point where segment A -> B in face f meets a segment already there (not at A).
  struct Meet {
    int point = -1;  // an existing point, or -1 (then `at` is new)
    Point2q at;
    int curve = -1, segment = -1, dir = 0;
    bool degenerate = false;
  };
  std::optional<Meet> first_meet(int f, const Point2q& A, const Point2q& B) {
    auto it = face_segments_.find(f);
    if (it == face_segments_.end()) return std::nullopt;
    std::optional<Meet> best;
    const bool increasing = compare_lex(A, B) == Sign::Negative;
    auto nearer = [&](const Point2q& x, const Point2q& y) {
      const Sign s = compare_lex(x, y);
      return increasing ? s == Sign::Negative : s == Sign::Positive;
    };
    for (const FaceSegment& s : it->second) {
      const SegmentRelation rel = classify(A, B, s.a, s.b);
      if (rel == SegmentRelation::Disjoint) continue;
      Meet m;
      m.curve = s.curve;
      m.segment = s.segment;
      m.dir = s.dir;
      if (rel == SegmentRelation::CollinearOverlap) {
        std::optional<Point2q> x;
        for (const Point2q* p : {&s.a, &s.b, &B})
          if (!same(*p, A) && on_segment(*p, A, B) && on_segment(*p, s.a, s.b) && (!x || nearer(*p, *x))) x = *p;
        if (!x) continue;
        m.degenerate = true;
        m.at = *x;
      } else {
        const std::optional<Point2q> x = intersection(A, B, s.a, s.b);
        if (!x || same(*x, A)) continue;
        m.at = *x;
      }
      const TraceCurve& other = graph_.curves[s.curve];
      if (same(m.at, s.a)) m.point = other.points[s.segment];
      else if (same(m.at, s.b)) m.point = other.points[s.segment + 1];
      if (!best || nearer(m.at, best->at)) best = m;
    }
    return best;
  }
  const EdgeWalk* walk_at(int ce, const Rational& t) const {
    auto it = edge_walks_.find(ce);
    if (it == edge_walks_.end()) return nullptr;
    for (const EdgeWalk& w : it->second)
      if (w.t0 <= t && t <= w.t1) return &w;
    return nullptr;
  }
  void add_walk(int c, int ce, const Rational& t0, const Rational& t1, int face, int dir) {
    EdgeWalk w;
    w.curve = c;
    w.segment = static_cast<int>(graph_.curves[c].segment_face.size()) - 1;
    w.t0 = t0;
    w.t1 = t1;
    w.face = face;
    w.dir = dir;
    edge_walks_[ce].push_back(std::move(w));
  }

  // Wall `index` (TraceOptions::walls): a curve along its edges, drawn whole before any other.
  // Its ends and turns become seeds (`seed`).
  void draw_wall(int index, const std::vector<int>& w, std::vector<unsigned char>& seed) {
    const int n = static_cast<int>(w.size()), nv = mesh_.num_vertices();
    const std::string name = "trace wall " + std::to_string(index);
    if (n < 2) throw Error(ErrorKind::InvalidArgument, name + " has fewer than two vertices");
    std::vector<int> hs(n - 1);
    for (int i = 0; i + 1 < n; ++i) {
      if (w[i] < 0 || w[i] >= nv || w[i + 1] < 0 || w[i + 1] >= nv)
        throw Error(ErrorKind::InvalidArgument, name + ": a vertex out of range");
      hs[i] = mesh_.find_halfedge(w[i], w[i + 1]);
      if (hs[i] < 0 || mesh_.twin(hs[i]) < 0)
        throw Error(ErrorKind::InvalidArgument,
                    name + ": vertices " + std::to_string(w[i]) + " and " + std::to_string(w[i + 1]) +
                        " are not joined by an interior edge",
                    {w[i], w[i + 1]});
      if (!walled_edges_.insert(canonical(mesh_, hs[i])).second)
        throw Error(ErrorKind::InvalidArgument,
                    name + ": the edge " + std::to_string(w[i]) + "-" + std::to_string(w[i + 1]) + " is in two walls",
                    {w[i], w[i + 1]});
    }
    ++graph_.stats.walls;
    const bool closed = n > 2 && w.front() == w.back();
    // Ray of w[i] along the edge to w[i + 1] (out) and along the edge back to w[i - 1] (in).
    auto out_ray = [&](int i) { return nearest_ray(w[i], TriMesh::face(hs[i]), frames_.edge_vector(hs[i])); };
    auto in_ray = [&](int i) {
      const int t = mesh_.twin(hs[i - 1]);
      return nearest_ray(w[i], TriMesh::face(t), frames_.edge_vector(t));
    };
    auto regular = [&](int v) { return !rays(v).boundary && rays(v).valence == 4; };
    // Vertex x's rays to trace: the one opposite ray r (continuing the wall), or every one.
    auto seed_from = [&](int x, int r) {
      seed[x] |= options_.wall_side_rays ? static_cast<unsigned char>(0xFF) : static_cast<unsigned char>(1u << ((r + 2) % 4));
    };
    const int out0 = out_ray(0);
    const int c = start_curve(w[0], out0);
    runners_[c].state = State::Done;
    auto stuck = [&]() {
      finish(c, CurveEnd::Stuck);
      ++graph_.stats.stuck_walls;
      graph_.stuck_walls.push_back(index);
    };
    if (out0 < 0 || used_ray(vertex_point(w[0]), out0, c)) return stuck();
    use_ray(vertex_point(w[0]), out0, c);
    for (int i = 0; i + 1 < n; ++i) {
      const int h = hs[i], x = w[i + 1], px = vertex_point(x), f = TriMesh::face(h);
      const int dir = frames_.nearest_direction(f, frames_.edge_vector(h));
      const int ra = in_ray(i + 1);
      if (ra < 0 || used_ray(px, ra, c) || (i + 2 == n && closed && ra == out0)) return stuck();
      add_segment(c, px, -1, ra);
      add_walk(c, canonical(mesh_, h), Rational(0), Rational(1), f, dir);
      use_ray(px, ra, c);
      on_curve_vertex_[x] = 1;
      if (i + 2 < n) {
        const int out = out_ray(i + 1);
        if (out < 0 || out == ra || used_ray(px, out, c)) return stuck();
        graph_.curves[c].ray_forward.back() = out;
        use_ray(px, out, c);
        if (regular(x) && out != (ra + 2) % 4) seed_from(x, ra);
      } else if (closed) {
        if (regular(x) && out0 != (ra + 2) % 4) seed_from(x, ra);
      } else if (regular(x)) {
        seed_from(x, ra);  // the last vertex: the wall ends
      }
    }
    if (!closed && regular(w.front())) seed_from(w.front(), out0);
    const int last = w.back();
    finish(c, !regular(last) || seed[last] ? CurveEnd::Cone : CurveEnd::Curve);
  }

  // Ends curve c at meeting m, its segment in face f with direction dir.
  void end_at_meet(int c, int f, int dir, const Meet& m) {
    if (m.degenerate) {
      finish(c, CurveEnd::Stuck);
      return;
    }
    if (((dir - m.dir) % 2 + 2) % 2 == 0 && (m.point < 0 || graph_.points[m.point].kind != TracePoint::Kind::Vertex)) {
      // Parallel curves meeting: head-on they are one separatrix traced from both ends (merged at
      // the meeting point); one catching up with the other cannot end on it.
      if ((dir - m.dir + 4) % 4 == 2 && merge_head_on(c, f, dir, m)) return;
      if (end_at_vertex_of(c, f, dir, m)) return;
      ++graph_.stats.parallel_meets;
      if ((dir - m.dir + 4) % 4 == 0) ++graph_.stats.same_direction_meets;
      if (drop_curve(c)) return;
      finish(c, CurveEnd::Stuck);
      return;
    }
    int p = m.point;
    if (p < 0) {
      // A node of the other curve close by on the same segment (where a curve from its other side
      // ended): end there too, rather than a hair's breadth away.
      if (snap_to_node(c, f, dir, m)) {
        ++graph_.stats.node_snaps;
        return;
      } else {
        p = face_point(f, m.at);
        hits_.push_back({m.curve, m.segment, p});
      }
    }
    const TracePoint& q = graph_.points[p];
    const int ray = q.kind == TracePoint::Kind::Vertex ? arrival_ray(q.element, f, dir) : ray_of(p, f, dir + 2);
    add_segment(c, p, f, ray);
    record_face_segment(c, f, dir);
    if (q.kind == TracePoint::Kind::Vertex) use_ray(p, ray, c);
    finish(c, CurveEnd::Curve);
  }

  // Whether two points of a face's barycentric plane lie on one edge of the face.
  static bool along_face_edge(const Point2q& a, const Point2q& b) {
    const Point2q O{Rational(0), Rational(0)}, E1{Rational(1), Rational(0)}, E2{Rational(0), Rational(1)};
    return (on_segment(a, O, E1) && on_segment(b, O, E1)) || (on_segment(a, E1, E2) && on_segment(b, E1, E2)) ||
           (on_segment(a, E2, O) && on_segment(b, E2, O));
  }

  // The rays used at point p (not a vertex) by the curves through it or ending there, and by the
  // curves it lies on as a T-junction not inserted yet (a hit).
  std::vector<int> rays_at(int p) const {
    std::vector<int> out;
    for (const Hit& h : hits_) {
      if (h.point != p) continue;
      const int f = graph_.curves[h.curve].segment_face[h.segment];
      if (f >= 0) {
        const auto it = face_segments_.find(f);
        if (it == face_segments_.end()) continue;
        for (const FaceSegment& fs : it->second)
          if (fs.curve == h.curve && fs.segment == h.segment) out.push_back(ray_of(p, f, fs.dir)), out.push_back(ray_of(p, f, fs.dir + 2));
      } else {
        for (const auto& [ce, walks] : edge_walks_)
          for (const EdgeWalk& w : walks)
            if (w.curve == h.curve && w.segment == h.segment) out.push_back(ray_of(p, w.face, w.dir)), out.push_back(ray_of(p, w.face, w.dir + 2));
      }
    }
    auto it = point_curves_.find(p);
    if (it == point_curves_.end()) return out;
    for (int cc : it->second) {
      const TraceCurve& cu = graph_.curves[cc];
      for (std::size_t k = cu.points.size(); k-- > 0;)
        if (cu.points[k] == p) {
          if (cu.ray_back[k] >= 0) out.push_back(cu.ray_back[k]);
          if (cu.ray_forward[k] >= 0) out.push_back(cu.ray_forward[k]);
        }
    }
    return out;
  }

  // Curve c (direction dir in face f) meets segment m.segment of curve b = m.curve at the new
  // point X = m.at. Where b already carries a node within TraceOptions::snap_length (3D, along b)
  // of X at which a curve from c's side could end (another curve ended there from the other side,
  // so c's ray there is free), c goes there instead: along b, one grid step beside b's crossings
  // of the edges in between, on c's side, every piece checked exactly not to meet anything. One
  // node instead of two a short way apart, whose short arc no integer length >= 1 could fit (the
  // zero-length arcs of T-mesh quantization, Lyon, Campen & Kobbelt 2021, made geometric). True
  // when c has ended there.
  bool snap_to_node(int c, int f, int dir, const Meet& m) {
    const double limit = options_.snap_length > 0 ? options_.snap_length : options_.snap_distance * mean_edge_;
    if (!(limit > 0)) return false;
    const int b = m.curve, s = m.segment;
    const TraceCurve& other = graph_.curves[b];
    const int ns = static_cast<int>(other.segment_face.size());
    const Point2q A = bary(graph_.curves[c].points.back(), f);
    const Sign side = orient2d(bary(other.points[s], f), bary(other.points[s + 1], f), A);
    if (side == Sign::Zero) return false;
    Vec3d X{0, 0, 0};
    {
      const auto fv = mesh_.face_vertices(f);
      const double w1 = to_double(m.at.x), w2 = to_double(m.at.y), w0 = 1 - w1 - w2;
      for (int i = 0; i < 3; ++i) {
        const double w = i == 0 ? w0 : i == 1 ? w1 : w2;
        X.x += w * positions_[fv[i]].x, X.y += w * positions_[fv[i]].y, X.z += w * positions_[fv[i]].z;
      }
    }
    auto dist = [](const Vec3d& p, const Vec3d& q) {
      return std::sqrt((p.x - q.x) * (p.x - q.x) + (p.y - q.y) * (p.y - q.y) + (p.z - q.z) * (p.z - q.z));
    };
    // Candidates along b in both directions: (distance, node point, its segment, direction).
    struct Cand {
      double d;
      int point, segment, step;  // step +1: ahead along b, -1: behind
    };
    std::vector<Cand> cands;
    for (const int step : {+1, -1}) {
      double d = 0;
      Vec3d prev = X;
      for (int k = s; k >= 0 && k < ns; k += step) {
        if (other.segment_face[k] < 0) break;  // a walk along an edge: no hugging there
        // Hits on segment k (ends of other curves), and its far end if one ended there.
        for (const Hit& h : hits_)
          if (h.curve == b && h.segment == k) {
            const double dh = d + dist(prev, point_position(h.point));
            if (dh <= limit) cands.push_back({dh, h.point, k, step});
          }
        const int far = other.points[step > 0 ? k + 1 : k];
        d += dist(prev, point_position(far));
        prev = point_position(far);
        if (d > limit || graph_.points[far].kind == TracePoint::Kind::Vertex) break;
        if (point_uses_[far] > 1) cands.push_back({d, far, k, step});
      }
    }
    std::sort(cands.begin(), cands.end(), [](const Cand& x, const Cand& y) {
      return x.d != y.d ? x.d < y.d : x.point < y.point;
    });
    for (const Cand& cand : cands) {
      // Only nodes on the hit segment's side of X that lie ahead of X in `step` direction, or on
      // a later segment, are reached by the plan below; a hit on segment s itself behind X with
      // step +1 is found again with step -1.
      if (plan_and_go(c, f, dir, b, s, cand.segment, cand.step, cand.point, side)) return true;
    }
    return false;
  }

  // The path of snap_to_node: from c's point in face f along curve b's segments s .. t (step +1
  // or -1) to node y on segment t, on c's side `side` of b. Commits and ends c when every piece
  // passes the exact checks; else changes nothing.
  bool plan_and_go(int c, int f, int dir, int b, int s, int t, int step, int y, Sign side) {
    const TraceCurve& other = graph_.curves[b];
    struct Piece {
      int face, dir;
      int edge;          // canonical edge of the crossing point at the piece's end (-1: the node)
      Rational t_edge;   // its parameter
      int he;            // the half-edge of `face` on that edge
    };
    std::vector<Piece> pieces;
    int cur_face = f, cur_dir = dir;
    Point2q from = bary(graph_.curves[c].points.back(), f);
    std::vector<std::pair<int, Rational>> fresh;  // edge points to create, in order
    const Rational step_t = make_rational(Integer(1), Integer(1) << bits_);
    for (int k = s;; k += step) {
      if (k != t) {
        // Cross the edge where b leaves segment k (towards t): next to b's crossing point.
        const int qb = other.points[step > 0 ? k + 1 : k];
        const TracePoint& Q = graph_.points[qb];
        if (Q.kind != TracePoint::Kind::Edge) return false;
        const int ce = Q.element;
        int he = ce;
        if (TriMesh::face(he) != cur_face) he = mesh_.twin(ce);
        if (he < 0 || TriMesh::face(he) != cur_face || mesh_.twin(he) < 0) return false;
        const Point2q Ba = bary(other.points[k], cur_face), Bb = bary(other.points[k + 1], cur_face);
        bool placed = false;
        for (const Rational& tq : {Rational(Q.t + step_t), Rational(Q.t - step_t)}) {
          if (!(tq > 0 && tq < 1) || find_edge_point(ce, tq) >= 0 || walk_at(ce, tq)) continue;
          const Rational tl = he == ce ? tq : Rational(1 - tq);
          const Point2q qf = edge_bary(he, tl);
          if (orient2d(Ba, Bb, qf) != side) continue;
          if (along_face_edge(from, qf) || first_meet(cur_face, from, qf)) return false;
          pieces.push_back({cur_face, cur_dir, ce, tq, he});
          from = edge_bary(mesh_.twin(he), Rational(1 - tl));
          cur_dir = (cur_dir + frames_.shift[he]) % 4;
          cur_face = TriMesh::face(mesh_.twin(he));
          if (other.segment_face[k + step] != cur_face) return false;  // b goes on elsewhere
          placed = true;
          break;
        }
        if (!placed) return false;
        continue;
      }
      // The last piece, into the node.
      const Point2q yq = bary(y, cur_face);
      if (along_face_edge(from, yq)) return false;
      if (const auto mm = first_meet(cur_face, from, yq); mm && mm->point != y && !same(mm->at, yq)) return false;
      const int ray = ray_of(y, cur_face, cur_dir + 2);
      std::vector<int> used = rays_at(y);
      // Curve b runs through y (a point on its segment t not yet inserted into it): its rays too.
      for (const FaceSegment& fs : face_segments_[cur_face])
        if (fs.curve == b && fs.segment == t) {
          used.push_back(ray_of(y, cur_face, fs.dir));
          used.push_back(ray_of(y, cur_face, fs.dir + 2));
        }
      if (std::find(used.begin(), used.end(), ray) != used.end()) return false;
      // Commit.
      for (const Piece& pc : pieces) {
        const int q = edge_point(pc.edge, pc.t_edge);
        add_segment(c, q, pc.face, ray_of(q, pc.face, pc.dir + 2));
        record_face_segment(c, pc.face, pc.dir);
        const int g2 = TriMesh::face(mesh_.twin(pc.he));
        graph_.curves[c].ray_forward.back() = ray_of(q, g2, (pc.dir + frames_.shift[pc.he]) % 4);
      }
      add_segment(c, y, cur_face, ray);
      record_face_segment(c, cur_face, cur_dir);
      finish(c, CurveEnd::Curve);
      return true;
    }
  }

  // A parallel meeting with a segment that ends at a vertex of face f (a curve taken into a cone,
  // or starting from one): curve c goes on straight to that vertex instead, if nothing lies in
  // between and a ray on its side of the vertex is free.
  bool end_at_vertex_of(int c, int f, int dir, const Meet& m) {
    const TraceCurve& other = graph_.curves[m.curve];
    const TraceCurve& cur = graph_.curves[c];
    for (int end : {m.segment + 1, m.segment}) {
      const int pv = other.points[end];
      if (graph_.points[pv].kind != TracePoint::Kind::Vertex) continue;
      const int x = graph_.points[pv].element;
      if (corner_of(f, x) < 0 || pv == cur.points.back()) continue;
      const Point2q A = bary(cur.points.back(), f), B = bary(pv, f);
      if (const auto mm = first_meet(f, A, B); mm && mm->point != pv) continue;
      // The direction back along the new segment, in f's frame.
      const int i = corner_of(f, x);
      const TracePoint& q = graph_.points[cur.points.back()];
      Vec2d P;
      if (q.kind == TracePoint::Kind::Edge) {
        int h = q.element;
        double t = to_double(q.t);
        if (TriMesh::face(h) != f) h = mesh_.twin(h), t = 1 - t;
        P = lerp2(frames_.corner[f][h % 3], frames_.corner[f][(h % 3 + 1) % 3], t);
      } else if (q.kind == TracePoint::Kind::Vertex) {
        P = frames_.corner[f][corner_of(f, q.element)];
      } else {
        continue;
      }
      (void)P;
      (void)i;
      const int ra = arrival_ray_for(c, x, f, frames_.direction(f, dir + 2));
      if (ra < 0) continue;
      add_segment(c, pv, f, ra);
      record_face_segment(c, f, dir);
      ++graph_.stats.vertex_joins;
      arrive(c, x, ra);
      return true;
    }
    return false;
  }

  // Curve c (direction dir in face f) meets curve b = m.curve head-on at m.at on b's segment
  // m.segment: b is cut back to the meeting point and both end there, so that the two form one
  // straight curve (the point gets both directions: two wedges of two quarter turns). Refused
  // (false) when anything already rests on the part of b beyond the point.
  bool merge_head_on(int c, int f, int dir, const Meet& m) {
    const int b = m.curve, s = m.segment;
    if (b == c) return false;
    TraceCurve& cb = graph_.curves[b];
    const int last = static_cast<int>(cb.points.size()) - 1;
    // The meeting point's position along b: at points[s], inside the segment, or at points[s+1].
    const bool at_start = m.point >= 0 && m.point == cb.points[s];
    const bool at_end = m.point >= 0 && m.point == cb.points[s + 1];
    const int keep_to = at_end ? s + 1 : s;  // b keeps points[0..keep_to] (+ the new point)
    if (at_start && s == 0) return false;
    for (int k = keep_to + 1; k <= last; ++k) {
      const int p = cb.points[k];
      if (graph_.points[p].kind == TracePoint::Kind::Vertex || point_uses_[p] > 1) return false;
    }
    const Point2q X = m.at;
    const Point2q A = bary(cb.points[s], f);
    for (const Hit& h : hits_) {
      if (h.curve != b || h.segment < s) continue;
      if (h.segment > s || at_start) return false;
      if (at_end) continue;
      const Point2q H = bary(h.point, f);
      if (same(H, X) || !on_segment(H, A, X)) return false;
    }
    // Cut b: its face segments and walks past s, its segment s to the meeting point.
    for (int k = keep_to; k < last; ++k) {
      const int fk = cb.segment_face[k];
      if (fk >= 0) {
        auto& list = face_segments_[fk];
        list.erase(std::remove_if(list.begin(), list.end(), [&](const FaceSegment& x) { return x.curve == b && x.segment >= keep_to && !(x.segment == s && !at_end); }), list.end());
      } else {
        for (auto& [ce, walks] : edge_walks_)
          walks.erase(std::remove_if(walks.begin(), walks.end(), [&](const EdgeWalk& x) { return x.curve == b && x.segment >= k; }), walks.end());
      }
    }
    for (int k = keep_to + 1; k <= last; ++k) {
      const int p = cb.points[k];
      --point_uses_[p];
      if (point_uses_[p] == 0 && graph_.points[p].kind == TracePoint::Kind::Edge) {
        auto& pts = edge_points_[graph_.points[p].element];
        pts.erase(std::remove(pts.begin(), pts.end(), p), pts.end());
        dead_[p] = 1;
      }
    }
    cb.points.resize(keep_to + 1);
    cb.segment_face.resize(keep_to);
    cb.ray_back.resize(keep_to + 1);
    cb.ray_forward.resize(keep_to + 1);
    int p = m.point;
    if (!at_end) {
      if (p < 0) p = face_point(f, X);
      // b's segment s now ends at the meeting point.
      add_segment(b, p, f, ray_of(p, f, m.dir + 2));
      for (FaceSegment& x : face_segments_[f])
        if (x.curve == b && x.segment == s) x.b = X;
    } else {
      cb.ray_back.back() = ray_of(p, f, m.dir + 2);
    }
    cb.ray_forward.back() = -1;
    finish(b, CurveEnd::Curve);
    finished_elsewhere_.push_back(b);
    add_segment(c, p, f, ray_of(p, f, dir + 2));
    record_face_segment(c, f, dir);
    finish(c, CurveEnd::Curve);
    ++graph_.stats.head_on_merges;
    return true;
  }

  // Removes curve c entirely (its start vertex keeps the ray untraced: a wedge of two quarter
  // turns there), unless another curve rests on it. True when removed.
  bool drop_curve(int c) {
    TraceCurve& cur = graph_.curves[c];
    // Its points other than the start and the point it is ending at must be its own alone.
    for (std::size_t k = 1; k + 1 < cur.points.size(); ++k)
      if (point_uses_[cur.points[k]] > 1 || graph_.points[cur.points[k]].kind == TracePoint::Kind::Vertex) return false;
    if (runners_[c].target >= 0) return false;  // a paired curve: its partner would be started
    for (const Hit& h : hits_)
      if (h.curve == c) return false;
    for (std::size_t k = 0; k < cur.segment_face.size(); ++k) {
      const int fk = cur.segment_face[k];
      if (fk < 0) continue;
      auto& list = face_segments_[fk];
      list.erase(std::remove_if(list.begin(), list.end(), [&](const FaceSegment& x) { return x.curve == c; }), list.end());
    }
    for (auto& [ce, walks] : edge_walks_)
      walks.erase(std::remove_if(walks.begin(), walks.end(), [&](const EdgeWalk& x) { return x.curve == c; }), walks.end());
    for (auto it = edge_walks_.begin(); it != edge_walks_.end();) it = it->second.empty() ? edge_walks_.erase(it) : std::next(it);
    for (std::size_t k = 1; k < cur.points.size(); ++k) {
      const int p = cur.points[k];
      if (--point_uses_[p] == 0 && graph_.points[p].kind == TracePoint::Kind::Edge) {
        auto& pts = edge_points_[graph_.points[p].element];
        pts.erase(std::remove(pts.begin(), pts.end(), p), pts.end());
        dead_[p] = 1;
      }
    }
    auto it = vertex_rays_used_.find(cur.points[0]);
    if (it != vertex_rays_used_.end())
      it->second.erase(std::remove_if(it->second.begin(), it->second.end(), [&](const auto& x) { return x.second == c; }),
                       it->second.end());
    cur.points.resize(1);
    cur.segment_face.clear();
    cur.ray_back.resize(1);
    cur.ray_forward.resize(1);
    finish(c, CurveEnd::Stuck);
    ++graph_.stats.dropped;
    return true;
  }

  void step(int c) {
    Runner& r = runners_[c];
    TraceCurve& cur = graph_.curves[c];
    if (static_cast<int>(cur.segment_face.size()) >= max_segments_) {
      finish(c, CurveEnd::Bound);
      return;
    }
    const int here = cur.points.back();
    if (r.where.vertex >= 0) {
      // A ray another curve already arrived by: a starting curve is that one (dropped), a
      // curve passing through ends here.
      if (used_ray(here, r.where.ray, c)) {
        finish(c, cur.segment_face.empty() ? CurveEnd::Stuck : CurveEnd::Curve);
        return;
      }
    }
    const int target = r.target;
    if (target >= 0) maybe_steer(r.where, [&](int x) { return x == target; });
    const Advance a = advance(r.where, [&](int x) { return x == target; });
    switch (a.kind) {
      case Advance::Kind::Stuck: finish(c, CurveEnd::Stuck); return;
      case Advance::Kind::Edge: step_edge(c, a); return;
      case Advance::Kind::Vertex: step_vertex(c, a); return;
      case Advance::Kind::Walk: step_walk(c, a); return;
      case Advance::Kind::Slide: step_slide(c, a); return;
    }
  }

  // The curve runs from its point on edge a.he along the edge to its end a.vertex.
  void step_slide(int c, const Advance& a) {
    TraceCurve& cur = graph_.curves[c];
    const int from = cur.points.back();
    const TracePoint& q = graph_.points[from];
    const int ce = q.element;
    const Rational t0 = q.t, t1 = Rational(a.vertex == mesh_.origin(ce) ? 0 : 1);
    const bool up = t0 < t1;
    ++graph_.stats.slides;
    // Another walk on the edge there, or a point between: the curve ends on it.
    if (auto it = edge_walks_.find(ce); it != edge_walks_.end())
      for (const EdgeWalk& w : it->second)
        if (up ? w.t1 > t0 : w.t0 < t0) {
          finish(c, CurveEnd::Stuck);
          return;
        }
    int first = -1;
    if (auto it = edge_points_.find(ce); it != edge_points_.end())
      for (int p : it->second) {
        const Rational& t = graph_.points[p].t;
        if (p == from || (up ? !(t > t0) : !(t < t0))) continue;
        if (first < 0 || (up ? t < graph_.points[first].t : t > graph_.points[first].t)) first = p;
      }
    // The curve keeps its field direction (a.dir in face a.face), so its rays stay those of a
    // straight curve; only its path runs along the edge.
    const int fc = a.face, dir = a.dir;
    if (first >= 0) {
      add_segment(c, first, -1, ray_of(first, fc, dir + 2));
      add_walk(c, ce, up ? t0 : graph_.points[first].t, up ? graph_.points[first].t : t0, fc, dir);
      finish(c, CurveEnd::Curve);
      return;
    }
    const int x = a.vertex, px = vertex_point(x);
    const int ra = arrival_ray_for(c, x, fc, frames_.direction(fc, dir + 2));
    add_segment(c, px, -1, ra);
    add_walk(c, ce, up ? t0 : t1, up ? t1 : t0, fc, dir);
    arrive(c, x, ra);
  }

  void leave_vertex_ray(int c) {
    Runner& r = runners_[c];
    if (r.where.vertex >= 0 && !used_ray(graph_.curves[c].points.back(), r.where.ray, -2 - c))
      use_ray(graph_.curves[c].points.back(), r.where.ray, c);
  }

  void step_edge(int c, const Advance& a) {
    const Point2q A = bary(graph_.curves[c].points.back(), a.face);
    leave_vertex_ray(c);
    step_edge_from(c, a, A);
  }

  void step_edge_from(int c, const Advance& a, const Point2q& A) {
    const int f = a.face, he = a.he, dir = a.dir;
    const int ce = canonical(mesh_, he);
    const Rational t = ce == he ? a.t : Rational(1 - a.t);
    TraceCurve& cur = graph_.curves[c];
    const Point2q B = edge_bary(he, a.t);
    if (const auto m = first_meet(f, A, B)) {
      end_at_meet(c, f, dir, *m);
      return;
    }
    const int existing = find_edge_point(ce, t);
    const int q = existing >= 0 ? existing : edge_point(ce, t);
    add_segment(c, q, f, ray_of(q, f, dir + 2));
    record_face_segment(c, f, dir);
    if (existing >= 0) {
      finish(c, CurveEnd::Curve);
      return;
    }
    if (const EdgeWalk* w = walk_at(ce, t)) {
      hits_.push_back({w->curve, w->segment, q});
      finish(c, CurveEnd::Curve);
      return;
    }
    const int tw = mesh_.twin(he);
    if (tw < 0) {
      finish(c, CurveEnd::Boundary);
      return;
    }
    Runner& r = runners_[c];
    const int steer = r.where.steer;
    r.where = Where{};
    r.where.face = TriMesh::face(tw);
    r.where.he = tw;
    r.where.s = 1 - a.t;
    r.where.dir = (dir + frames_.shift[he]) % 4;
    r.where.steer = steer;
    cur.ray_forward.back() = ray_of(q, r.where.face, r.where.dir);
  }

  // The curve reaches vertex x (a corner of its face) inside face a.face.
  void step_vertex(int c, const Advance& a) {
    const int f = a.face, x = a.vertex;
    TraceCurve& cur = graph_.curves[c];
    const int px = vertex_point(x);
    const Point2q A = bary(cur.points.back(), f), B = bary(px, f);
    leave_vertex_ray(c);
    if (const auto m = first_meet(f, A, B)) {
      if (m->point != px) {
        // The way into the vertex (not along the field) is barred: go on by the edge exit.
        if (a.alt_he >= 0) {
          Advance e = a;
          e.kind = Advance::Kind::Edge;
          e.he = a.alt_he;
          e.t = a.alt_t;
          e.alt_he = -1;
          step_edge_from(c, e, A);
          return;
        }
        end_at_meet(c, f, a.dir, *m);
        return;
      }
    }
    const Runner& r = runners_[c];
    (void)r;
    const int ra = arrival_ray_for(c, x, f, frames_.direction(f, a.dir + 2));
    const bool blocked = ra < 0;
    if (blocked) ++graph_.stats.blocked_arrivals;
    if (blocked && a.alt_he >= 0) {
      // Not by a ray another curve holds: pass the vertex by on the clamped edge exit.
      Advance e = a;
      e.kind = Advance::Kind::Edge;
      e.he = a.alt_he;
      e.t = a.alt_t;
      e.alt_he = -1;
      step_edge_from(c, e, A);
      return;
    }
    add_segment(c, px, f, ra);
    record_face_segment(c, f, a.dir);
    arrive(c, x, ra);
  }

  // A walk along mesh edge a.he from the curve's vertex.
  void step_walk(int c, const Advance& a) {
    const int h = a.he, b = a.vertex;
    const int ce = canonical(mesh_, h);
    const bool forward = ce == h;
    TraceCurve& cur = graph_.curves[c];
    if (edge_walks_.count(ce)) {
      finish(c, cur.segment_face.empty() ? CurveEnd::Stuck : CurveEnd::Curve);
      return;
    }
    leave_vertex_ray(c);
    int first = -1;
    if (auto it = edge_points_.find(ce); it != edge_points_.end())
      for (int p : it->second)
        if (first < 0 || (forward ? graph_.points[p].t < graph_.points[first].t : graph_.points[p].t > graph_.points[first].t))
          first = p;
    const int fh = TriMesh::face(h);
    const int tw = mesh_.twin(h);
    const int dir_h = a.face == fh ? a.dir : (tw >= 0 && a.face == TriMesh::face(tw) ? (a.dir + frames_.shift[tw]) % 4 : a.dir);
    if (first >= 0) {
      add_segment(c, first, -1, ray_of(first, fh, dir_h + 2));
      add_walk(c, ce, forward ? Rational(0) : graph_.points[first].t, forward ? graph_.points[first].t : Rational(1), fh, dir_h);
      finish(c, CurveEnd::Curve);
      return;
    }
    const Runner& r = runners_[c];
    (void)r;
    const int ra = arrival_ray_for(c, b, fh, frames_.direction(fh, dir_h + 2));
    if (ra < 0) ++graph_.stats.blocked_arrivals;
    add_segment(c, vertex_point(b), -1, ra);
    add_walk(c, ce, Rational(0), Rational(1), fh, dir_h);
    arrive(c, b, ra);
  }

  // Whether ray k of vertex x may take curve c's arrival: not held by another curve, not a
  // boundary ray, not kept for another paired curve.
  bool ray_free(int x, int k, int c) {
    const int px = vertex_point(x);
    const VertexRays& rx = rays(x);
    const int nr = static_cast<int>(rx.rays.size());
    if (k < 0 || k >= nr || used_ray(px, k, c) || (rx.boundary && (k == 0 || k == nr - 1))) return false;
    const Runner& r = runners_[c];
    if (reserved_.count({px, k}) && !(r.target == x && r.target_ray == k)) return false;
    return true;
  }
  // The ray curve c arrives by at vertex x, coming in along `back` (face f; pointing back along
  // the curve): its target ray if x is its paired cone, else the nearest free one (keeping order).
  int arrival_ray_for(int c, int x, int f, const Vec2d& back) {
    const Runner& r = runners_[c];
    if (r.target == x && ray_free(x, r.target_ray, c)) return r.target_ray;
    return nearest_free_ray(x, f, back, [&](int k) { return ray_free(x, k, c); });
  }

  // The curve has arrived at vertex x by ray ra of x: it ends there or goes straight on.
  void arrive(int c, int x, int ra) {
    const int px = vertex_point(x);
    if (ra < 0) {
      // Every ray on its side of the vertex is taken: the curve runs along one of those curves.
      if (!drop_curve(c)) finish(c, CurveEnd::Stuck);
      return;
    }
    const VertexRays& rx = rays(x);
    const bool taken = used_ray(px, ra, c);
    use_ray(px, ra, c);
    if (traced_[x]) {
      finish(c, taken ? CurveEnd::Curve : CurveEnd::Cone);
      on_curve_vertex_[x] = 1;
      return;
    }
    if (on_curve_vertex_[x] || taken) {
      finish(c, CurveEnd::Curve);
      return;
    }
    on_curve_vertex_[x] = 1;
    if (rx.boundary || rx.valence != 4) {
      finish(c, rx.boundary ? CurveEnd::Boundary : CurveEnd::Cone);
      return;
    }
    ++graph_.stats.vertex_passes;
    Runner& r = runners_[c];
    r.where = Where{};
    r.where.vertex = x;
    r.where.ray = (ra + 2) % 4;
    graph_.curves[c].ray_forward.back() = r.where.ray;
  }

  // Inserts every T-junction point into the curve it lies on, in order along the segment.
  void apply_hits() {
    std::sort(hits_.begin(), hits_.end(), [](const Hit& a, const Hit& b) {
      return a.curve != b.curve ? a.curve < b.curve : a.segment != b.segment ? a.segment > b.segment : a.point < b.point;
    });
    std::size_t i = 0;
    while (i < hits_.size()) {
      std::size_t j = i;
      while (j < hits_.size() && hits_[j].curve == hits_[i].curve && hits_[j].segment == hits_[i].segment) ++j;
      TraceCurve& cur = graph_.curves[hits_[i].curve];
      const int s = hits_[i].segment, f = cur.segment_face[s];
      std::vector<int> pts;
      for (std::size_t k = i; k < j; ++k) pts.push_back(hits_[k].point);
      if (f >= 0) {
        const Point2q A = bary(cur.points[s], f), B = bary(cur.points[s + 1], f);
        const bool inc = compare_lex(A, B) == Sign::Negative;
        std::sort(pts.begin(), pts.end(), [&](int a, int b) {
          const Sign sg = compare_lex(bary(a, f), bary(b, f));
          return inc ? sg == Sign::Negative : sg == Sign::Positive;
        });
      } else {
        const TracePoint& a = graph_.points[cur.points[s]];
        const int ce = graph_.points[pts[0]].element;
        const bool inc = a.kind == TracePoint::Kind::Vertex ? a.element == mesh_.origin(ce)
                                                            : a.kind == TracePoint::Kind::Edge && a.t < graph_.points[pts[0]].t;
        std::sort(pts.begin(), pts.end(), [&](int x, int y) {
          return inc ? graph_.points[x].t < graph_.points[y].t : graph_.points[x].t > graph_.points[y].t;
        });
      }
      pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
      int dir = -1, dir_face = f;
      if (f >= 0) {
        for (const FaceSegment& fs : face_segments_[f])
          if (fs.curve == hits_[i].curve && fs.segment == s) dir = fs.dir;
      } else {
        // The segment walks along the edge its T-junction points lie on: that edge's walks first,
        // every edge's only if it is not there (a point not on an edge).
        auto take = [&](const std::vector<EdgeWalk>& walks) {
          for (const EdgeWalk& w : walks)
            if (w.curve == hits_[i].curve && w.segment == s) dir = w.dir, dir_face = w.face;
        };
        const TracePoint& q = graph_.points[pts[0]];
        if (q.kind == TracePoint::Kind::Edge)
          if (const auto it = edge_walks_.find(q.element); it != edge_walks_.end()) take(it->second);
        if (dir < 0)
          for (const auto& entry : edge_walks_) take(entry.second);
      }
      if (dir < 0) throw Error(ErrorKind::Internal, "trace: a T-junction on a segment that was not recorded");
      std::vector<int> rb, rf;
      for (int p : pts) {
        rb.push_back(ray_of(p, dir_face, dir + 2));
        rf.push_back(ray_of(p, dir_face, dir));
      }
      cur.points.insert(cur.points.begin() + s + 1, pts.begin(), pts.end());
      cur.segment_face.insert(cur.segment_face.begin() + s + 1, pts.size(), f);
      cur.ray_back.insert(cur.ray_back.begin() + s + 1, rb.begin(), rb.end());
      cur.ray_forward.insert(cur.ray_forward.begin() + s + 1, rf.begin(), rf.end());
      i = j;
    }
  }

  void compact_points() {
    TraceGraph& g = graph_;
    std::vector<char> used(g.points.size(), 0);
    for (const TraceCurve& c : g.curves)
      for (int p : c.points) used[p] = 1;
    std::vector<int> id(g.points.size(), -1);
    int n = 0;
    for (std::size_t p = 0; p < g.points.size(); ++p)
      if (used[p]) id[p] = n++;
    if (n == static_cast<int>(g.points.size())) return;
    std::vector<TracePoint> points(n);
    std::vector<int> count(n);
    std::vector<char> cyclic(n);
    for (std::size_t p = 0; p < g.points.size(); ++p)
      if (id[p] >= 0) points[id[p]] = std::move(g.points[p]), count[id[p]] = g.ray_count[p], cyclic[id[p]] = g.ray_cyclic[p];
    g.points = std::move(points);
    g.ray_count = std::move(count);
    g.ray_cyclic = std::move(cyclic);
    for (TraceCurve& c : g.curves)
      for (int& p : c.points) p = id[p];
  }

  void finish_stats() {
    TraceStats& st = graph_.stats;
    st.curves = static_cast<int>(graph_.curves.size());
    for (const TraceCurve& c : graph_.curves) {
      switch (c.end) {
        case CurveEnd::Curve: ++st.ends_on_curves; break;
        case CurveEnd::Cone: ++st.ends_at_cones; break;
        case CurveEnd::Boundary: ++st.ends_on_boundary; break;
        case CurveEnd::Bound: ++st.ends_at_bound; break;
        case CurveEnd::Stuck: ++st.ends_stuck; break;
      }
    }
  }

  const TriMesh& mesh_;
  double scale_ = 1;
  std::vector<Vec3d> positions_;  // the input's, times scale_
  std::unique_ptr<FieldFrames> own_frames_;  // when none are given
  const FieldFrames& frames_;
  TraceOptions options_;
  TraceReuse* reuse_ = nullptr;
  int bits_ = 24, max_segments_ = 0;
  std::vector<VertexRays> rays_;
  std::vector<char> rays_done_;
  std::vector<int> vertex_point_;
  std::vector<char> on_curve_vertex_;  // per vertex: a curve starts, ends or passes there
  std::vector<char> traced_;           // per vertex: its rays are traced (cone, boundary corner, seed)
  std::unordered_map<int, std::vector<int>> edge_points_;
  std::unordered_map<int, std::vector<FaceSegment>> face_segments_;
  std::unordered_map<int, std::vector<EdgeWalk>> edge_walks_;
  std::set<int> walled_edges_;  // canonical half-edges of the walls
  std::unordered_map<int, std::vector<std::pair<int, int>>> vertex_rays_used_;
  std::vector<Hit> hits_;
  std::vector<int> point_uses_;  // per point: occurrences in curves
  std::unordered_map<int, std::vector<int>> point_curves_;  // point -> curves through it (may repeat)
  double mean_edge_ = 0;
  double steer_length_ = 0;
  std::unordered_map<std::uint64_t, std::vector<int>> traced_hash_;  // steering: traced vertices by cell
  std::unordered_set<std::uint64_t> near_cells_;                     // the cells next to (or of) one of them
  std::vector<char> dead_;       // per point: cut away with a merged curve
  std::vector<int> finished_elsewhere_;   // curves finished by another's step (merges)
  std::set<std::pair<int, int>> reserved_;  // (vertex point, ray) kept for a paired curve's arrival
  std::set<std::pair<int, int>> banned_;    // (vertex, ray) not traced
  std::vector<Runner> runners_;
  TraceGraph graph_;
};

}  // namespace

namespace {
void check_trace_inputs(const TriMesh& mesh, const std::vector<Vec3d>& positions, const std::vector<Vec3d>& face_direction,
                        const TraceOptions& options) {
  if (static_cast<int>(positions.size()) != mesh.num_vertices() ||
      static_cast<int>(face_direction.size()) != mesh.num_faces())
    throw Error(ErrorKind::InvalidArgument, "trace_motorcycles: positions or face directions do not match the mesh");
  if (options.parameter_bits < 2 || options.parameter_bits > 40)
    throw Error(ErrorKind::InvalidArgument, "trace_motorcycles: parameter_bits must be in 2..40");
}
}  // namespace

TraceGraph trace_motorcycles(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                             const std::vector<Vec3d>& face_direction, const TraceOptions& options) {
  check_trace_inputs(mesh, positions, face_direction, options);
  Tracer tracer(mesh, positions, face_direction, options);
  return tracer.run(options.seeds);
}

TraceGraph field_detail::trace_motorcycles_reusing(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                                                   const std::vector<Vec3d>& face_direction, const TraceOptions& options,
                                                   const FieldFrames& frames, TraceReuse& reuse) {
  check_trace_inputs(mesh, positions, face_direction, options);
  Tracer tracer(mesh, positions, face_direction, options, &frames, &reuse);
  return tracer.run(options.seeds);
}

}  // namespace igm

namespace igm {

namespace {

// The canonical half-edges a point lies on (its edge, or every edge at a vertex is not listed:
// vertices are handled by the caller).
bool on_edge(const TriMesh& mesh, const TracePoint& q, int ce) {
  if (q.kind == TracePoint::Kind::Edge) return q.element == ce;
  if (q.kind == TracePoint::Kind::Vertex) return mesh.origin(ce) == q.element || mesh.target(ce) == q.element;
  return false;
}

}  // namespace

std::string check_trace_graph(const TriMesh& mesh, const TraceGraph& g) {
  const int np = static_cast<int>(g.points.size());
  if (static_cast<int>(g.ray_count.size()) != np || static_cast<int>(g.ray_cyclic.size()) != np)
    return "ray numbering sizes do not match the points";
  for (int p = 0; p < np; ++p) {
    const TracePoint& q = g.points[p];
    const std::string id = "point " + std::to_string(p);
    switch (q.kind) {
      case TracePoint::Kind::Vertex:
        if (q.element < 0 || q.element >= mesh.num_vertices()) return id + ": vertex out of range";
        break;
      case TracePoint::Kind::Edge: {
        if (q.element < 0 || q.element >= mesh.num_halfedges()) return id + ": half-edge out of range";
        const int t = mesh.twin(q.element);
        if (t >= 0 && t < q.element) return id + ": not on the canonical half-edge";
        if (!(q.t > 0 && q.t < 1)) return id + ": edge parameter not inside (0,1)";
        break;
      }
      case TracePoint::Kind::Face:
        if (q.element < 0 || q.element >= mesh.num_faces()) return id + ": face out of range";
        if (!(q.w[0] > 0 && q.w[1] > 0 && q.w[2] > 0) || q.w[0] + q.w[1] + q.w[2] != 1)
          return id + ": barycentric weights not positive or not summing to 1";
        break;
    }
  }
  struct Seg {
    int curve, index;
    Point2q a, b;
    int pa, pb;
  };
  std::unordered_map<int, std::vector<Seg>> by_face;
  std::unordered_map<int, std::vector<std::pair<int, int>>> by_edge;  // canonical edge -> (curve, segment)
  for (int c = 0; c < static_cast<int>(g.curves.size()); ++c) {
    const TraceCurve& cur = g.curves[c];
    const std::string id = "curve " + std::to_string(c);
    const std::size_t n = cur.points.size();
    if (n < 2 || cur.segment_face.size() != n - 1 || cur.ray_back.size() != n || cur.ray_forward.size() != n)
      return id + ": inconsistent sizes";
    for (std::size_t i = 0; i < n; ++i) {
      const int p = cur.points[i];
      if (p < 0 || p >= np) return id + ": point id out of range";
      for (int r : {cur.ray_back[i], cur.ray_forward[i]})
        if (r < -1 || r >= g.ray_count[p]) return id + ": ray out of range at point " + std::to_string(p);
    }
    for (std::size_t i = 0; i + 1 < n; ++i) {
      const int pa = cur.points[i], pb = cur.points[i + 1];
      if (pa == pb) return id + ": a segment of zero length";
      const int f = cur.segment_face[i];
      if (f >= 0) {
        if (f >= mesh.num_faces()) return id + ": segment face out of range";
        const auto a = field_detail::point_in_face_if(mesh, g.points[pa], f), b = field_detail::point_in_face_if(mesh, g.points[pb], f);
        if (!a || !b) return id + ": segment " + std::to_string(i) + " has an end outside its face " + std::to_string(f);
        by_face[f].push_back({c, static_cast<int>(i), *a, *b, pa, pb});
      } else {
        // Along a mesh edge: find the edge both ends lie on.
        int found = -1;
        const TracePoint &qa = g.points[pa], &qb = g.points[pb];
        std::vector<int> cands;
        if (qa.kind == TracePoint::Kind::Edge) cands.push_back(qa.element);
        else if (qb.kind == TracePoint::Kind::Edge) cands.push_back(qb.element);
        else if (qa.kind == TracePoint::Kind::Vertex && qb.kind == TracePoint::Kind::Vertex) {
          int h = -1;
          for (int x = 0; x < mesh.num_halfedges() && h < 0; ++x)
            if (mesh.origin(x) == qa.element && mesh.target(x) == qb.element) h = x;
          if (h >= 0) cands.push_back(mesh.twin(h) >= 0 && mesh.twin(h) < h ? mesh.twin(h) : h);
        }
        for (int ce : cands)
          if (on_edge(mesh, qa, ce) && on_edge(mesh, qb, ce)) found = ce;
        if (found < 0) return id + ": segment " + std::to_string(i) + " is not along a mesh edge";
        by_edge[found].push_back({c, static_cast<int>(i)});
      }
    }
  }
  for (const auto& [f, segs] : by_face) {
    for (std::size_t i = 0; i < segs.size(); ++i)
      for (std::size_t j = i + 1; j < segs.size(); ++j) {
        const Seg &s = segs[i], &t = segs[j];
        const SegmentRelation rel = classify(s.a, s.b, t.a, t.b);
        if (rel == SegmentRelation::Disjoint) continue;
        const std::string what = "curves " + std::to_string(s.curve) + " and " + std::to_string(t.curve) + " in face " +
                                 std::to_string(f);
        if (rel != SegmentRelation::Touching) return what + ": segments cross or overlap";
        const auto x = intersection(s.a, s.b, t.a, t.b);
        const bool shared = x && ((same(*x, s.a) && (s.pa == t.pa || s.pa == t.pb)) || (same(*x, s.b) && (s.pb == t.pa || s.pb == t.pb)));
        if (!shared) return what + ": segments touch away from a shared point";
      }
  }
  // Walks along one edge may be split at points but never overlap.
  auto param = [&](const TracePoint& q, int ce) {
    if (q.kind == TracePoint::Kind::Edge) return q.t;
    return Rational(q.element == mesh.origin(ce) ? 0 : 1);
  };
  for (const auto& [ce, segs] : by_edge) {
    std::vector<std::pair<Rational, Rational>> spans;
    for (const auto& [c, i] : segs) {
      Rational a = param(g.points[g.curves[c].points[i]], ce), b = param(g.points[g.curves[c].points[i + 1]], ce);
      if (b < a) std::swap(a, b);
      spans.push_back({a, b});
    }
    std::sort(spans.begin(), spans.end());
    for (std::size_t k = 1; k < spans.size(); ++k)
      if (spans[k].first < spans[k - 1].second) return "edge " + std::to_string(ce) + ": walked twice";
  }
  return "";
}

}  // namespace igm
