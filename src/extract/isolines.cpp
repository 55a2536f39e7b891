#include "igm/extract/isolines.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <string>
#include <utility>

#include "../core/parallel.h"
#include "igm/core/error.h"
#include "isolines_internal.h"

namespace igm {

namespace {

using isolines::apply;
using isolines::axis_of;
using isolines::Charts;
using isolines::find_grid_points;
using isolines::find_point;
using isolines::Grid2;
using isolines::GridPoint;
using isolines::GridPoints;
using isolines::Heading;
using isolines::in_wedge;
using isolines::kDx;
using isolines::kDy;
using Clock = std::chrono::steady_clock;

constexpr long kMaxUv = 1L << 60;  // |UV coordinate| bound: every integer sum below fits in 64 bits
constexpr std::int64_t kChunk = 4096;  // triangles or half-edges per parallel chunk (core/parallel.h)

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

[[noreturn]] void broken(const std::string& what, std::int64_t id) {
  throw Error(ErrorKind::Internal, "extract_isolines: " + what, {id});
}

bool is_integer(const Rational& q) { return mpz_cmp_ui(q.get_den_mpz_t(), 1) == 0; }

void set_point(Point2q& p, const Grid2& g) {
  mpq_set_si(p.x.get_mpq_t(), static_cast<long>(g.x), 1UL);
  mpq_set_si(p.y.get_mpq_t(), static_cast<long>(g.y), 1UL);
}

// The seams: per half-edge h (face f, corner i -> i+1) the k and t with uv_g = R^k uv_f + t on both
// ends, g the twin's face, found as the certifier defines them (certify/README.md, check 3).
void seams_of(Charts& c, int h0, int h1);

// In parallel (core/parallel.h); of several broken seams the first half-edge's is reported.
void build_seams(Charts& c) {
  const int H = c.mesh.num_halfedges();
  c.k.assign(H, 0);
  c.t.assign(H, Grid2{});
  std::vector<std::exception_ptr> failure((H + kChunk - 1) / kChunk);
  parallel::for_chunks(H, kChunk, [&](std::int64_t b, std::int64_t e) {
    try {
      seams_of(c, static_cast<int>(b), static_cast<int>(e));
    } catch (...) {
      failure[b / kChunk] = std::current_exception();
    }
  });
  for (const std::exception_ptr& x : failure)
    if (x) std::rethrow_exception(x);
}

// The seams of half-edges [h0, h1).
void seams_of(Charts& c, int h0, int h1) {
  Rational ex, ey, gx, gy, rx, ry, tx, ty;
  for (int h = h0; h < h1; ++h) {  // bound: 3F half-edges
    const int tw = c.mesh.twin(h);
    if (tw < 0) continue;  // a boundary half-edge: no seam
    // The ends a, b in h's triangle and the same ends a2, b2 in the twin's.
    const Point2q &a = c.corner(h), &b = c.corner(TriMesh::next(h));
    const Point2q &b2 = c.corner(tw), &a2 = c.corner(TriMesh::next(tw));
    // Inside a chart (the same UVs on both sides): k = 0, t = 0.
    if (a.x == a2.x && a.y == a2.y && b.x == b2.x && b.y == b2.y) continue;
    ex = b.x - a.x;
    ey = b.y - a.y;
    gx = b2.x - a2.x;
    gy = b2.y - a2.y;
    int found = -1;
    for (int k = 0; k < 4 && found < 0; ++k) {  // bound: 4; (rx, ry) = R^k (ex, ey)
      if (k == 0) {
        rx = ex;
        ry = ey;
      } else {
        std::swap(rx, ry);
        rx = -rx;
      }
      if (rx == gx && ry == gy) found = k;
    }
    if (found < 0)
      broken("the edge of half-edge " + std::to_string(h) + " has no rotation seam", h);
    // t = a2 - R^k a
    switch (found) {
      case 0:
        tx = a2.x - a.x;
        ty = a2.y - a.y;
        break;
      case 1:
        tx = a2.x + a.y;
        ty = a2.y - a.x;
        break;
      case 2:
        tx = a2.x + a.x;
        ty = a2.y + a.y;
        break;
      default:
        tx = a2.x - a.y;
        ty = a2.y + a.x;
        break;
    }
    if (!is_integer(tx) || !is_integer(ty))
      broken("the seam of half-edge " + std::to_string(h) + " has no integer translation", h);
    c.k[h] = static_cast<signed char>(found);
    c.t[h] = {mpz_get_si(tx.get_num_mpz_t()), mpz_get_si(ty.get_num_mpz_t())};
  }
}

// Step 2's start: per grid point its outgoing directions, counter-clockwise; slot s leaves grid
// point point[s] in triangle face[s] along axis m[s] from the integer point start[s] of its chart.
// A grid point on the boundary has the closed wedge from the boundary's forward direction (its
// first slot) counter-clockwise to the boundary's backward one (its last slot).
struct Slots {
  std::vector<int> begin;  // per grid point, size points + 1
  std::vector<int> point, face, m;
  std::vector<Grid2> start;
  std::vector<char> boundary;  // per grid point: on the boundary
};

void add_slot(Slots& s, int point, int face, int m, const Grid2& at) {
  s.point.push_back(point);
  s.face.push_back(face);
  s.m.push_back(m);
  s.start.push_back(at);
}

// Appends the axis directions in the half-open wedge [a - o, b - o) counter-clockwise.
void add_wedge(Slots& s, int point, int face, const Point2q& o, const Point2q& a, const Point2q& b,
               const Grid2& at) {
  bool in[4];
  for (int m = 0; m < 4; ++m) in[m] = in_wedge(o, a, b, m);
  int first = 0;
  while (first < 4 && !(in[first] && !in[(first + 3) % 4])) ++first;  // bound: 4
  if (first == 4) return;  // empty (a wedge of angle < 2 pi holds no full circle)
  for (int i = 0; i < 4 && in[(first + i) % 4]; ++i)  // bound: 4
    add_slot(s, point, face, (first + i) % 4, at);
}

Slots make_slots(const Charts& c, const GridPoints& gp) {
  Slots s;
  const int n = static_cast<int>(gp.points.size());
  s.begin.reserve(n + 1);
  s.boundary.assign(n, 0);
  Point2q o;
  for (int p = 0; p < n; ++p) {  // bound: grid points
    s.begin.push_back(static_cast<int>(s.point.size()));
    const GridPoint& q = gp.points[p];
    const std::array<Point2q, 3>& x = (*c.uv)[q.face];
    if (q.kind == GridPointKind::Face) {
      for (int m = 0; m < 4; ++m) {
        s.point.push_back(p);
        s.face.push_back(q.face);
        s.m.push_back(m);
        s.start.push_back(q.uv);
      }
    } else if (q.kind == GridPointKind::Edge) {
      // The side's triangle from the side's direction to its reverse, then the twin's likewise;
      // inside a boundary side the reverse itself closes the half-plane.
      const int he = 3 * q.face + q.local, tw = c.mesh.twin(he), g = tw / 3, i = tw % 3;
      set_point(o, q.uv);
      add_wedge(s, p, q.face, o, x[(q.local + 1) % 3], x[q.local], q.uv);
      if (tw < 0) {
        s.boundary[p] = 1;
        const int back = axis_of(o, x[q.local]);
        if (back < 0)
          broken("the boundary side of triangle " + std::to_string(q.face) +
                     " through grid point " + std::to_string(p) + " is on no isoline",
                 p);
        add_slot(s, p, q.face, back, q.uv);
      } else {
        const Grid2 other = apply(c.k[he], q.uv, c.t[he]);
        set_point(o, other);
        add_wedge(s, p, g, o, (*c.uv)[g][(i + 1) % 3], (*c.uv)[g][i], other);
      }
      const int expected = tw < 0 ? 3 : 4;
      if (static_cast<int>(s.point.size()) - s.begin[p] != expected)
        broken("grid point " + std::to_string(p) + " inside an edge of triangle " +
                   std::to_string(q.face) + " has " +
                   std::to_string(static_cast<int>(s.point.size()) - s.begin[p]) +
                   " isoline directions, not " + std::to_string(expected),
               p);
    } else {
      // Around the vertex counter-clockwise, each triangle's corner wedge in its own chart; at a
      // boundary vertex from the first corner of its fan to the last, then its closing direction.
      const int v = (*c.triangles)[q.face][q.local];
      Heading first{q.face, q.local, 0, Grid2{}};
      const bool open = isolines::rewind_to_fan_start(c, first);
      s.boundary[p] = open;
      int face = first.face, corner = first.corner, steps = 0;
      while (steps < c.degree[v]) {  // bound: the degree of v
        const std::array<Point2q, 3>& y = (*c.uv)[face];
        if (!is_integer(y[corner].x) || !is_integer(y[corner].y))
          broken("vertex " + std::to_string(v) + " is a grid point in one triangle only", v);
        const Grid2 at{mpz_get_si(y[corner].x.get_num_mpz_t()),
                       mpz_get_si(y[corner].y.get_num_mpz_t())};
        add_wedge(s, p, face, y[corner], y[(corner + 1) % 3], y[(corner + 2) % 3], at);
        ++steps;
        const int tw = c.mesh.twin(3 * face + (corner + 2) % 3);
        if (tw < 0) {
          const int back = isolines::closing_axis(c, face, corner);
          if (back < 0)
            broken("a boundary edge at vertex " + std::to_string(v) + " is on no isoline", v);
          add_slot(s, p, face, back, at);
          break;
        }
        face = tw / 3;
        corner = tw % 3;
      }
      if (open ? steps != c.degree[v] : (face != first.face || corner != first.corner))
        broken("the triangles around vertex " + std::to_string(v) + " do not close", v);
      if (static_cast<int>(s.point.size()) == s.begin[p])
        broken("grid point " + std::to_string(p) + " (vertex " + std::to_string(v) +
                   ") has no isoline direction",
               p);
    }
  }
  s.begin.push_back(static_cast<int>(s.point.size()));
  return s;
}

// The slot of grid point p leaving along the reverse of a trace's arrival `end`, or -1.
int arrival_slot(const Charts& c, const Slots& s, int p, const isolines::TraceEnd& end,
                 Point2q& scratch) {
  Heading at = end.at;
  at.m = (at.m + 2) & 3;
  if (at.corner >= 0) {
    // The reverse direction lies in at.face's closed wedge: this triangle's or the next one's.
    at = isolines::turn_to_wedge(c, at, false);
  } else if (end.side >= 0) {
    const std::array<Point2q, 3>& x = (*c.uv)[at.face];
    const int i = end.side;
    set_point(scratch, at.target);
    const int he = 3 * at.face + i;
    // The reverse points into the twin; on a boundary side it runs back along the side, which
    // this triangle holds (the closed half-plane).
    if (!in_wedge(scratch, x[(i + 1) % 3], x[i], at.m) && c.mesh.twin(he) >= 0) {
      at.m = (at.m + c.k[he]) & 3;
      at.face = c.mesh.twin(he) / 3;
    }
  }
  for (int q = s.begin[p]; q < s.begin[p + 1]; ++q)  // bound: the valence of p
    if (s.face[q] == at.face && s.m[q] == at.m) return q;
  return -1;
}

}  // namespace

namespace {

// Step 2 for the slots [q0, q1): each slot's unit segment traced (trace), its arrival slot at the
// grid point where it ends (arrival), its triangle steps and vertex crossings.
void trace_slots(const Charts& c, const GridPoints& gp, const Slots& s, int q0, int q1, std::vector<int>& arrival,
                 std::vector<std::int64_t>& steps, std::vector<std::int64_t>& crossings) {
  Point2q scratch;
  for (int q = q0; q < q1; ++q) {  // bound: slots; each trace bounded by trace_step_bound triangles
    const int p = s.point[q];
    Heading h{s.face[q], -1, s.m[q], Grid2{s.start[q].x + kDx[s.m[q]], s.start[q].y + kDy[s.m[q]]}};
    const isolines::TraceEnd end = isolines::trace(c, h, gp.chords, p);
    steps[q] = end.steps;
    crossings[q] = end.vertex_crossings;
    const int to = find_point(c, gp, end.at.face, end.at.corner, end.side, end.at.target);
    if (to < 0)
      broken("the isoline from grid point " + std::to_string(p) + " along its direction " +
                 std::to_string(q - s.begin[p]) + " ends at (" + std::to_string(end.at.target.x) +
                 ", " + std::to_string(end.at.target.y) + ") of triangle " +
                 std::to_string(end.at.face) + ", which is no grid point found",
             p);
    arrival[q] = arrival_slot(c, s, to, end, scratch);
    if (arrival[q] < 0 || arrival[q] == q)
      broken("the isoline from grid point " + std::to_string(p) + " along its direction " +
                 std::to_string(q - s.begin[p]) + " arrives at grid point " + std::to_string(to) +
                 " along no direction of it",
             p);
  }
}

}  // namespace

IsolineResult extract_isolines(const IsolineInput& input, const IsolineOptions& options) {
  const auto t_total = Clock::now();
  if (options.max_grid_work < 1 || options.max_grid_work > (std::int64_t{1} << 28))
    throw Error(ErrorKind::InvalidArgument,
                "IsolineOptions::max_grid_work must be in 1..2^28, got " +
                    std::to_string(options.max_grid_work));
  IsolineResult result;
  IsolineStats stats;
  {
    auto t0 = Clock::now();
    certify::IgmInput cin;
    cin.faces = input.triangles;
    cin.num_vertices =
        input.positions.empty() ? -1 : static_cast<std::int64_t>(input.positions.size());
    cin.corner_uv.reserve(3 * input.corner_uv.size());
    for (const auto& tri : input.corner_uv)
      for (const Point2q& uv : tri) cin.corner_uv.push_back({uv.x, uv.y});
    certify::Options copt;
    copt.max_witnesses = options.max_witnesses;
    copt.allow_boundary = options.allow_boundary;
    copt.allow_components = options.allow_components;
    copt.threads = options.threads;
    copt.feature_edges = options.feature_edges;
    result.report = certify::certify_igm(std::move(cin), copt);
    stats.seconds_certify = seconds_since(t0);
  }
  if (!result.report.valid()) return result;

  // The certified IGM: manifold, oriented, positive UV triangles, rigid seams; closed and connected
  // unless allowed, every boundary edge on an integer isoline.
  auto t0 = Clock::now();
  const int F = static_cast<int>(input.triangles.size());
  int V = static_cast<int>(result.report.num_vertices);
  Charts c;
  c.triangles = &input.triangles;
  c.uv = &input.corner_uv;
  c.mesh = TriMesh::from_triangles(V, input.triangles, /*allow_boundary=*/true);
  c.degree.assign(V, 0);
  for (const auto& tri : input.triangles)
    for (int v : tri) ++c.degree[v];
  c.floors.resize(3 * static_cast<std::size_t>(F));
  // In parallel (core/parallel.h); the first triangle beyond the bound is named.
  const int too_large = parallel::reduce_chunks<int>(
      F, kChunk, -1,
      [&](std::int64_t b, std::int64_t e) {
        mpz_class fl;
        for (std::int64_t f = b; f < e; ++f)  // bound: F
          for (int i = 0; i < 3; ++i)
            for (int axis = 0; axis < 2; ++axis) {
              const Rational& q = axis == 0 ? input.corner_uv[f][i].x : input.corner_uv[f][i].y;
              if (mpq_cmp_si(q.get_mpq_t(), kMaxUv, 1UL) > 0 || mpq_cmp_si(q.get_mpq_t(), -kMaxUv, 1UL) < 0)
                return static_cast<int>(f);
              mpz_fdiv_q(fl.get_mpz_t(), q.get_num_mpz_t(), q.get_den_mpz_t());
              c.floors[3 * f + i].floor[axis] = mpz_get_si(fl.get_mpz_t());
              c.floors[3 * f + i].integer[axis] = is_integer(q);
            }
        return -1;
      },
      [](int a, int b) { return a >= 0 ? a : b; });
  if (too_large >= 0)
    throw Error(ErrorKind::TooLarge,
                "extract_isolines: triangle " + std::to_string(too_large) + " has a UV coordinate beyond 2^60",
                {too_large});
  build_seams(c);
  const GridPoints gp = find_grid_points(c, options.max_grid_work);
  stats.rows_scanned = gp.rows;
  const int n = static_cast<int>(gp.points.size());
  if (n == 0) broken("no grid point on the surface (a valid IGM has one at least)", 0);
  const Slots s = make_slots(c, gp);
  stats.seconds_grid = seconds_since(t0);

  // Step 2: trace every slot's unit segment; it must end at a grid point that sends it back.
  t0 = Clock::now();
  const int S = static_cast<int>(s.point.size());
  std::vector<int> arrival(S, -1);
  stats.trace_step_bound = gp.chords;
  // The traces are independent: in parallel (core/parallel.h), each slot's counts kept and summed
  // after in slot order; of several failures the first slot's is reported.
  std::vector<std::int64_t> steps(S, 0), crossings(S, 0);
  std::vector<std::exception_ptr> failure((S + 255) / 256);
  parallel::for_chunks(S, 256, [&](std::int64_t b, std::int64_t e) {
    try {
      trace_slots(c, gp, s, static_cast<int>(b), static_cast<int>(e), arrival, steps, crossings);
    } catch (...) {
      failure[b / 256] = std::current_exception();
    }
  });
  for (const std::exception_ptr& x : failure)
    if (x) std::rethrow_exception(x);
  for (int q = 0; q < S; ++q) {
    ++stats.traces;
    stats.trace_steps += steps[q];
    stats.max_trace_steps = std::max(stats.max_trace_steps, steps[q]);
    stats.vertex_crossings += crossings[q];
  }
  for (int q = 0; q < S; ++q)  // bound: slots
    if (arrival[arrival[q]] != q)
      broken("the isoline from grid point " + std::to_string(s.point[q]) + " along its direction " +
                 std::to_string(q - s.begin[s.point[q]]) + " is not traced back to it",
             s.point[q]);
  stats.seconds_trace = seconds_since(t0);

  // Step 3: the faces, each side followed by the next one clockwise from its reverse at its end.
  // Arriving at a boundary point along its first slot (going backwards along the boundary), the
  // next side clockwise lies outside the surface: the face wraps to the point's last slot. The
  // quads are the faces without a wrap; a face made of wraps only is a boundary loop of the grid
  // run backwards (the outside); any other face is an error.
  t0 = Clock::now();
  IsolineQuads out;
  std::vector<int> edge_of(S, -1);
  for (int q = 0; q < S; ++q)  // bound: slots
    if (edge_of[q] < 0) edge_of[q] = edge_of[arrival[q]] = out.num_edges++;
  std::vector<char> used(S, 0);
  for (int q0 = 0; q0 < S; ++q0) {  // bound: slots, and all faces together use each slot once
    if (used[q0]) continue;
    std::array<int, 4> quad{}, sides{};
    int q = q0, len = 0, wraps = 0;
    do {
      if (used[q])
        broken("the isoline faces from grid point " + std::to_string(s.point[q0]) + " overlap",
               s.point[q0]);
      used[q] = 1;
      if (len < 4) {
        quad[len] = s.point[q];
        sides[len] = edge_of[q];
      }
      ++len;
      const int a = arrival[q], p = s.point[a], val = s.begin[p + 1] - s.begin[p];
      wraps += s.boundary[p] && a == s.begin[p];
      q = s.begin[p] + (a - s.begin[p] + val - 1) % val;
    } while (q != q0);
    if (wraps > 0 && wraps == len) {
      ++out.boundary_loops;
      continue;
    }
    if (wraps > 0 || len != 4)
      broken("the isoline face from grid point " + std::to_string(s.point[q0]) +
                 " along its direction " + std::to_string(q0 - s.begin[s.point[q0]]) +
                 " is no quad",
             s.point[q0]);
    out.quads.push_back(quad);
    out.quad_edges.push_back(sides);
  }
  std::int64_t boundary_halfedges = 0;
  for (int h = 0; h < c.mesh.num_halfedges(); ++h) boundary_halfedges += c.mesh.twin(h) < 0;
  const std::int64_t E = (3 * static_cast<std::int64_t>(F) + boundary_halfedges) / 2;
  const std::int64_t chi = static_cast<std::int64_t>(V) - E + F;
  const std::int64_t chi_quads =
      n - static_cast<std::int64_t>(out.num_edges) + static_cast<std::int64_t>(out.quads.size());
  if (chi_quads != chi)
    broken("the quads have Euler characteristic " + std::to_string(chi_quads) + ", the IGM " +
               std::to_string(chi),
           0);
  if (out.boundary_loops != result.report.boundary_loops.value_or(-1))
    broken("the quads have " + std::to_string(out.boundary_loops) + " boundary loops, the IGM " +
               std::to_string(result.report.boundary_loops.value_or(-1)),
           0);
  out.genus = static_cast<int>(result.report.genus.value_or((2 - chi) / 2));

  // The output: exact barycentric coordinates, valences, 3D positions.
  out.vertices.resize(n);
  parallel::for_chunks(n, 256, [&](std::int64_t b, std::int64_t e) {  // each point on its own
    isolines::FaceFrame frame;
    for (std::int64_t p = b; p < e; ++p) {
      const GridPoint& q = gp.points[p];
      IsolineQuadVertex& v = out.vertices[p];
      v.triangle = q.face;
      v.kind = q.kind;
      v.local = q.local;
      v.uv = {q.uv.x, q.uv.y};
      v.valence = s.begin[p + 1] - s.begin[p];
      v.boundary = s.boundary[p] != 0;
      if (q.kind == GridPointKind::Vertex) {
        for (int i = 0; i < 3; ++i) v.barycentric[i] = i == q.local ? 1 : 0;
      } else {
        if (frame.face != q.face) frame.set(q.face, input.corner_uv[q.face]);
        frame.barycentric(q.uv, v.barycentric);
      }
    }
  });
  for (int p = 0; p < n; ++p) {  // bound: grid points
    const GridPoint& q = gp.points[p];
    const IsolineQuadVertex& v = out.vertices[p];
    if (q.kind == GridPointKind::Vertex) ++stats.grid_points_on_vertices;
    if (q.kind == GridPointKind::Edge) ++stats.grid_points_on_edges;
    if (q.kind == GridPointKind::Face) ++stats.grid_points_in_faces;
    if (v.boundary) {
      ++stats.grid_points_on_boundary;
      if (v.valence != 3) ++stats.boundary_corners;
    } else if (v.valence != 4) {
      ++stats.cones;
    }
  }
  if (!input.positions.empty()) {
    out.positions.reserve(n);
    for (const IsolineQuadVertex& v : out.vertices) {  // bound: grid points
      const std::array<int, 3>& t = input.triangles[v.triangle];
      const double w[3] = {to_double(v.barycentric[0]), to_double(v.barycentric[1]),
                           to_double(v.barycentric[2])};
      Vec3d x;
      for (int i = 0; i < 3; ++i) {
        const Vec3d& p = input.positions[t[i]];
        x.x += w[i] * p.x;
        x.y += w[i] * p.y;
        x.z += w[i] * p.z;
      }
      out.positions.push_back(x);
    }
  }
  stats.seconds_quads = seconds_since(t0);
  stats.seconds_total = seconds_since(t_total);
  out.stats = stats;
  result.quads = std::move(out);
  return result;
}

certify::Report certify_isoline_quads(const IsolineResult& result, const IsolineOptions& options) {
  if (!result.quads)
    throw Error(ErrorKind::InvalidArgument, "certify_isoline_quads: the extraction has no quads");
  const IsolineQuads& q = *result.quads;
  certify::QuadInput in;
  in.quads = q.quads;
  in.num_vertices = static_cast<std::int64_t>(q.vertices.size());
  certify::Options o;
  o.threads = options.threads;
  o.max_witnesses = options.max_witnesses;
  o.allow_boundary = options.allow_boundary;
  o.allow_components = options.allow_components;
  o.expected_genus = result.report.genus.value_or(q.genus);
  if (options.allow_boundary) o.expected_boundary_loops = result.report.boundary_loops;
  if (options.allow_boundary || options.allow_components)
    for (const certify::ComponentInfo& c : result.report.components)  // bound: components
      o.expected_components.push_back({c.genus.value_or(-1), c.boundary_loops.value_or(-1)});
  return certify::certify_quads(in, o);
}

}  // namespace igm
