#include "igm/embed/tutte.h"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <chrono>
#include <cmath>
#include <string>

#include "igm/core/error.h"
#include "igm/embed/exact_refinement.h"
#include "igm/embed/polygon.h"

// Why the certified solve terminates: A = L_II, the Laplacian with the uniform or the given
// positive symmetric integer weights restricted to interior vertices, is symmetric positive
// definite (weakly diagonally dominant, strictly on rows next to the boundary, irreducible because
// the disk is connected); b holds weighted sums of boundary positions.
// By Tutte's theorem in Floater's form (convex boundary traversed once, convex-combination
// weights, no interior edge between two vertices of one side) the exact solution x* = A^-1 b is
// an embedding, so the refinement of embed/exact_refinement.cpp (convergence argument there)
// certifies every triangle after finitely many steps.

namespace igm {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

[[noreturn]] void bad(const std::string& message, std::vector<std::int64_t> elements) {
  throw Error(ErrorKind::InvalidArgument, "tutte_embed: " + message, std::move(elements));
}

std::string edge_str(int a, int b) {
  std::string s = "(";  // appended piece by piece: GCC 12 warns (-Wrestrict, falsely) on "(" + to_string(a)
  s.append(std::to_string(a)).append(", ").append(std::to_string(b)).append(")");
  return s;
}

// Half-edge structure of the input disk. Half-edge 3f+i runs from triangles[f][i] to
// triangles[f][(i+1)%3]; twin is -1 on the boundary.
struct Disk {
  int nv = 0, nf = 0;
  std::vector<int> origin, twin;
  std::vector<int> out_begin, out;  // CSR: half-edges leaving each vertex, sorted by target
  std::vector<int> out_target;      // target of out[k]
  int target(int h) const { return origin[h % 3 == 2 ? h - 2 : h + 1]; }
  static int prev(int h) { return h % 3 == 0 ? h + 2 : h - 1; }
};

// Which polygon sides each boundary position lies on: side_in[i] is the side of the boundary
// edge ending at i, side_out[i] the side of the edge starting at i (equal except at corners).
struct Sides {
  std::vector<int> side_in, side_out;
  bool share(int i, int j) const {
    return side_in[i] == side_in[j] || side_in[i] == side_out[j] || side_out[i] == side_in[j] ||
           side_out[i] == side_out[j];
  }
  bool has(int i, int s) const { return side_in[i] == s || side_out[i] == s; }
};

Sides check_boundary_polygon(const std::vector<int>& boundary, const std::vector<Point2q>& P) {
  const int n = static_cast<int>(P.size());
  std::vector<char> corner(n, 0);
  std::vector<Point2q> corners;
  int first_corner = -1;
  for (int i = 0; i < n; ++i) {
    const Point2q& a = P[(i + n - 1) % n];
    const Point2q& b = P[i];
    const Point2q& c = P[(i + 1) % n];
    const Sign s = orient2d(a, b, c);
    if (s == Sign::Negative)
      bad("boundary polygon turns clockwise (not convex counter-clockwise) at boundary vertex " +
              std::to_string(boundary[i]),
          {boundary[i]});
    if (s == Sign::Zero) {
      const Rational dot = (b.x - a.x) * (c.x - b.x) + (b.y - a.y) * (c.y - b.y);
      if (sgn(dot) <= 0)
        bad("boundary position of vertex " + std::to_string(boundary[i]) +
                " repeats or goes back along its side",
            {boundary[i]});
    } else {
      corner[i] = 1;
      corners.push_back(b);
      if (first_corner < 0) first_corner = i;
    }
  }
  if (corners.size() < 3 || !is_strictly_convex_ccw(corners))
    bad("boundary positions do not form a convex polygon traversed once counter-clockwise", {});
  Sides sides;
  sides.side_in.assign(n, -1);
  sides.side_out.assign(n, -1);
  int side = 0;
  for (int k = 0; k < n; ++k) {
    const int i = (first_corner + k) % n;
    if (corner[i] && k > 0) ++side;
    sides.side_out[i] = side;
    sides.side_in[(i + 1) % n] = side;
  }
  return sides;
}

Disk build_and_check_disk(int nv, const std::vector<std::array<int, 3>>& tris,
                          const std::vector<int>& boundary, std::vector<int>& bpos) {
  Disk d;
  d.nv = nv;
  d.nf = static_cast<int>(tris.size());
  const int nh = 3 * d.nf;
  d.origin.resize(nh);
  for (int f = 0; f < d.nf; ++f) {
    const auto& t = tris[f];
    for (int i = 0; i < 3; ++i) {
      if (t[i] < 0 || t[i] >= nv)
        bad("triangle " + std::to_string(f) + " refers to vertex " + std::to_string(t[i]) +
                " outside 0.." + std::to_string(nv - 1),
            {f});
      d.origin[3 * f + i] = t[i];
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      bad("triangle " + std::to_string(f) + " repeats a vertex", {f});
  }
  // CSR of outgoing half-edges, each bucket sorted by target: O(F log valence).
  d.out_begin.assign(nv + 1, 0);
  for (int h = 0; h < nh; ++h) ++d.out_begin[d.origin[h] + 1];
  for (int v = 0; v < nv; ++v) d.out_begin[v + 1] += d.out_begin[v];
  {
    // Sort keys (target << 32 | half-edge) inside each bucket: contiguous integer sorts.
    std::vector<std::uint64_t> key(nh);
    std::vector<int> fill(d.out_begin.begin(), d.out_begin.end() - 1);
    for (int h = 0; h < nh; ++h)
      key[fill[d.origin[h]]++] = (static_cast<std::uint64_t>(d.target(h)) << 32) | static_cast<std::uint32_t>(h);
    d.out.resize(nh);
    d.out_target.resize(nh);
    for (int v = 0; v < nv; ++v) {
      if (d.out_begin[v] == d.out_begin[v + 1])
        bad("vertex " + std::to_string(v) + " is used by no triangle", {v});
      std::sort(key.begin() + d.out_begin[v], key.begin() + d.out_begin[v + 1]);
      for (int k = d.out_begin[v]; k < d.out_begin[v + 1]; ++k) {
        d.out[k] = static_cast<int>(key[k] & 0xffffffffu);
        d.out_target[k] = static_cast<int>(key[k] >> 32);
        if (k > d.out_begin[v] && d.out_target[k] == d.out_target[k - 1])
          bad("edge " + edge_str(v, d.out_target[k]) +
                  " has two triangles in the same direction (non-manifold or inconsistently oriented)",
              {v, d.out_target[k]});
      }
    }
  }
  d.twin.assign(nh, -1);
  int num_boundary_he = 0;
  for (int h = 0; h < nh; ++h) {
    const int a = d.origin[h], b = d.target(h);
    auto first = d.out_target.begin() + d.out_begin[b], last = d.out_target.begin() + d.out_begin[b + 1];
    auto it = std::lower_bound(first, last, a);
    if (it != last && *it == a)
      d.twin[h] = d.out[it - d.out_target.begin()];
    else
      ++num_boundary_he;
  }
  // The boundary loop must be exactly the given cycle, in the given orientation.
  const int nb = static_cast<int>(boundary.size());
  bpos.assign(nv, -1);
  for (int i = 0; i < nb; ++i) {
    const int v = boundary[i];
    if (v < 0 || v >= nv)
      bad("boundary entry " + std::to_string(i) + " is vertex " + std::to_string(v) +
              ", outside 0.." + std::to_string(nv - 1),
          {v});
    if (bpos[v] >= 0) bad("vertex " + std::to_string(v) + " appears twice in the boundary cycle", {v});
    bpos[v] = i;
  }
  for (int v = 0; v < nv; ++v) {
    int count = 0, to = -1;
    for (int k = d.out_begin[v]; k < d.out_begin[v + 1]; ++k)
      if (d.twin[d.out[k]] < 0) {
        ++count;
        to = d.target(d.out[k]);
      }
    if (bpos[v] < 0) {
      if (count > 0)
        bad("edge " + edge_str(v, to) + " is on the mesh boundary but vertex " + std::to_string(v) +
                " is not in the boundary cycle (several boundary loops?)",
            {v, to});
      continue;
    }
    const int expect = boundary[(bpos[v] + 1) % nb];
    if (count == 0)
      bad("boundary vertex " + std::to_string(v) + " is interior in the mesh", {v});
    if (count > 1) bad("vertex " + std::to_string(v) + " lies on the mesh boundary twice (pinched)", {v});
    if (to != expect)
      bad("mesh boundary runs " + edge_str(v, to) + " but the boundary cycle runs " +
              edge_str(v, expect) + " (other loop or opposite orientation)",
          {v, to});
  }
  if (num_boundary_he != nb)
    bad("the mesh has " + std::to_string(num_boundary_he) + " boundary edges, the cycle has " +
            std::to_string(nb),
        {});
  // One fan per vertex: rotating counter-clockwise (h -> twin(prev(h))) from the outgoing
  // boundary half-edge (or any half-edge of an interior vertex) must visit every triangle at v.
  // Each walk takes at most valence + 1 steps.
  for (int v = 0; v < nv; ++v) {
    const int deg = d.out_begin[v + 1] - d.out_begin[v];
    int start = d.out[d.out_begin[v]];
    if (bpos[v] >= 0)
      for (int k = d.out_begin[v]; k < d.out_begin[v + 1]; ++k)
        if (d.twin[d.out[k]] < 0) start = d.out[k];
    int h = start, visited = 0;
    while (visited <= deg) {
      ++visited;
      const int t = d.twin[Disk::prev(h)];
      if (t < 0 || t == start) break;
      h = t;
    }
    if (visited != deg)
      bad("vertex " + std::to_string(v) + " is non-manifold (its triangles form several fans)", {v});
  }
  // Connected, and Euler characteristic 1: with one boundary loop this is a disk.
  {
    std::vector<char> seen(d.nf, 0);
    std::vector<int> stack{0};
    seen[0] = 1;
    int reached = 1;
    while (!stack.empty()) {  // each face pushed once: O(F)
      const int f = stack.back();
      stack.pop_back();
      for (int i = 0; i < 3; ++i) {
        const int t = d.twin[3 * f + i];
        if (t >= 0 && !seen[t / 3]) {
          seen[t / 3] = 1;
          ++reached;
          stack.push_back(t / 3);
        }
      }
    }
    if (reached != d.nf) {
      int f = 0;
      while (seen[f]) ++f;
      bad("the mesh is not connected (triangle " + std::to_string(f) + " is not reached from triangle 0)",
          {f});
    }
  }
  const std::int64_t edges = (std::int64_t(nh) + num_boundary_he) / 2;
  const std::int64_t chi = std::int64_t(nv) - edges + d.nf;
  if (chi != 1)
    bad("Euler characteristic is " + std::to_string(chi) + ", a disk has 1 (handles inside?)", {});
  return d;
}

}  // namespace

TutteResult tutte_embed(int num_vertices, const std::vector<std::array<int, 3>>& triangles,
                        const std::vector<int>& boundary, const std::vector<Point2q>& boundary_uv,
                        const TutteOptions& options) {
  return tutte_embed(num_vertices, triangles, boundary, boundary_uv, {}, options);
}

TutteResult tutte_embed(int num_vertices, const std::vector<std::array<int, 3>>& triangles,
                        const std::vector<int>& boundary, const std::vector<Point2q>& boundary_uv,
                        const std::vector<int>& weights, const TutteOptions& options) {
  const auto t_start = Clock::now();
  TutteResult result;
  TutteStats& st = result.stats;
  if (num_vertices < 3) bad("needs at least 3 vertices, got " + std::to_string(num_vertices), {});
  if (triangles.empty()) bad("no triangles", {});
  if (boundary.size() < 3) bad("the boundary cycle needs at least 3 vertices", {});
  if (boundary.size() != boundary_uv.size())
    bad(std::to_string(boundary.size()) + " boundary vertices but " +
            std::to_string(boundary_uv.size()) + " boundary positions",
        {});
  if (options.max_iterations < 0) bad("max_iterations must be >= 0", {});
  if (options.min_iterations > options.max_iterations)
    bad("min_iterations must be <= max_iterations", {});

  // ---------------- pre-conditions ----------------
  std::vector<int> bpos;
  const Disk d = build_and_check_disk(num_vertices, triangles, boundary, bpos);
  const Sides sides = check_boundary_polygon(boundary, boundary_uv);
  for (int f = 0; f < d.nf; ++f) {
    const auto& t = triangles[f];
    if (bpos[t[0]] < 0 || bpos[t[1]] < 0 || bpos[t[2]] < 0) continue;
    const int i = bpos[t[0]], j = bpos[t[1]], k = bpos[t[2]];
    for (int s : {sides.side_in[i], sides.side_out[i]})
      if (sides.has(j, s) && sides.has(k, s))
        bad("triangle " + std::to_string(f) + " has its three vertices on polygon side " +
                std::to_string(s) + " (degenerate; split first)",
            {f});
  }

  for (int h = 0; h < 3 * d.nf; ++h) {
    const int a = d.origin[h], b = d.target(h);
    if (d.twin[h] >= 0 && a < b && bpos[a] >= 0 && bpos[b] >= 0 && sides.share(bpos[a], bpos[b]))
      bad("interior edge " + edge_str(a, b) +
              " joins two boundary vertices on the same polygon side (split it first)",
          {a, b});
  }
  const bool weighted = !weights.empty();
  if (weighted) {
    if (weights.size() != 3 * triangles.size())
      bad(std::to_string(weights.size()) + " half-edge weights for " + std::to_string(3 * triangles.size()) +
              " half-edges",
          {});
    for (int h = 0; h < 3 * d.nf; ++h) {
      const int a = d.origin[h], b = d.target(h);
      if (d.twin[h] < 0) continue;
      if (weights[h] < 1) bad("edge " + edge_str(a, b) + " has weight " + std::to_string(weights[h]) + " (needs >= 1)", {a, b});
      if (weights[h] != weights[d.twin[h]])
        bad("edge " + edge_str(a, b) + " has different weights on its two half-edges", {a, b});
    }
  }
  auto weight = [&](int h) { return weighted ? weights[h] : 1; };
  // ---------------- interior system ----------------
  const int nv = num_vertices;
  std::vector<int> idx(nv, -1), vert;
  for (int v = 0; v < nv; ++v)
    if (bpos[v] < 0) {
      idx[v] = static_cast<int>(vert.size());
      vert.push_back(v);
    }
  const int m = static_cast<int>(vert.size());
  st.seconds_validate = since(t_start);
  const auto t_assemble = Clock::now();
  st.interior_vertices = m;
  st.boundary_vertices = static_cast<int>(boundary.size());
  st.triangles = d.nf;
  // Interior neighbours in CSR; degrees; exact right-hand side on rows next to the boundary.
  std::vector<int> nb_begin(m + 1, 0), nb, nbw;
  std::vector<int> deg(m);
  std::vector<int> brow;            // interior rows with boundary neighbours
  std::vector<Rational> bx, by;     // their exact right-hand sides
  nb.reserve(3 * static_cast<std::size_t>(d.nf));
  for (int i = 0; i < m; ++i) {
    const int v = vert[i];
    std::int64_t sum = 0;  // interior vertex: one out-edge per neighbour
    Rational sx = 0, sy = 0;
    bool touches = false;
    for (int k = d.out_begin[v]; k < d.out_begin[v + 1]; ++k) {
      const int w = d.out_target[k];
      const int wt = weight(d.out[k]);
      sum += wt;
      if (idx[w] >= 0) {
        nb.push_back(idx[w]);
        nbw.push_back(-wt);
      } else {
        touches = true;
        sx += wt * boundary_uv[bpos[w]].x;
        sy += wt * boundary_uv[bpos[w]].y;
      }
    }
    if (sum > INT32_MAX) bad("the weights around vertex " + std::to_string(v) + " sum past 2^31", {v});
    deg[i] = static_cast<int>(sum);
    nb_begin[i + 1] = static_cast<int>(nb.size());
    if (touches) {
      brow.push_back(i);
      bx.push_back(sx);
      by.push_back(sy);
    }
  }
  st.seconds_assemble = since(t_assemble);

  // Orientation checks. Triangles with a boundary vertex use exact rationals; the others the
  // filter of the current representation (doubles, or the common grid 2^-e).
  using Mode = RefinementIterate::Mode;
  auto certificate = [&](const RefinementIterate& x) -> std::int64_t {
    std::int64_t flips = 0;
    GridScratch s;
    for (int f = 0; f < d.nf; ++f) {
      const auto& t = triangles[f];
      Sign o;
      if (x.mode == Mode::Exact || bpos[t[0]] >= 0 || bpos[t[1]] >= 0 || bpos[t[2]] >= 0) {
        auto point_of = [&](int v) { return bpos[v] >= 0 ? boundary_uv[bpos[v]] : x.point(idx[v]); };
        o = orient2d(point_of(t[0]), point_of(t[1]), point_of(t[2]));
      } else {
        const int a = idx[t[0]], b = idx[t[1]], c = idx[t[2]];
        if (x.mode == Mode::Double) {
          const std::vector<double>&xd = *x.xd, &yd = *x.yd;
          o = orient2d(Vec2d{xd[a], yd[a]}, Vec2d{xd[b], yd[b]}, Vec2d{xd[c], yd[c]});
        } else {
          const std::vector<mpz_class>&X = *x.X, &Y = *x.Y;
          o = grid_orient(X[a], Y[a], X[b], Y[b], X[c], Y[c], s);  // the common factor 2^-2e does not change the sign
        }
      }
      if (o != Sign::Positive) ++flips;
    }
    return flips;
  };
  auto finish = [&](const RefinementIterate& interior) {
    result.uv.resize(nv);
    for (int v = 0; v < nv; ++v) result.uv[v] = bpos[v] >= 0 ? boundary_uv[bpos[v]] : interior.point(idx[v]);
    std::size_t bits = 0;
    for (const Point2q& p : result.uv) bits = std::max({bits, bit_size(p.x), bit_size(p.y)});
    st.max_bits = bits;
    st.seconds_total = since(t_start);
  };

  if (m == 0) {  // every vertex on the boundary: the placement is the embedding
    RefinementIterate none;
    none.mode = Mode::Exact;
    const auto t0 = Clock::now();
    st.flips_double = certificate(none);
    st.seconds_checks = since(t0);
    if (st.flips_double != 0)
      throw Error(ErrorKind::Internal, "tutte_embed: a triangle of an all-boundary disk is not positive");
    finish(none);
    return result;
  }

  // ---------------- the certified solve (embed/exact_refinement.h) ----------------
  SpdSystem system;
  system.n = m;
  system.diag = std::move(deg);
  system.xadj = std::move(nb_begin);
  system.adj = std::move(nb);
  system.val = std::move(nbw);
  system.rhs_rows = std::move(brow);
  system.rhs_x = std::move(bx);
  system.rhs_y = std::move(by);
  for (const Point2q& p : boundary_uv)
    system.magnitude = std::max({system.magnitude, std::fabs(to_double(p.x)), std::fabs(to_double(p.y))});
  RefinementOptions ro;
  ro.max_iterations = options.max_iterations;
  ro.min_iterations = options.min_iterations;
  ro.exact_fallback_max_unknowns = options.exact_fallback_max_interior;
  RefinementResult solved =
      refine_until_certified(system, certificate, ro, {"tutte_embed", "interior vertices", "the exact Tutte solution"});
  const RefinementStats& rs = solved.stats;
  st.flips_double = rs.flips_double;
  st.flips_per_iteration = rs.flips_per_iteration;
  st.iterations = rs.iterations;
  st.grid_exponent = rs.grid_exponent;
  st.exact_fallback = rs.exact_fallback;
  st.factor_entries = rs.factor_entries;
  st.seconds_factorization = rs.seconds_factorization;
  st.seconds_solve = rs.seconds_solve;
  st.seconds_refinement = rs.seconds_refinement;
  st.seconds_checks = rs.seconds_checks;
  st.seconds_fallback = rs.seconds_fallback;
  finish(solved.iterate());
  return result;
}

}  // namespace igm
