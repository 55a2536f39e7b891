// Step 1 of extract_isolines: every integer point of the surface once, and the exact
// barycentric coordinates of the points it found.
#include <algorithm>
#include <exception>
#include <string>

#include "../core/parallel.h"
#include "igm/core/error.h"
#include "isolines_internal.h"

namespace igm::isolines {

namespace {

[[noreturn]] void broken(const std::string& what, std::int64_t id) {
  throw Error(ErrorKind::Internal, "extract_isolines: " + what, {id});
}

bool less_yx(const Grid2& a, const Grid2& b) { return a.y != b.y ? a.y < b.y : a.x < b.x; }

bool equals(const Point2q& p, const Grid2& g) {
  return mpq_cmp_si(p.x.get_mpq_t(), static_cast<long>(g.x), 1UL) == 0 &&
         mpq_cmp_si(p.y.get_mpq_t(), static_cast<long>(g.y), 1UL) == 0;
}

// One end of a row's cross-section: the exact abscissa num / den (den > 0).
struct RowEnd {
  mpz_class num, den;
};

}  // namespace

void FaceFrame::set(int f, const std::array<Point2q, 3>& X) {
  face = f;
  d = 1;
  for (const Point2q& p : X) {
    mpz_lcm(d.get_mpz_t(), d.get_mpz_t(), p.x.get_den_mpz_t());
    mpz_lcm(d.get_mpz_t(), d.get_mpz_t(), p.y.get_den_mpz_t());
  }
  for (int i = 0; i < 3; ++i) {
    mpz_divexact(x[i].get_mpz_t(), d.get_mpz_t(), X[i].x.get_den_mpz_t());
    x[i] *= X[i].x.get_num();
    mpz_divexact(y[i].get_mpz_t(), d.get_mpz_t(), X[i].y.get_den_mpz_t());
    y[i] *= X[i].y.get_num();
  }
  total = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
}

void FaceFrame::barycentric(const Grid2& p, std::array<Rational, 3>& w) {
  mpz_mul_si(px.get_mpz_t(), d.get_mpz_t(), static_cast<long>(p.x));
  mpz_mul_si(py.get_mpz_t(), d.get_mpz_t(), static_cast<long>(p.y));
  for (int i = 0; i < 2; ++i) {  // n_i = det(x_{i+1} - D p, x_{i+2} - D p)
    const int a = (i + 1) % 3, b = (i + 2) % 3;
    s1 = x[a] - px;
    s2 = y[b] - py;
    n[i] = s1 * s2;
    s1 = y[a] - py;
    s2 = x[b] - px;
    n[i] -= s1 * s2;
  }
  n[2] = total - n[0] - n[1];
  for (int i = 0; i < 3; ++i) {
    mpq_set_num(w[i].get_mpq_t(), n[i].get_mpz_t());
    mpq_set_den(w[i].get_mpq_t(), total.get_mpz_t());
    w[i].canonicalize();
  }
}

int find_point(const Charts& c, const GridPoints& gp, int g, int corner, int side, const Grid2& t) {
  if (corner >= 0) return gp.vertex_point[(*c.triangles)[g][corner]];
  int face = g;
  Grid2 key = t;
  if (side >= 0) {
    const int he = 3 * g + side, tw = c.mesh.twin(he);
    if (tw >= 0 && tw < he) {  // owned by the twin's triangle: look there, in its chart
      face = tw / 3;
      key = apply(c.k[he], t, c.t[he]);
    }
  }
  const auto begin = gp.face_points.begin() + gp.face_begin[face];
  const auto end = gp.face_points.begin() + gp.face_begin[face + 1];
  const auto it = std::lower_bound(
      begin, end, key, [&](int p, const Grid2& k) { return less_yx(gp.points[p].uv, k); });
  if (it == end || gp.points[*it].uv.x != key.x || gp.points[*it].uv.y != key.y) return -1;
  return *it;
}

namespace {

// A grid point a triangle's scan found, before numbering; with the seam's image when it lies
// inside a side that the twin's triangle owns (foreign_face >= 0).
struct Found {
  GridPoint q;
  int foreign_face = -1, foreign_side = -1;
  Grid2 foreign_uv;
};

// Phase 1 of find_grid_points for the triangles [f0, f1): per triangle its rows, chords, work
// (rows and points) and found points, in scan order. Stops after the triangle whose work passes
// max_work in this range alone, or at a broken triangle (error, failed_face).
struct Scan {
  std::vector<Found> found;
  std::vector<std::int64_t> found_end, work, rows, chords;  // per triangle scanned
  std::exception_ptr error;
  int failed_face = -1;
};

void scan_triangles(const Charts& c, int f0, int f1, std::int64_t max_work, Scan& out) {
  FaceFrame fr;
  mpz_class row, lo_x, hi_x, lo_y, hi_y, t1, t2;
  RowEnd ends[3];
  Point2q p;
  std::int64_t range_work = 0;
  for (int f = f0; f < f1 && range_work <= max_work; ++f) {  // bound: F triangles
    std::int64_t work = 0, rows = 0, chords = 0;
    try {
      const std::array<Point2q, 3>& X = (*c.uv)[f];
      fr.set(f, X);  // the triangle's corners as integers x_i, y_i over the common denominator d
      int ymin = 0, ymax = 0, xmin = 0, xmax = 0;
      for (int i = 1; i < 3; ++i) {
        if (fr.y[i] < fr.y[ymin]) ymin = i;
        if (fr.y[i] > fr.y[ymax]) ymax = i;
        if (fr.x[i] < fr.x[xmin]) xmin = i;
        if (fr.x[i] > fr.x[xmax]) xmax = i;
      }
      mpz_cdiv_q(lo_y.get_mpz_t(), fr.y[ymin].get_mpz_t(), fr.d.get_mpz_t());
      mpz_fdiv_q(hi_y.get_mpz_t(), fr.y[ymax].get_mpz_t(), fr.d.get_mpz_t());
      mpz_cdiv_q(lo_x.get_mpz_t(), fr.x[xmin].get_mpz_t(), fr.d.get_mpz_t());
      mpz_fdiv_q(hi_x.get_mpz_t(), fr.x[xmax].get_mpz_t(), fr.d.get_mpz_t());
      const std::int64_t j0 = mpz_get_si(lo_y.get_mpz_t()), j1 = mpz_get_si(hi_y.get_mpz_t());
      const std::int64_t i0 = mpz_get_si(lo_x.get_mpz_t()), i1 = mpz_get_si(hi_x.get_mpz_t());
      chords = std::max<std::int64_t>(0, j1 - j0 + 1) + std::max<std::int64_t>(0, i1 - i0 + 1);
      // bound: the rows of the bounding box and their points (work: max_work in this range)
      for (std::int64_t j = j0; j <= j1 && range_work + work <= max_work; ++j) {
        ++work;
        ++rows;
        mpz_mul_si(row.get_mpz_t(), fr.d.get_mpz_t(), static_cast<long>(j));  // the row y = j, by d
        // The row's ends: the corners on it and where it crosses the sides, as num / den (den > 0).
        int n = 0;
        for (int i = 0; i < 3; ++i) {
          const int k = (i + 1) % 3;
          const int ca = cmp(fr.y[i], row), cb = cmp(fr.y[k], row);
          if (ca == 0) {
            ends[n].num = fr.x[i];
            ends[n++].den = fr.d;
          } else if ((ca < 0 && cb > 0) || (ca > 0 && cb < 0)) {
            // x = x_i + (row - y_i)(x_k - x_i) / (y_k - y_i), over d
            t1 = fr.y[k] - fr.y[i];
            t2 = row - fr.y[i];
            ends[n].num = fr.x[k] - fr.x[i];
            ends[n].num *= t2;
            ends[n].num += fr.x[i] * t1;
            ends[n].den = t1 * fr.d;
            if (sgn(ends[n].den) < 0) {
              ends[n].num = -ends[n].num;
              ends[n].den = -ends[n].den;
            }
            ++n;
          }
        }
        if (n == 0)
          broken("row " + std::to_string(j) + " of triangle " + std::to_string(f) + " meets no side", f);
        int lo = 0, hi = 0;
        for (int i = 1; i < n; ++i) {  // compare a/b < c/d as a d < c b (b, d > 0)
          t1 = ends[i].num * ends[lo].den;
          t2 = ends[lo].num * ends[i].den;
          if (t1 < t2) lo = i;
          t1 = ends[i].num * ends[hi].den;
          t2 = ends[hi].num * ends[i].den;
          if (t1 > t2) hi = i;
        }
        const bool inner_row = cmp(fr.y[ymin], row) < 0 && cmp(fr.y[ymax], row) > 0;
        mpz_cdiv_q(t1.get_mpz_t(), ends[lo].num.get_mpz_t(), ends[lo].den.get_mpz_t());
        mpz_fdiv_q(t2.get_mpz_t(), ends[hi].num.get_mpz_t(), ends[hi].den.get_mpz_t());
        const std::int64_t a0 = mpz_get_si(t1.get_mpz_t()), a1 = mpz_get_si(t2.get_mpz_t());
        const bool lo_on = mpz_divisible_p(ends[lo].num.get_mpz_t(), ends[lo].den.get_mpz_t()) != 0;
        const bool hi_on = mpz_divisible_p(ends[hi].num.get_mpz_t(), ends[hi].den.get_mpz_t()) != 0;
        for (std::int64_t i = a0; i <= a1 && range_work + work <= max_work; ++i) {  // bound: the row's points
          ++work;
          const Grid2 g{i, j};
          GridPoint q{f, GridPointKind::Face, -1, g};
          // Strictly inside the row's cross-section on a row strictly between the lowest and the
          // highest corner: inside the open triangle. Otherwise on its boundary, or not.
          const bool inner = inner_row && !(i == a0 && lo_on) && !(i == a1 && hi_on);
          if (!inner) {
            for (int k = 0; k < 3 && q.kind == GridPointKind::Face; ++k)
              if (equals(X[k], g)) q = {f, GridPointKind::Vertex, k, g};
            if (q.kind == GridPointKind::Face) {
              p.x = static_cast<long>(i);
              p.y = static_cast<long>(j);
              for (int k = 0; k < 3 && q.kind == GridPointKind::Face; ++k)
                if (orient2d(X[k], X[(k + 1) % 3], p) == Sign::Zero) q = {f, GridPointKind::Edge, k, g};
            }
          }
          Found found{q};
          if (q.kind == GridPointKind::Edge) {
            const int he = 3 * f + q.local, tw = c.mesh.twin(he);
            if (tw >= 0 && tw < he) found = {q, tw / 3, tw % 3, apply(c.k[he], g, c.t[he])};
          }
          out.found.push_back(found);
        }
      }
    } catch (...) {
      out.error = std::current_exception();
      out.failed_face = f;
    }
    out.found_end.push_back(static_cast<std::int64_t>(out.found.size()));
    out.work.push_back(work);
    out.rows.push_back(rows);
    out.chords.push_back(chords);
    range_work += work;
    if (out.error) return;
  }
}

}  // namespace

// Two phases: the triangles scanned in parallel (core/parallel.h, chunks of triangles), then their
// points numbered in triangle order as one sequential scan would, the work bound checked where
// that scan would have checked it.
GridPoints find_grid_points(const Charts& c, std::int64_t max_work) {
  const int F = static_cast<int>(c.triangles->size());
  GridPoints gp;
  gp.vertex_point.assign(c.degree.size(), -1);
  gp.face_begin.assign(F + 1, 0);
  std::vector<int> vertex_seen(c.degree.size(), 0);
  struct Foreign {  // a point inside a side owned by the twin's triangle: checked below
    int face;
    int side;
    Grid2 uv;
  };
  std::vector<Foreign> foreign;
  constexpr std::int64_t kChunk = 4096;
  std::vector<Scan> scans(static_cast<std::size_t>((F + kChunk - 1) / kChunk));
  parallel::for_chunks(F, kChunk, [&](std::int64_t b, std::int64_t e) {
    scan_triangles(c, static_cast<int>(b), static_cast<int>(e), max_work, scans[b / kChunk]);
  });
  std::int64_t work = 0;
  for (std::size_t k = 0; k < scans.size(); ++k) {
    Scan& sc = scans[k];
    const int f0 = static_cast<int>(k * kChunk);
    for (std::size_t i = 0; i < sc.work.size(); ++i) {  // bound: the range's scanned triangles
      const int f = f0 + static_cast<int>(i);
      gp.face_begin[f] = static_cast<int>(gp.face_points.size());
      work += sc.work[i];
      if (work > max_work)
        throw Error(ErrorKind::TooLarge,
                    "extract_isolines: more than " + std::to_string(max_work) +
                        " grid points and rows (IsolineOptions::max_grid_work), at triangle " + std::to_string(f),
                    {f});
      if (f == sc.failed_face) std::rethrow_exception(sc.error);
      gp.rows += sc.rows[i];
      gp.chords = std::min<std::int64_t>(std::int64_t{1} << 62, gp.chords + sc.chords[i]);  // saturated
      for (std::int64_t x = i == 0 ? 0 : sc.found_end[i - 1]; x < sc.found_end[i]; ++x) {
        const Found& fd = sc.found[x];
        const GridPoint& q = fd.q;
        if (q.kind == GridPointKind::Vertex) {
          const int v = (*c.triangles)[f][q.local];
          ++vertex_seen[v];
          if (gp.vertex_point[v] >= 0) continue;
          gp.vertex_point[v] = static_cast<int>(gp.points.size());
          gp.points.push_back(q);
          continue;
        }
        if (fd.foreign_face >= 0) {
          foreign.push_back({fd.foreign_face, fd.foreign_side, fd.foreign_uv});
          continue;
        }
        gp.face_points.push_back(static_cast<int>(gp.points.size()));
        gp.points.push_back(q);
      }
    }
    Scan().found.swap(sc.found);
  }
  gp.face_begin[F] = static_cast<int>(gp.face_points.size());
  // Found once: every point inside an interior side is found from both triangles, the second time
  // (through the seam) at a point the first one owns (a boundary side has one triangle); every
  // corner at a grid point, from all its triangles.
  std::int64_t on_edges = 0;
  for (const GridPoint& q : gp.points)
    on_edges += q.kind == GridPointKind::Edge && c.mesh.twin(3 * q.face + q.local) >= 0;
  if (static_cast<std::int64_t>(foreign.size()) != on_edges)
    broken(std::to_string(on_edges) + " grid points inside edges seen from one side, " +
               std::to_string(foreign.size()) + " from the other",
           0);
  for (const Foreign& fp : foreign) {  // bound: the points inside edges
    const int q = find_point(c, gp, fp.face, -1, fp.side, fp.uv);
    if (q < 0 || gp.points[q].kind != GridPointKind::Edge || gp.points[q].local != fp.side)
      broken("the grid point (" + std::to_string(fp.uv.x) + ", " + std::to_string(fp.uv.y) +
                 ") inside side " + std::to_string(fp.side) + " of triangle " +
                 std::to_string(fp.face) + " is not found from that side's triangle",
             fp.face);
  }
  for (std::size_t v = 0; v < c.degree.size(); ++v)  // bound: V
    if (gp.vertex_point[v] >= 0 && vertex_seen[v] != c.degree[v])
      broken("vertex " + std::to_string(v) + " is on the grid in " +
                 std::to_string(vertex_seen[v]) + " of its " + std::to_string(c.degree[v]) +
                 " triangles",
             static_cast<std::int64_t>(v));
  return gp;
}

}  // namespace igm::isolines
