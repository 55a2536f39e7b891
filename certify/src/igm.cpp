// Checks 2-4 of an IGM (triangles with one exact UV per corner) and the public entry points.
#include <algorithm>
#include <fstream>
#include <sstream>

#include "certify/exact.h"
#include "certify/obj.h"
#include "internal.h"

namespace igm::certify {

using detail::add_witness;
using detail::point_string;
using detail::Topology;

const char* to_string(Status s) {
  switch (s) {
    case Status::Pass: return "pass";
    case Status::Fail: return "fail";
    case Status::Incomplete: return "incomplete";
    case Status::Skipped: return "skipped";
  }
  return "?";
}

const char* to_string(Verdict v) {
  switch (v) {
    case Verdict::Valid: return "valid";
    case Verdict::Invalid: return "invalid";
    case Verdict::Unreadable: return "unreadable";
  }
  return "?";
}

std::int64_t CheckResult::count(const std::string& key) const {
  for (const auto& [k, v] : counts)
    if (k == key) return v;
  return -1;
}

const CheckResult* Report::check(int id) const {
  for (const auto& c : checks)
    if (c.id == id) return &c;
  return nullptr;
}

namespace {

// Internal IGM data: triangles as a corner list (face f owns corners 3f..3f+2) and exact UVs.
struct IgmData {
  std::int64_t V = 0;
  std::vector<std::int64_t> face_begin;
  std::vector<int> corner_vertex;
  std::vector<ExactPoint> uv;  // distinct UV values
  std::vector<int> corner_uv;  // per corner: index into uv
};

// Edge transition codes besides k = 0..3.
constexpr int kNoRotation = -1;    // no R^k maps one side's edge vector onto the other's
constexpr int kNonInteger = -2;    // rotation found, translation not integer
constexpr int kZeroLength = -3;    // zero UV vector on both sides, some k gives integer t: passes
                                   // check 3 but cannot orient a wedge (vertex undetermined)
constexpr int kNotInterior = -4;   // not a manifold, consistently oriented edge

bool is_integer(const mpq_class& q) { return mpz_cmp_ui(q.get_den_mpz_t(), 1) == 0; }

// x == -y for canonical rationals.
bool equal_neg(const mpq_class& x, const mpq_class& y) {
  return mpz_cmpabs(x.get_num_mpz_t(), y.get_num_mpz_t()) == 0 && sgn(x) == -sgn(y) &&
         mpz_cmp(x.get_den_mpz_t(), y.get_den_mpz_t()) == 0;
}

// R^k (x, y) == (u, v) exactly, R = rotation by +90 degrees: R(x, y) = (-y, x).
bool rotated_equal(int k, const mpq_class& x, const mpq_class& y, const mpq_class& u, const mpq_class& v) {
  switch (k) {
    case 0: return u == x && v == y;
    case 1: return equal_neg(u, y) && v == x;
    case 2: return equal_neg(u, x) && equal_neg(v, y);
    default: return u == y && equal_neg(v, x);
  }
}

// t = p - R^k q.
void translation(int k, const ExactPoint& p, const ExactPoint& q, mpq_class& tx, mpq_class& ty) {
  switch (k) {
    case 0: tx = p.x - q.x; ty = p.y - q.y; break;
    case 1: tx = p.x + q.y; ty = p.y - q.x; break;
    case 2: tx = p.x + q.x; ty = p.y + q.y; break;
    default: tx = p.x - q.y; ty = p.y + q.x; break;
  }
}

// Half-open quadrant of the direction p - o (0: x>0,y>=0; 1: x<=0,y>0; 2: x<0,y<=0; 3: x>=0,y<0),
// -1 for the zero vector. R maps quadrant q onto q+1 exactly.
// Exact comparison of two coordinates; the truncated approximations decide when they differ
// (truncation toward zero is monotone, so a < b for the approximations implies a < b exactly).
int compare(const mpq_class& a, double da, const mpq_class& b, double db, bool filterable) {
  if (filterable && da != db) return da < db ? -1 : 1;
  const int c = cmp(a, b);
  return c < 0 ? -1 : (c > 0 ? 1 : 0);
}

// The segment a-b is parallel to an axis (u or v constant along it), exactly.
bool axis_parallel(const ExactPoint& a, const ExactPoint& b) {
  const bool f = a.filterable && b.filterable;
  return compare(a.x, a.ax, b.x, b.ax, f) == 0 || compare(a.y, a.ay, b.y, b.ay, f) == 0;
}

// The segment a-b lies on an integer isoline: u = c or v = c along it, c in Z.
bool on_integer_isoline(const ExactPoint& a, const ExactPoint& b) {
  return (a.x == b.x && is_integer(a.x)) || (a.y == b.y && is_integer(a.y));
}

std::string isoline_condition(const ExactPoint& a, const ExactPoint& b);

// The edge of half-edge h in h's face (chart) lies on an integer isoline (on_integer_isoline of the
// corner UVs at its ends): nullopt; else a witness without reason: the edge (u < v), the face and
// the UVs of its corners at u and v (and with `condition`, which test failed). The rule shared by
// boundary edges (check 3) and feature edges (the features check).
std::optional<Witness> off_isoline(const IgmData& d, const Topology& t, std::int64_t h, bool condition = false) {
  const std::int64_t hu = t.origin(h) < t.target(h) ? h : t.next(h);
  const std::int64_t hv = hu == h ? t.next(h) : h;
  const ExactPoint &pu = d.uv[d.corner_uv[hu]], &pv = d.uv[d.corner_uv[hv]];
  if (on_integer_isoline(pu, pv)) return std::nullopt;
  Witness w{"edge", {t.origin(hu), t.origin(hv)}, "",
            {{"face", std::to_string(t.corner_face[h])},
             {"uv_u", point_string(pu.x, pu.y)},
             {"uv_v", point_string(pv.x, pv.y)}}};
  if (condition) w.values.emplace_back("condition", isoline_condition(pu, pv));
  return w;
}

// Why a and b are on no integer isoline, per coordinate: "u differs" or "u equal, not integer",
// then the same for v.
std::string isoline_condition(const ExactPoint& a, const ExactPoint& b) {
  auto one = [](const char* name, const mpq_class& x, const mpq_class& y) {
    return std::string(name) + (x != y ? " differs" : " equal, not integer");
  };
  return one("u", a.x, b.x) + "; " + one("v", a.y, b.y);
}

// Every feature edge lies on an integer isoline in the chart of every face containing it. The
// pairs were validated (find_edge) into `edges`, in the order given.
CheckResult check_features(const IgmData& d, const Topology& t, const std::vector<FeatureEdge>& pairs,
                           const std::vector<std::int64_t>& edges, std::size_t W) {
  CheckResult c;
  c.id = 6;
  c.name = "features";
  std::vector<char> seen(static_cast<std::size_t>(t.E), 0);
  std::int64_t distinct = 0, off_edges = 0, sides = 0, off_sides = 0;
  for (std::size_t i = 0; i < pairs.size(); ++i) {  // bound: number of pairs
    const std::int64_t e = edges[i];
    if (seen[e]) continue;
    seen[e] = 1;
    ++distinct;
    bool off = false;
    for (std::int64_t k = t.edge_start[e]; k < t.edge_start[e + 1]; ++k) {  // bound: faces on e
      const std::int64_t h = t.edge_halfedges[k];
      ++sides;
      std::optional<Witness> w = off_isoline(d, t, h, true);
      if (!w) continue;
      ++off_sides;
      off = true;
      w->reason = "feature edge not on an integer isoline of this face's chart (u or v constant and integer)";
      if (pairs[i].line > 0) w->values.emplace_back("line", std::to_string(pairs[i].line));
      add_witness(c, W, std::move(*w));
    }
    off_edges += off ? 1 : 0;
  }
  c.counts = {{"feature_pairs", std::int64_t(pairs.size())},
              {"duplicates", std::int64_t(pairs.size()) - distinct},
              {"edges_checked", distinct},
              {"edges_on_isoline", distinct - off_edges},
              {"edges_off_isoline", off_edges},
              {"faces_checked", sides},
              {"faces_off_isoline", off_sides}};
  c.note = "in every face containing a feature edge (u < v): u_u = u_v in Z or v_u = v_v in Z, exactly; "
           "one witness per face off its isoline";
  c.status = off_edges == 0 ? Status::Pass : Status::Fail;
  return c;
}

// The pairs as edges of t (same order), or the message of the first that is not one.
std::vector<std::int64_t> feature_edge_ids(const Topology& t, const std::vector<FeatureEdge>& pairs,
                                           std::string& error) {
  std::vector<std::int64_t> ids;
  ids.reserve(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {  // bound: number of pairs
    const FeatureEdge& p = pairs[i];
    auto where = [&] {  // built only for the message
      return (p.line > 0 ? "features line " + std::to_string(p.line) : "feature edge " + std::to_string(i)) +
             ": pair \"" + std::to_string(p.a) + " " + std::to_string(p.b) + "\"";
    };
    for (std::int64_t x : {p.a, p.b})
      if (x < 0 || x >= t.V) {
        error = where() + ": vertex id " + std::to_string(x) + " out of range (the mesh has " +
                std::to_string(t.V) + " vertices, ids 0.." + std::to_string(t.V - 1) + ")";
        return {};
      }
    const std::int64_t e = detail::find_edge(t, p.a, p.b);
    if (e < 0) {
      error = where() + " is not an edge of the mesh";
      return {};
    }
    ids.push_back(e);
  }
  return ids;
}

int quadrant(const ExactPoint& o, const ExactPoint& p) {
  const bool f = o.filterable && p.filterable;
  const int sx = compare(p.x, p.ax, o.x, o.ax, f), sy = compare(p.y, p.ay, o.y, o.ay, f);
  if (sx == 0 && sy == 0) return -1;
  if (sx > 0 && sy >= 0) return 0;
  if (sx <= 0 && sy > 0) return 1;
  if (sx < 0 && sy <= 0) return 2;
  return 3;
}

Report unreadable(const std::string& mode, const std::string& source, const std::string& msg, std::int64_t line) {
  Report r;
  r.mode = mode;
  r.source = source;
  r.verdict = Verdict::Unreadable;
  r.error = msg;
  r.error_line = line;
  return r;
}

void finish(Report& r) {
  bool all = !r.checks.empty();
  for (const auto& c : r.checks) all = all && c.status == Status::Pass;
  if (r.features) all = all && r.features->status == Status::Pass;
  r.verdict = all ? Verdict::Valid : Verdict::Invalid;
}

Report certify_igm_data(IgmData& d, const Options& opt, const std::string& source) {
  Report rep;
  rep.mode = "igm";
  rep.source = source;
  const std::size_t W = opt.max_witnesses;
  const std::int64_t F = std::int64_t(d.face_begin.size()) - 1;
  // The per-element work runs on opt.threads threads over a static partition of the elements
  // (certify/README.md, "Threads"); every count, histogram and witness list is merged in element
  // order, so the report does not depend on the thread count.
  const std::int64_t NU = std::int64_t(d.uv.size());
  detail::parallel_ranges(NU, detail::range_count(NU, opt.threads), [&](int, std::int64_t b, std::int64_t e) {
    for (std::int64_t i = b; i < e; ++i) prepare(d.uv[i]);
  });
  auto uv = [&](std::int64_t corner) -> const ExactPoint& { return d.uv[d.corner_uv[corner]]; };

  // ---- check 1: topology ----
  CheckResult c1;
  c1.id = 1;
  c1.name = "topology";
  Topology t = detail::analyze_topology(d.V, d.face_begin, d.corner_vertex, opt, c1);
  detail::fill_mesh(rep, t, c1);
  std::vector<std::int64_t> feature_ids;
  if (opt.feature_edges) {
    std::string error;
    feature_ids = feature_edge_ids(t, *opt.feature_edges, error);
    if (!error.empty()) return unreadable("igm", source, error, 0);
  }

  // ---- check 2: strictly positive UV triangles ----
  CheckResult c2;
  c2.id = 2;
  c2.name = "uv_orientation";
  std::vector<signed char> orient(static_cast<std::size_t>(F));
  detail::parallel_ranges(F, detail::range_count(F, opt.threads), [&](int, std::int64_t b, std::int64_t e) {
    for (std::int64_t f = b; f < e; ++f) orient[f] = static_cast<signed char>(orient2d(uv(3 * f), uv(3 * f + 1), uv(3 * f + 2)));
  });
  std::int64_t positive = 0, flipped = 0, degenerate = 0;
  for (std::int64_t f = 0; f < F; ++f) {  // bound: F
    const ExactPoint &a = uv(3 * f), &b = uv(3 * f + 1), &c = uv(3 * f + 2);
    const int o = orient[f];
    if (o > 0) {
      ++positive;
      continue;
    }
    (o < 0 ? flipped : degenerate) += 1;
    add_witness(c2, W,
                {"face", {f}, o < 0 ? "flipped (negative orientation)" : "degenerate (zero area)",
                 {{"uv0", point_string(a.x, a.y)},
                  {"uv1", point_string(b.x, b.y)},
                  {"uv2", point_string(c.x, c.y)},
                  {"orient2d", orient2d_value(a, b, c).get_str()}}});
  }
  c2.counts = {{"faces", F}, {"positive", positive}, {"flipped", flipped}, {"degenerate", degenerate}};
  c2.status = (flipped == 0 && degenerate == 0 && F > 0) ? Status::Pass : Status::Fail;

  // ---- check 3: transitions across interior edges ----
  CheckResult c3;
  c3.id = 3;
  c3.name = "transitions";
  c3.histogram_name = "rotation_k";
  std::vector<signed char> edge_k(static_cast<std::size_t>(t.E), kNotInterior);
  // For a non-rigid edge: the rotation nearest to the actual relation of its edge vectors (the k
  // with the largest exact dot product (R^k e_a) . e_b, -1 on a tie), used only to report the index
  // of vertices on non-rigid edges (check 4, "nonrigid ring").
  std::vector<signed char> edge_near_k(static_cast<std::size_t>(t.E), -1);
  struct EdgeCounts {
    std::int64_t checked = 0, not_interior = 0, fail_rot = 0, fail_trans = 0, zero_len = 0;
    std::int64_t bnd_checked = 0, bnd_off = 0;
  };
  const int edge_ranges = detail::range_count(t.E, opt.threads);
  std::vector<EdgeCounts> edge_counts(static_cast<std::size_t>(edge_ranges));
  std::vector<CheckResult> edge_parts(static_cast<std::size_t>(edge_ranges));
  detail::parallel_ranges(t.E, edge_ranges, [&](int r, std::int64_t e_begin, std::int64_t e_end) {
  // This range's counts and witnesses (merged below in range order).
  EdgeCounts& n = edge_counts[static_cast<std::size_t>(r)];
  std::int64_t &checked = n.checked, &not_interior = n.not_interior, &fail_rot = n.fail_rot,
               &fail_trans = n.fail_trans, &zero_len = n.zero_len, &bnd_checked = n.bnd_checked,
               &bnd_off = n.bnd_off;
  CheckResult& c3 = edge_parts[static_cast<std::size_t>(r)];
  mpq_class e1x, e1y, e2x, e2y, tx, ty;
  for (std::int64_t e = e_begin; e < e_end; ++e) {  // bound: E edges
    const std::int64_t h0 = t.edge_halfedges[t.edge_start[e]];
    if (t.twin[h0] < 0) {
      ++not_interior;
      if (!opt.allow_boundary || !t.on_boundary(h0)) continue;
      // A boundary edge lies on an integer isoline of its face's chart (rigid transitions keep
      // both the direction class and integrality, so the chart does not matter).
      ++bnd_checked;
      if (std::optional<Witness> w = off_isoline(d, t, h0)) {
        ++bnd_off;
        w->reason = "boundary edge not on an integer isoline (u or v constant and integer)";
        add_witness(c3, W, std::move(*w));
      }
      continue;
    }
    // h1: a -> b with a < b, in face f1; h2: b -> a in face f2.
    const std::int64_t h1 = t.origin(h0) < t.target(h0) ? h0 : t.twin[h0];
    const std::int64_t h2 = t.twin[h1];
    const std::int64_t ca1 = h1, cb1 = t.next(h1), cb2 = h2, ca2 = t.next(h2);
    ++checked;
    if (d.corner_uv[ca1] == d.corner_uv[ca2] && d.corner_uv[cb1] == d.corner_uv[cb2] &&
        d.corner_uv[ca1] != d.corner_uv[cb1]) {
      edge_k[e] = 0;  // the same UV records on both sides: identity
      ++c3.histogram[0];
      continue;
    }
    const ExactPoint &a1 = uv(ca1), &b1 = uv(cb1), &a2 = uv(ca2), &b2 = uv(cb2);
    mpq_sub(e1x.get_mpq_t(), b1.x.get_mpq_t(), a1.x.get_mpq_t());
    mpq_sub(e1y.get_mpq_t(), b1.y.get_mpq_t(), a1.y.get_mpq_t());
    mpq_sub(e2x.get_mpq_t(), b2.x.get_mpq_t(), a2.x.get_mpq_t());
    mpq_sub(e2y.get_mpq_t(), b2.y.get_mpq_t(), a2.y.get_mpq_t());
    const std::int64_t u = t.origin(h1), v = t.target(h1);
    const bool zero1 = sgn(e1x) == 0 && sgn(e1y) == 0, zero2 = sgn(e2x) == 0 && sgn(e2y) == 0;
    int found = kNoRotation;
    if (zero1 && zero2) {
      for (int k = 0; k < 4 && found < 0; ++k) {  // bound: 4
        translation(k, a2, a1, tx, ty);
        if (is_integer(tx) && is_integer(ty)) found = k;
      }
      if (found >= 0) {
        ++zero_len;
        edge_k[e] = kZeroLength;
        continue;
      }
      found = kNonInteger;
    } else if (!zero1 && !zero2) {
      for (int k = 0; k < 4; ++k) {  // bound: 4
        if (rotated_equal(k, e1x, e1y, e2x, e2y)) {
          found = k;
          break;
        }
      }
      if (found >= 0) {
        // t = a2 - R^k a1; for b it is b2 - R^k b1 = t + (e2 - R^k e1) = t, the same map.
        translation(found, a2, a1, tx, ty);
        if (is_integer(tx) && is_integer(ty)) {
          edge_k[e] = static_cast<signed char>(found);
          ++c3.histogram[found];
          continue;
        }
        edge_k[e] = kNonInteger;
        edge_near_k[e] = static_cast<signed char>(found);
        ++fail_trans;
        add_witness(c3, W,
                    {"edge", {u, v}, "translation not integer",
                     {{"face_a", std::to_string(t.corner_face[h1])},
                      {"face_b", std::to_string(t.corner_face[h2])},
                      {"k", std::to_string(found)},
                      {"t", point_string(tx, ty)},
                      {"uv_a_u", point_string(a1.x, a1.y)},
                      {"uv_a_v", point_string(b1.x, b1.y)},
                      {"uv_b_u", point_string(a2.x, a2.y)},
                      {"uv_b_v", point_string(b2.x, b2.y)}}});
        continue;
      }
    }
    edge_k[e] = static_cast<signed char>(found);
    if (found == kNoRotation && !zero1 && !zero2) {
      // dot_k = (R^k e1) . e2: dot_0 = e1.e2, dot_1 = e1 x e2 (cross), dot_2 = -dot_0, dot_3 = -dot_1.
      const mpq_class d0 = e1x * e2x + e1y * e2y, d1 = e1x * e2y - e1y * e2x;
      const int c = cmp(abs(d0), abs(d1));
      if (c > 0) edge_near_k[e] = sgn(d0) > 0 ? 0 : 2;
      if (c < 0) edge_near_k[e] = sgn(d1) > 0 ? 1 : 3;
    }
    if (found == kNonInteger) {
      ++fail_trans;
    } else {
      ++fail_rot;
    }
    add_witness(c3, W,
                {"edge", {u, v},
                 found == kNonInteger ? "zero-length edge, translation not integer for any k"
                                      : "edge vectors not related by a rotation R^k",
                 {{"face_a", std::to_string(t.corner_face[h1])},
                  {"face_b", std::to_string(t.corner_face[h2])},
                  {"vector_a", point_string(e1x, e1y)},
                  {"vector_b", point_string(e2x, e2y)},
                  {"uv_a_u", point_string(a1.x, a1.y)},
                  {"uv_a_v", point_string(b1.x, b1.y)},
                  {"uv_b_u", point_string(a2.x, a2.y)},
                  {"uv_b_v", point_string(b2.x, b2.y)}}});
  }
  });
  EdgeCounts sum;
  for (int r = 0; r < edge_ranges; ++r) {
    const EdgeCounts& n = edge_counts[static_cast<std::size_t>(r)];
    sum.checked += n.checked;
    sum.not_interior += n.not_interior;
    sum.fail_rot += n.fail_rot;
    sum.fail_trans += n.fail_trans;
    sum.zero_len += n.zero_len;
    sum.bnd_checked += n.bnd_checked;
    sum.bnd_off += n.bnd_off;
    detail::merge_witnesses(c3, W, std::move(edge_parts[static_cast<std::size_t>(r)]));
  }
  const std::int64_t checked = sum.checked, not_interior = sum.not_interior, fail_rot = sum.fail_rot,
                     fail_trans = sum.fail_trans, zero_len = sum.zero_len, bnd_checked = sum.bnd_checked,
                     bnd_off = sum.bnd_off;
  c3.counts = {{"interior_edges_checked", checked},   {"rigid", checked - fail_rot - fail_trans},
               {"non_rigid", fail_rot + fail_trans},  {"no_rotation_matches", fail_rot},
               {"translation_not_integer", fail_trans}, {"zero_length_both_sides", zero_len},
               {"edges_not_interior", not_interior}};
  c3.note = "k maps the chart of the face left of u->v (u<v) onto the chart of the face right of it";
  if (opt.allow_boundary) {
    c3.counts.insert(c3.counts.end(), {{"boundary_edges_checked", bnd_checked},
                                       {"boundary_edges_on_isoline", bnd_checked - bnd_off},
                                       {"boundary_edges_off_isoline", bnd_off}});
    c3.note += "; boundary edges: u or v constant and integer along the edge in its face's chart";
  }
  if (fail_rot + fail_trans + bnd_off > 0) {
    c3.status = Status::Fail;
  } else {
    const bool unjudged = not_interior > bnd_checked || t.E == 0;  // e.g. non-manifold edges
    c3.status = unjudged ? Status::Incomplete : Status::Pass;
  }

  // ---- check 4: vertex indices (total angle k*pi/2), cones on integer points, Poincare-Hopf ----
  CheckResult c4;
  c4.id = 4;
  c4.name = "cones";
  c4.histogram_name = "vertex_index_k";
  if (opt.allow_boundary) c4.boundary_histogram_name = "boundary_index_k";
  // One vertex's walk over its corners: interior vertices around the closed ring, boundary
  // vertices (allow_boundary) across the open fan from the outgoing to the incoming boundary edge.
  struct Walk {
    enum Kind { Determined, NonrigidRing, Undetermined, Inconsistent } kind = Undetermined;
    std::int64_t k = 0;                   // quadrant boundaries crossed: angle k*pi/2
    const ExactPoint* non_int = nullptr;  // a corner UV that is not an integer point
    bool boundary = false;
    const char* why = "";                 // reason when undetermined
  };
  auto walk = [&](std::int64_t v) {
    mpq_class rx, ry, gx, gy, cr;  // scratch: each vertex's walk on its own
    Walk w;
    w.boundary = opt.allow_boundary && t.boundary_out[v] >= 0;
    if (!t.vertex_manifold[v]) {
      w.why = "non-manifold vertex";
      return w;
    }
    const std::int64_t start = w.boundary ? t.boundary_out[v] : t.vertex_corner[v];
    if (w.boundary && !axis_parallel(uv(start), uv(t.next(start)))) {
      w.why = "outgoing boundary edge not parallel to an axis";
      return w;
    }
    bool rigid = true;  // every edge of the ring passed check 3
    bool fan_end = false;
    std::int64_t sum_c = 0, hol = 0, steps = 0, h = start;
    int q_first = -1, q_last = -1;
    for (;;) {  // bound: vertex_degree[v] steps (checked)
      if (++steps > t.vertex_degree[v]) {
        w.why = "corner ring does not close";
        return w;
      }
      const std::int64_t f = t.corner_face[h], p = t.prev(h);
      const ExactPoint& pv = uv(h);
      if (!w.non_int && !(is_integer(pv.x) && is_integer(pv.y))) w.non_int = &pv;
      const int q1 = quadrant(pv, uv(t.next(h))), q2 = quadrant(pv, uv(p));
      if (q1 < 0 || q2 < 0) {
        w.why = "zero-length UV edge at the vertex";
        return w;
      }
      if (q_first < 0) q_first = q1;
      q_last = q2;
      int c;
      if (orient[f] > 0) {
        c = (q2 - q1 + 4) % 4;  // ccw turn in (0, pi): 0..2 quadrant boundaries
      } else if (orient[f] < 0) {
        c = -((q1 - q2 + 4) % 4);  // cw turn in (-pi, 0)
      } else {
        c = q1 == q2 ? 0 : 3;  // collinear: same direction 0, opposite directions undecidable
      }
      if (c == 3 || c == -3) {
        w.why = "antiparallel corner (degenerate triangle)";
        return w;
      }
      sum_c += c;
      if (w.boundary && t.on_boundary(p)) {  // the incoming boundary edge ends the fan
        if (!axis_parallel(pv, uv(p))) {
          w.why = "incoming boundary edge not parallel to an axis";
          return w;
        }
        fan_end = true;
        break;
      }
      const std::int64_t e = t.edge_of[p];
      if (e < 0 || t.twin[p] < 0) {
        w.why = "ring crosses a boundary or non-manifold edge";
        return w;
      }
      int k = edge_k[e];
      const std::int64_t hn = t.twin[p];  // v -> b in the next face
      if (k < 0) {
        // Non-rigid edge: transport with the nearest rotation and count the quadrant boundaries
        // crossed by the gap between the transported direction and the next face's direction.
        k = edge_near_k[e];
        if (k < 0) {
          w.why = "ring crosses a zero-length or tied non-rigid edge";
          return w;
        }
        rigid = false;
        const int r = ((t.origin(p) < t.target(p) ? k : -k) % 4 + 4) % 4;
        const ExactPoint &ov = pv, &ob = uv(p);                // in face f: v and b
        const ExactPoint &nv = uv(hn), &nb = uv(t.next(hn));  // in the next face
        gx = ob.x - ov.x;
        gy = ob.y - ov.y;
        switch (r) {  // (rx, ry) = R^r (gx, gy)
          case 0: rx = gx; ry = gy; break;
          case 1: rx = -gy; ry = gx; break;
          case 2: rx = -gx; ry = -gy; break;
          default: rx = gy; ry = -gx; break;
        }
        gx = nb.x - nv.x;
        gy = nb.y - nv.y;
        cr = rx * gy - ry * gx;
        ExactPoint zero, a, b2;
        a.x = rx;
        a.y = ry;
        b2.x = gx;
        b2.y = gy;
        const int qa = quadrant(zero, a), qb = quadrant(zero, b2);
        if (qa < 0 || qb < 0) {
          w.why = "zero-length UV edge at the vertex";
          return w;
        }
        int g;
        if (sgn(cr) > 0) {
          g = (qb - qa + 4) % 4;
        } else if (sgn(cr) < 0) {
          g = -((qa - qb + 4) % 4);
        } else {
          g = qa == qb ? 0 : 3;
        }
        if (g == 3 || g == -3) {
          w.why = "antiparallel gap across a non-rigid edge";
          return w;
        }
        sum_c += g;
      }
      hol += (t.origin(p) < t.target(p)) ? k : -k;
      h = hn;
      if (h == start) break;  // interior ring closed (a boundary fan never returns to start)
    }
    if (steps != t.vertex_degree[v] || w.boundary != fan_end) {
      w.why = "corner ring does not cover the vertex";
      return w;
    }
    // The quadrant of the direction followed along the walk moves by c per corner and by the
    // rotation per crossed edge: a closed ring returns to its start quadrant, an open fan ends in
    // the quadrant of its incoming boundary edge. Internal cross-check: cannot fail.
    const std::int64_t drift = w.boundary ? q_first + sum_c + hol - q_last : sum_c + hol;
    if ((drift % 4 + 4) % 4 != 0) {
      w.kind = Walk::Inconsistent;
      w.why = "transport inconsistent (internal error)";
      return w;
    }
    w.k = sum_c;
    w.kind = rigid ? Walk::Determined : Walk::NonrigidRing;
    return w;
  };

  const std::size_t NC = t.components.size();
  std::vector<std::int64_t> comp_ph(NC, 0);   // sum (4 - k) + sum_boundary (2 - k)
  std::vector<char> comp_exact(NC, 1);        // every vertex of the component determined
  std::int64_t determined = 0, undetermined = 0, cones = 0, off_integer = 0, nonpositive = 0;
  std::int64_t inconsistent = 0, nonrigid_ring = 0, nonrigid_cones = 0, nonrigid_off_integer = 0;
  std::int64_t bnd_vertices = 0, bnd_determined = 0, bnd_corners = 0, bnd_off_integer = 0;
  std::int64_t bnd_nonpositive = 0;
  std::vector<Walk> walks(static_cast<std::size_t>(d.V));
  detail::parallel_ranges(d.V, detail::range_count(d.V, opt.threads), [&](int, std::int64_t b, std::int64_t e) {
    for (std::int64_t v = b; v < e; ++v)  // bound: each walk <= degree steps
      if (t.vertex_corner[v] >= 0) walks[v] = walk(v);
  });
  for (std::int64_t v = 0; v < d.V; ++v) {  // bound: V vertices
    if (t.vertex_corner[v] < 0) continue;
    const Walk& w = walks[v];
    const std::int32_t comp = t.vertex_component[v];
    const std::int64_t k = w.k;
    const std::int64_t flat = w.boundary ? 2 : 4;  // index of a regular vertex
    const std::string ks = std::to_string(k);
    if (w.boundary) ++bnd_vertices;
    if (w.kind == Walk::Undetermined || w.kind == Walk::Inconsistent) {
      if (w.kind == Walk::Inconsistent) ++inconsistent;
      ++undetermined;
      comp_exact[comp] = 0;
      if (w.boundary)
        add_witness(c4, W, {"vertex", {v}, "boundary angle undetermined", {{"why", w.why}}});
      continue;
    }
    if (w.kind == Walk::NonrigidRing) {
      // Index with the nearest rotation across this ring's non-rigid edges: reported, not exact.
      ++nonrigid_ring;
      comp_exact[comp] = 0;
      if (k != flat) ++nonrigid_cones;
      if (k != flat && w.non_int) {
        ++nonrigid_off_integer;
        add_witness(c4, W,
                    {"vertex", {v},
                     w.boundary ? "boundary corner not on an integer point (ring has non-rigid "
                                  "edges; index with nearest rotations)"
                                : "cone not on an integer point (ring has non-rigid edges; index "
                                  "with nearest rotations)",
                     {{"k", ks}, {"uv", point_string(w.non_int->x, w.non_int->y)}}});
      }
      continue;
    }
    ++determined;
    comp_ph[comp] += flat - k;
    if (w.boundary) {
      ++bnd_determined;
      ++c4.boundary_histogram[k];
      if (k != 2) ++bnd_corners;
      if (k <= 0) {
        ++bnd_nonpositive;
        add_witness(c4, W, {"vertex", {v}, "boundary index k <= 0 (angle not positive)",
                            {{"k", ks}}});
      }
      if (k != 2 && w.non_int) {
        ++bnd_off_integer;
        add_witness(c4, W, {"vertex", {v}, "boundary corner (k != 2) not on an integer point",
                            {{"k", ks}, {"uv", point_string(w.non_int->x, w.non_int->y)}}});
      }
      continue;
    }
    ++c4.histogram[k];
    if (k != 4) ++cones;
    if (k <= 0) {
      ++nonpositive;
      add_witness(c4, W, {"vertex", {v}, "index k <= 0 (total angle not positive)", {{"k", ks}}});
    }
    if (k != 4 && w.non_int) {
      ++off_integer;
      add_witness(c4, W, {"vertex", {v}, "cone not on an integer point",
                          {{"k", ks}, {"uv", point_string(w.non_int->x, w.non_int->y)}}});
    }
  }
  // Poincare-Hopf per component, where every vertex of the component has an exact index.
  std::int64_t ph_sum = 0, comps_checked = 0, comps_failed = 0;
  for (std::size_t c = 0; c < NC; ++c) {  // bound: components <= V
    if (!t.ok || !comp_exact[c]) continue;
    ++comps_checked;
    ph_sum += comp_ph[c];
    const Topology::Component& tc = t.components[c];
    rep.components[c].poincare_hopf_sum = comp_ph[c];
    if (comp_ph[c] == 4 * tc.euler()) continue;
    ++comps_failed;
    Witness w{"mesh", {}, "Poincare-Hopf violated: sum(4-k) != 4*chi",
              {{"sum_4_minus_k", std::to_string(comp_ph[c])},
               {"4_chi", std::to_string(4 * tc.euler())}}};
    if (opt.allow_boundary) {
      w.reason = "Poincare-Hopf violated: sum_interior(4-k) + sum_boundary(2-k) != 4*chi";
      w.values[0].first = "sum_index_defects";
    }
    if (NC > 1) {
      w.kind = "component";
      w.ids = {tc.first_vertex};
      w.reason += " of the component";
    }
    add_witness(c4, W, std::move(w));
  }
  const bool ph_checkable = t.ok && comps_checked == std::int64_t(NC);
  c4.counts = {{"vertices_determined", determined},
               {"vertices_nonrigid_ring", nonrigid_ring},
               {"vertices_undetermined", undetermined},
               {"cones", cones},
               {"cones_off_integer", off_integer},
               {"nonrigid_ring_cones", nonrigid_cones},
               {"nonrigid_ring_cones_off_integer", nonrigid_off_integer},
               {"cones_off_integer_total", off_integer + nonrigid_off_integer},
               {"nonpositive_index", nonpositive},
               {"poincare_hopf_sum", ph_checkable ? ph_sum : 0},
               {"poincare_hopf_expected", ph_checkable ? 4 * t.euler : 0},
               {"poincare_hopf_checked", ph_checkable ? 1 : 0},
               {"transport_inconsistent", inconsistent}};
  if (opt.allow_boundary) {
    c4.counts.insert(c4.counts.end(), {{"boundary_vertices", bnd_vertices},
                                       {"boundary_vertices_determined", bnd_determined},
                                       {"boundary_corners", bnd_corners},
                                       {"boundary_corners_off_integer", bnd_off_integer},
                                       {"boundary_nonpositive_index", bnd_nonpositive}});
  }
  if (opt.allow_components) {
    c4.counts.insert(c4.counts.end(), {{"poincare_hopf_components_checked", comps_checked},
                                       {"poincare_hopf_components_failed", comps_failed}});
  }
  c4.note =
      "determined: ring of rigid edges, exact index; nonrigid_ring: ring crosses edges that failed check 3, index "
      "computed with the nearest rotation there (reported, not a proof); undetermined: non-manifold ring, "
      "zero-length or tied edge, or antiparallel corner";
  if (opt.allow_boundary)
    c4.note += "; boundary vertices: angle k*pi/2 over the fan between their boundary edges, "
               "flat at k = 2, exact when both boundary edges are axis-parallel";
  const bool failed = off_integer > 0 || nonrigid_off_integer > 0 || nonpositive > 0 ||
                      bnd_off_integer > 0 || bnd_nonpositive > 0 || comps_failed > 0;
  if (failed) {
    c4.status = Status::Fail;
  } else if (!ph_checkable) {
    c4.status = Status::Incomplete;
  } else {
    c4.status = Status::Pass;
  }
  rep.checks.push_back(std::move(c1));
  rep.checks.push_back(std::move(c2));
  rep.checks.push_back(std::move(c3));
  rep.checks.push_back(std::move(c4));
  if (opt.feature_edges) rep.features = check_features(d, t, *opt.feature_edges, feature_ids, W);
  finish(rep);
  return rep;
}

// Quad mode: when an expectation is given, counts it ("expected_<name>") and requires the found
// value to be defined and equal (else a mesh witness with both). Returns false on a mismatch.
bool expect(CheckResult& c, std::size_t max_witnesses, const std::string& name,
            const std::optional<std::int64_t>& found, const std::optional<std::int64_t>& expected,
            const char* reason) {
  if (!expected) return true;
  c.counts.emplace_back("expected_" + name, *expected);
  if (found == expected) return true;
  add_witness(c, max_witnesses,
              {"mesh", {}, reason,
               {{name, found ? std::to_string(*found) : "undefined"},
                {"expected", std::to_string(*expected)}}});
  return false;
}

// The components' (genus, loops) equal the expected ones as multisets; a component with an
// undefined genus or loop count matches nothing.
bool components_match(const Report& rep, std::vector<ComponentTopology> expected) {
  std::vector<ComponentTopology> found;
  for (const auto& c : rep.components) {  // bound: components
    if (!c.genus || !c.boundary_loops) return false;
    found.push_back({*c.genus, *c.boundary_loops});
  }
  std::sort(found.begin(), found.end());
  std::sort(expected.begin(), expected.end());
  return found == expected;
}

// "(g, b) x n" groups of a multiset, sorted; -1 stands for undefined.
std::string multiset_string(std::vector<ComponentTopology> m) {
  std::sort(m.begin(), m.end());
  std::string s;
  for (std::size_t i = 0; i < m.size();) {  // bound: |m|, each group consumed once
    std::size_t j = i;
    while (j < m.size() && m[j] == m[i]) ++j;
    if (!s.empty()) s += ", ";
    s += "(genus " + std::to_string(m[i].genus) + ", loops " +
         std::to_string(m[i].boundary_loops) + ") x " + std::to_string(j - i);
    i = j;
  }
  return s.empty() ? "none" : s;
}

// Checks 1 + 5 on a polygon mesh (quad mode).
Report certify_quad_data(std::int64_t V, const std::vector<std::int64_t>& face_begin,
                         const std::vector<int>& corner_vertex, const Options& opt, const std::string& source) {
  Report rep;
  rep.mode = "quad";
  rep.source = source;
  CheckResult c5;
  c5.id = 5;
  c5.name = "quad_mesh";
  c5.histogram_name = "valence";
  Topology t = detail::analyze_topology(V, face_begin, corner_vertex, opt, c5);
  const std::int64_t F = std::int64_t(face_begin.size()) - 1;
  std::int64_t non_quads = 0;
  for (std::int64_t f = 0; f < F; ++f) {  // bound: F
    const std::int64_t n = face_begin[f + 1] - face_begin[f];
    if (n != 4) {
      ++non_quads;
      add_witness(c5, opt.max_witnesses, {"face", {f}, "not a quad", {{"corners", std::to_string(n)}}});
    }
  }
  std::vector<std::int64_t> valence(static_cast<std::size_t>(V), 0);
  for (std::int64_t e = 0; e < t.E; ++e) {  // bound: E
    const std::int64_t h = t.edge_halfedges[t.edge_start[e]];
    ++valence[t.origin(h)];
    ++valence[t.target(h)];
  }
  for (std::int64_t v = 0; v < V; ++v) ++c5.histogram[valence[v]];  // bound: V
  bool ok = t.ok && non_quads == 0;
  c5.counts.emplace_back("non_quad_faces", non_quads);
  detail::fill_mesh(rep, t, c5);
  ok &= expect(c5, opt.max_witnesses, "genus", rep.genus, opt.expected_genus,
                "genus differs from the expected genus");
  ok &= expect(c5, opt.max_witnesses, "boundary_loops", rep.boundary_loops,
                opt.expected_boundary_loops, "number of boundary loops differs from the expected one");
  if (!opt.expected_components.empty() && !components_match(rep, opt.expected_components)) {
    ok = false;
    std::vector<ComponentTopology> found;
    for (const auto& c : rep.components)  // bound: components
      found.push_back({c.genus.value_or(-1), c.boundary_loops.value_or(-1)});
    add_witness(c5, opt.max_witnesses,
                {"mesh", {}, "components' (genus, boundary loops) differ from the expected ones",
                 {{"found", multiset_string(found)},
                  {"expected", multiset_string(opt.expected_components)}}});
  }
  c5.status = ok ? Status::Pass : Status::Fail;
  rep.checks.push_back(std::move(c5));
  finish(rep);
  return rep;
}

Report igm_from_text(const std::string& text, const Options& opt, const std::string& source) {
  ObjReadResult r = read_obj(text);
  if (!r.ok) return unreadable("igm", source, r.error, r.error_line);
  ObjMesh& m = r.mesh;
  IgmData d;
  d.V = m.num_vertices;
  const std::int64_t F = m.num_faces();
  if (F == 0) return unreadable("igm", source, "no faces", 0);
  for (std::int64_t f = 0; f < F; ++f) {  // bound: F
    const std::int64_t n = m.face_begin[f + 1] - m.face_begin[f];
    if (n != 3)
      return unreadable("igm", source,
                        "line " + std::to_string(m.face_line[f]) + ": face with " + std::to_string(n) +
                            " corners; an IGM is a triangle mesh (use quad mode for quad meshes)",
                        m.face_line[f]);
    for (std::int64_t c = m.face_begin[f]; c < m.face_begin[f + 1]; ++c)
      if (m.corner_uv[c] < 0)
        return unreadable("igm", source,
                          "line " + std::to_string(m.face_line[f]) + ": face corner without a UV (f v/vt expected)",
                          m.face_line[f]);
  }
  d.face_begin = std::move(m.face_begin);
  d.corner_vertex = std::move(m.corner_vertex);
  d.corner_uv = std::move(m.corner_uv);
  d.uv.resize(m.uv.size());
  for (std::size_t i = 0; i < m.uv.size(); ++i) {  // bound: number of vt
    mpq_swap(d.uv[i].x.get_mpq_t(), m.uv[i][0].get_mpq_t());
    mpq_swap(d.uv[i].y.get_mpq_t(), m.uv[i][1].get_mpq_t());
  }
  return certify_igm_data(d, opt, source);
}

Report quads_from_text(const std::string& text, const Options& opt, const std::string& source) {
  ObjReadResult r = read_obj(text);
  if (!r.ok) return unreadable("quad", source, r.error, r.error_line);
  if (r.mesh.num_faces() == 0) return unreadable("quad", source, "no faces", 0);
  return certify_quad_data(r.mesh.num_vertices, r.mesh.face_begin, r.mesh.corner_vertex, opt, source);
}

}  // namespace

namespace detail {

std::string read_file(const std::string& path, bool& ok) {
  std::ifstream in(path, std::ios::binary);
  ok = static_cast<bool>(in);
  if (!ok) return {};
  std::ostringstream ss;
  ss << in.rdbuf();
  ok = !in.bad();
  return ss.str();
}

}  // namespace detail

Report certify_igm(const IgmInput& in, const Options& opt) {
  IgmInput copy = in;
  return certify_igm(std::move(copy), opt);
}

Report certify_igm(IgmInput&& in, const Options& opt) {
  auto num = [](std::int64_t x) { return std::to_string(x); };
  const std::string src = "<memory>";
  const std::int64_t F = std::int64_t(in.faces.size());
  if (F == 0) return unreadable("igm", src, "no faces", 0);
  if (std::int64_t(in.corner_uv.size()) != 3 * F)
    return unreadable("igm", src,
                      "corner_uv has " + std::to_string(in.corner_uv.size()) + " entries, expected 3 per face (" +
                          std::to_string(3 * F) + ")",
                      0);
  const std::int64_t declared_v =
      in.num_vertices >= 0 ? in.num_vertices : (in.positions.empty() ? -1 : std::int64_t(in.positions.size()));
  if (declared_v > 3 * F) {  // no allocation proportional to a declared but absent size
    std::string m = "num_vertices ";
    m += num(declared_v);
    m += " exceeds the ";
    m += num(3 * F);
    m += " face corners: most vertices would be unreferenced";
    return unreadable("igm", src, m, 0);
  }
  IgmData d;
  std::int64_t max_index = -1;
  for (std::int64_t f = 0; f < F; ++f)  // bound: F
    for (int v : in.faces[f]) {
      if (v < 0 || (declared_v >= 0 && v >= declared_v))
        return unreadable("igm", src, "face " + std::to_string(f) + ": vertex index " + std::to_string(v) + " out of range", 0);
      max_index = std::max<std::int64_t>(max_index, v);
    }
  d.V = declared_v >= 0 ? declared_v : max_index + 1;
  d.face_begin.resize(static_cast<std::size_t>(F + 1));
  d.corner_vertex.resize(static_cast<std::size_t>(3 * F));
  d.corner_uv.resize(static_cast<std::size_t>(3 * F));
  d.uv.resize(static_cast<std::size_t>(3 * F));
  for (std::int64_t f = 0; f <= F; ++f) d.face_begin[f] = 3 * f;  // bound: F+1
  for (std::int64_t c = 0; c < 3 * F; ++c) {                         // bound: 3F
    d.corner_vertex[c] = in.faces[c / 3][c % 3];
    d.corner_uv[c] = static_cast<int>(c);
    mpq_swap(d.uv[c].x.get_mpq_t(), in.corner_uv[c][0].get_mpq_t());  // the input is consumed
    mpq_swap(d.uv[c].y.get_mpq_t(), in.corner_uv[c][1].get_mpq_t());
  }
  return certify_igm_data(d, opt, src);
}

Report certify_quads(const QuadInput& in, const Options& opt) {
  const std::string src = "<memory>";
  const std::int64_t F = std::int64_t(in.quads.size());
  if (F == 0) return unreadable("quad", src, "no faces", 0);
  if (in.num_vertices > 4 * F) {
    std::string m = "num_vertices ";
    m += std::to_string(in.num_vertices);
    m += " exceeds the ";
    m += std::to_string(4 * F);
    m += " face corners: most vertices would be unreferenced";
    return unreadable("quad", src, m, 0);
  }
  std::int64_t max_index = -1;
  std::vector<std::int64_t> fb(static_cast<std::size_t>(F + 1));
  std::vector<int> cv;
  cv.reserve(static_cast<std::size_t>(4 * F));
  for (std::int64_t f = 0; f < F; ++f) {  // bound: F
    fb[f] = 4 * f;
    for (int v : in.quads[f]) {
      if (v < 0 || (in.num_vertices >= 0 && v >= in.num_vertices))
        return unreadable("quad", src, "quad " + std::to_string(f) + ": vertex index " + std::to_string(v) + " out of range", 0);
      max_index = std::max<std::int64_t>(max_index, v);
      cv.push_back(v);
    }
  }
  fb[F] = 4 * F;
  const std::int64_t V = in.num_vertices >= 0 ? in.num_vertices : max_index + 1;
  return certify_quad_data(V, fb, cv, opt, src);
}

Report certify_igm_text(const std::string& text, const Options& opt) { return igm_from_text(text, opt, "<text>"); }
Report certify_quads_text(const std::string& text, const Options& opt) { return quads_from_text(text, opt, "<text>"); }

Report certify_igm_file(const std::string& path, const Options& opt) {
  bool ok = false;
  std::string text = detail::read_file(path, ok);
  if (!ok) return unreadable("igm", path, "cannot read file '" + path + "'", 0);
  return igm_from_text(text, opt, path);
}

Report certify_quads_file(const std::string& path, const Options& opt) {
  bool ok = false;
  std::string text = detail::read_file(path, ok);
  if (!ok) return unreadable("quad", path, "cannot read file '" + path + "'", 0);
  return quads_from_text(text, opt, path);
}

}  // namespace igm::certify
