// The exact walks of extract_isolines: turning around a mesh vertex to the triangle whose corner
// wedge holds a direction, and following an integer isoline from a grid point to the next one.
#include <string>

#include "igm/core/error.h"
#include "isolines_internal.h"

namespace igm::isolines {

namespace {

int sgn3(int c) { return c < 0 ? -1 : (c > 0 ? 1 : 0); }
int cmpq(const Rational& a, const Rational& b) { return sgn3(cmp(a, b)); }
// Sign of (coordinate axis of corner h) - v, exact: from the corner's floor and integrality.
int cmp_corner(const Charts& c, int h, int axis, std::int64_t v) {
  const CornerFloor& f = c.floors[h];
  const std::int64_t lo = f.floor[axis];
  if (lo != v) return lo < v ? -1 : 1;  // lo < v: x < lo + 1 <= v; lo > v: x >= lo > v
  return f.integer[axis] ? 0 : 1;       // lo == v: x == v, or v < x < v + 1
}

// Side of corner h relative to the oriented line through the integer point t with direction d_m:
// sign of d_m x (x - t), > 0 on the left. Exact.
int side(const Charts& c, int h, int m, const Grid2& t) {
  switch (m) {
    case 0: return cmp_corner(c, h, 1, t.y);
    case 1: return -cmp_corner(c, h, 0, t.x);
    case 2: return -cmp_corner(c, h, 1, t.y);
    default: return cmp_corner(c, h, 0, t.x);
  }
}

// Sign of d_m . (x - t) for corner h: > 0 when it lies ahead of t along d_m. Exact.
int ahead(const Charts& c, int h, int m, const Grid2& t) {
  switch (m) {
    case 0: return cmp_corner(c, h, 0, t.x);
    case 1: return cmp_corner(c, h, 1, t.y);
    case 2: return -cmp_corner(c, h, 0, t.x);
    default: return -cmp_corner(c, h, 1, t.y);
  }
}

[[noreturn]] void broken(const std::string& what, std::int64_t id) {
  throw Error(ErrorKind::Internal, "extract_isolines: " + what, {id});
}

}  // namespace

int cross_axis(const Point2q& o, const Point2q& a, int m) {
  switch (m) {  // (a - o) x d_m
    case 0: return -cmpq(a.y, o.y);
    case 1: return cmpq(a.x, o.x);
    case 2: return cmpq(a.y, o.y);
    default: return -cmpq(a.x, o.x);
  }
}

int dot_axis(const Point2q& o, const Point2q& a, int m) {
  switch (m) {
    case 0: return cmpq(a.x, o.x);
    case 1: return cmpq(a.y, o.y);
    case 2: return -cmpq(a.x, o.x);
    default: return -cmpq(a.y, o.y);
  }
}

bool in_wedge(const Point2q& o, const Point2q& a, const Point2q& b, int m) {
  // The wedge turns by at most pi: d is inside iff it is left of a - o and right of b - o; on
  // its first ray iff it points along a - o.
  const int c = cross_axis(o, a, m);
  return c > 0 ? cross_axis(o, b, m) < 0 : (c == 0 && dot_axis(o, a, m) > 0);
}

int axis_of(const Point2q& o, const Point2q& a) {
  for (int m = 0; m < 4; ++m)  // bound: 4
    if (cross_axis(o, a, m) == 0 && dot_axis(o, a, m) > 0) return m;
  return -1;
}

int closing_axis(const Charts& c, int face, int corner) {
  if (c.mesh.twin(3 * face + (corner + 2) % 3) >= 0) return -1;
  const std::array<Point2q, 3>& x = (*c.uv)[face];
  return axis_of(x[corner], x[(corner + 2) % 3]);
}

namespace {

// Carries h across half-edge he of its face into the twin's chart (he has a twin).
void cross(const Charts& c, Heading& h, int he) {
  h.target = apply(c.k[he], h.target, c.t[he]);
  h.m = (h.m + c.k[he]) & 3;
}

}  // namespace

bool rewind_to_fan_start(const Charts& c, Heading& h) {
  const int degree = c.degree[c.vertex(3 * h.face + h.corner)];
  Heading cur = h;
  for (int step = 0; step < degree; ++step) {  // bound: the degree of the vertex
    const int he = 3 * cur.face + cur.corner;  // its outgoing side: the previous triangle's
    const int tw = c.mesh.twin(he);
    if (tw < 0) {
      h = cur;
      return true;
    }
    cross(c, cur, he);
    cur.face = tw / 3;
    cur.corner = (tw % 3 + 1) % 3;
  }
  return false;
}

Heading turn_to_wedge(const Charts& c, Heading h, bool unique) {
  const int v = c.vertex(3 * h.face + h.corner);
  const int degree = c.degree[v];
  Heading cur = h, found;
  if (unique) rewind_to_fan_start(c, cur);  // a boundary vertex: its whole fan from its start
  int matches = 0;
  bool open = false;
  for (int step = 0; step < degree; ++step) {  // bound: the degree of v
    const std::array<Point2q, 3>& x = (*c.uv)[cur.face];
    const int i = cur.corner;
    const int closing = closing_axis(c, cur.face, i);
    if (in_wedge(x[i], x[(i + 1) % 3], x[(i + 2) % 3], cur.m) || closing == cur.m) {
      if (!unique) return cur;
      if (matches++ == 0) found = cur;
    }
    // The next triangle counter-clockwise around v: across the side from corner i+2 to corner i.
    const int he = 3 * cur.face + (i + 2) % 3;
    const int tw = c.mesh.twin(he);
    if (tw < 0) {  // the end of a boundary fan
      open = true;
      break;
    }
    cross(c, cur, he);
    cur.face = tw / 3;
    cur.corner = tw % 3;
  }
  if (!unique)
    broken("no triangle around vertex " + std::to_string(v) +
               " holds the direction (it leaves the surface, or the ring does not close)",
           v);
  if (!open && (cur.face != h.face || cur.corner != h.corner || cur.m != h.m ||
                cur.target.x != h.target.x || cur.target.y != h.target.y))
    broken("an isoline passes vertex " + std::to_string(v) +
               " whose seams do not close up to the identity (a cone away from a grid point)",
           v);
  if (matches != 1)
    broken("an isoline passes vertex " + std::to_string(v) + " whose corners hold its direction " +
               std::to_string(matches) + " times, not once (total angle != 2 pi)",
           v);
  return found;
}

TraceEnd trace(const Charts& c, Heading h, std::int64_t max_steps, std::int64_t what) {
  TraceEnd r;
  Point2q target;
  for (;;) {  // bound: max_steps triangles (checked), each turn at a vertex bounded by its degree
    if (++r.steps > max_steps)
      broken("the isoline from grid point " + std::to_string(what) + " passes more than " +
                 std::to_string(max_steps) + " triangles",
             what);
    const std::array<Point2q, 3>& x = (*c.uv)[h.face];
    int s[3];
    for (int i = 0; i < 3; ++i) s[i] = side(c, 3 * h.face + i, h.m, h.target);
    // Where the line leaves the closed triangle, ahead: along a side (both ends on the line, the
    // triangle on its left; on a boundary side also on its right, running against the side) at
    // the side's end; else where the counter-clockwise boundary crosses from the line's right to
    // its left: inside side i, or at corner i.
    int exit_side = -1, exit_corner = -1, along_side = -1;
    for (int i = 0; i < 3 && exit_corner < 0; ++i) {
      const int j = (i + 1) % 3, l = (i + 2) % 3;
      if (s[i] == 0 && s[j] == 0) {
        const bool against = s[l] < 0 && c.mesh.twin(3 * h.face + i) < 0;
        if (s[l] <= 0 && !against)
          broken("the isoline from grid point " + std::to_string(what) +
                     " runs along a side of triangle " + std::to_string(h.face) + " outside it",
                 what);
        exit_corner = against ? i : j;
        along_side = i;
      }
    }
    for (int i = 0; i < 3 && exit_corner < 0 && exit_side < 0; ++i) {
      const int j = (i + 1) % 3, l = (i + 2) % 3;
      if (s[i] < 0 && s[j] > 0) exit_side = i;
      if (s[i] == 0 && s[l] < 0 && s[j] > 0) exit_corner = i;
    }
    if (exit_side < 0 && exit_corner < 0)
      broken("the isoline from grid point " + std::to_string(what) + " misses triangle " +
                 std::to_string(h.face),
             what);
    if (exit_side >= 0) {
      mpq_set_si(target.x.get_mpq_t(), static_cast<long>(h.target.x), 1UL);
      mpq_set_si(target.y.get_mpq_t(), static_cast<long>(h.target.y), 1UL);
      const Sign o = orient2d(x[exit_side], x[(exit_side + 1) % 3], target);
      if (o != Sign::Negative) {  // the target lies before the exit, or on the exit side
        // (neither end of the exit side is on the line; strictly between the entry and the exit
        // the line runs inside the open triangle)
        h.corner = -1;
        r.at = h;
        r.side = o == Sign::Zero ? exit_side : -1;
        return r;
      }
      const int he = 3 * h.face + exit_side;  // cross the seam into the twin's chart
      if (c.mesh.twin(he) < 0)
        broken("the isoline from grid point " + std::to_string(what) +
                   " leaves the surface across a boundary side of triangle " +
                   std::to_string(h.face),
               what);
      cross(c, h, he);
      h.face = c.mesh.twin(he) / 3;
      continue;
    }
    const int a = ahead(c, 3 * h.face + exit_corner, h.m, h.target);
    if (a >= 0) {  // the target lies before the exit corner (on the side the line runs along,
                   // if it does, else inside the triangle), or is that corner
      h.corner = a == 0 ? exit_corner : -1;
      r.at = h;
      r.side = a > 0 && along_side >= 0 ? along_side : -1;
      return r;
    }
    // Through a mesh vertex that is no grid point: a regular vertex (cones are grid points), where
    // exactly one corner wedge holds the direction.
    ++r.vertex_crossings;
    h.corner = exit_corner;
    h = turn_to_wedge(c, h, true);
  }
}

}  // namespace igm::isolines
