#include "igm/features/feature_edges.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include "igm/core/det_math.h"
#include "igm/core/error.h"
#include "igm/mesh/scale.h"

namespace igm {

namespace {

constexpr double kPi = 3.14159265358979323846;

struct V3 {
  double x, y, z;
};
V3 sub(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 cross(const V3& a, const V3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

// The angle between u and w is >= the angle whose cosine is c: u.w <= c |u| |w|, in squared
// form (no sqrt, no libm): c >= 0: u.w <= 0 or (u.w)^2 <= c^2 |u|^2 |w|^2; c < 0: u.w < 0 and
// (u.w)^2 >= c^2 |u|^2 |w|^2.
bool angle_at_least(const V3& u, const V3& w, double c) {
  const double d = dot(u, w);
  const double q = c * c * (dot(u, u) * dot(w, w));
  if (c >= 0) return d <= 0 || d * d <= q;
  return d < 0 && d * d >= q;
}

double check_angle(double degrees, const char* what) {
  if (!(degrees >= 0 && degrees <= 180))
    throw Error(ErrorKind::InvalidArgument,
                std::string(what) + " must be in [0, 180] degrees, got " + std::to_string(degrees));
  return det_sincos(degrees * (kPi / 180)).cos;
}

std::string pair_name(std::int64_t a, std::int64_t b) {
  return "feature edge (" + std::to_string(a) + ", " + std::to_string(b) + ")";
}

}  // namespace

FeatureEdges detect_features(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                             const std::vector<std::array<int, 2>>& user_edges, const FeatureOptions& options) {
  const double cos_sharp = check_angle(options.angle_degrees, "the feature angle");
  const double cos_corner = check_angle(options.corner_angle_degrees, "the feature corner angle");
  if (options.noise_min_edges < 0)
    throw Error(ErrorKind::InvalidArgument, "noise_min_edges must be >= 0, got " + std::to_string(options.noise_min_edges));
  if (!(options.noise_min_length >= 0 && options.noise_min_length <= 1))
    throw Error(ErrorKind::InvalidArgument,
                "noise_min_length must be in [0, 1] (of the diagonal), got " + std::to_string(options.noise_min_length));
  if (!(options.quad_size >= 0 && options.quad_size < INFINITY) ||
      !(options.min_quad_edges >= 0 && options.min_quad_edges < INFINITY))
    throw Error(ErrorKind::InvalidArgument, "quad_size and min_quad_edges must be finite and >= 0, got " +
                                                std::to_string(options.quad_size) + " and " +
                                                std::to_string(options.min_quad_edges));
  const int nv = mesh.num_vertices(), nh = mesh.num_halfedges(), nf = mesh.num_faces();
  if (static_cast<int>(positions.size()) != nv)
    throw Error(ErrorKind::InvalidArgument, "detect_features: " + std::to_string(positions.size()) +
                                                " positions for " + std::to_string(nv) + " vertices");
  const double s = unit_scale(positions);
  std::vector<V3> p(nv);
  V3 lo{0, 0, 0}, hi{0, 0, 0};
  for (int v = 0; v < nv; ++v) {
    p[v] = {s * positions[v].x, s * positions[v].y, s * positions[v].z};
    if (v == 0) lo = hi = p[v];
    lo = {std::min(lo.x, p[v].x), std::min(lo.y, p[v].y), std::min(lo.z, p[v].z)};
    hi = {std::max(hi.x, p[v].x), std::max(hi.y, p[v].y), std::max(hi.z, p[v].z)};
  }
  const V3 span = sub(hi, lo);
  const double diagonal = std::sqrt(dot(span, span)) / s;
  auto length = [&](int h) {
    const V3 d = sub(p[mesh.target(h)], p[mesh.origin(h)]);
    return std::sqrt(dot(d, d)) / s;
  };

  FeatureEdges out;
  out.halfedge.assign(nh, 0);
  auto canonical = [&](int h) { return mesh.twin(h) < 0 || h < mesh.twin(h) ? h : mesh.twin(h); };
  // --- sharp edges ---
  std::vector<V3> normal(nf);
  std::vector<std::uint8_t> zero(nf, 0);
  for (int f = 0; f < nf; ++f) {
    const auto fv = mesh.face_vertices(f);
    normal[f] = cross(sub(p[fv[1]], p[fv[0]]), sub(p[fv[2]], p[fv[0]]));
    zero[f] = normal[f].x == 0 && normal[f].y == 0 && normal[f].z == 0;
    out.stats.degenerate_faces += zero[f];
  }
  std::vector<std::uint8_t> detected(nh, 0), user(nh, 0);  // by canonical half-edge
  if (options.enabled)
    for (int h = 0; h < nh; ++h) {
      const int t = mesh.twin(h);
      if (t < h) continue;  // boundary (t == -1) or seen from the twin
      const int f = TriMesh::face(h), g = TriMesh::face(t);
      if (zero[f] || zero[g]) continue;
      detected[h] = angle_at_least(normal[f], normal[g], cos_sharp);
    }
  for (const auto& e : user_edges) {
    const int a = e[0], b = e[1];
    if (a < 0 || a >= nv || b < 0 || b >= nv)
      throw Error(ErrorKind::InvalidArgument, pair_name(a, b) + ": a vertex id out of range 0.." + std::to_string(nv - 1),
                  {a, b});
    if (a == b) throw Error(ErrorKind::InvalidArgument, pair_name(a, b) + ": the same vertex twice", {a, b});
    int h = mesh.find_halfedge(a, b);
    if (h < 0) h = mesh.find_halfedge(b, a);
    if (h < 0) throw Error(ErrorKind::InvalidArgument, pair_name(a, b) + ": not an edge of the mesh", {a, b});
    user[canonical(h)] = 1;
  }

  // Feature-edge adjacency per vertex (canonical half-edges, increasing), rebuilt after the noise rule.
  std::vector<int> edges, first, adjacent;
  auto build = [&](const std::vector<std::uint8_t>& is_feature) {
    edges.clear();
    for (int h = 0; h < nh; ++h)
      if (is_feature[h]) edges.push_back(h);
    first.assign(nv + 1, 0);
    for (int h : edges) ++first[mesh.origin(h) + 1], ++first[mesh.target(h) + 1];
    for (int v = 0; v < nv; ++v) first[v + 1] += first[v];
    adjacent.assign(first[nv], 0);
    std::vector<int> fill(first.begin(), first.end() - 1);
    for (int h : edges) adjacent[fill[mesh.origin(h)]++] = h, adjacent[fill[mesh.target(h)]++] = h;
  };
  auto degree = [&](int v) { return first[v + 1] - first[v]; };
  auto other_end = [&](int h, int v) { return mesh.origin(h) == v ? mesh.target(h) : mesh.origin(h); };
  auto directed = [&](int h, int from) { return mesh.origin(h) == from ? h : mesh.twin(h); };
  // Walks the chain from `start` along canonical edge h until a vertex where stop(v) holds (or back
  // to `start`); marks the edges used. Bound: each step uses an unused edge.
  std::vector<std::uint8_t> used(nh, 0);
  auto walk = [&](int start, int h, auto&& stop) {
    FeatureCurve c;
    c.vertices.push_back(start);
    int v = start;
    while (true) {
      used[h] = 1;
      c.halfedges.push_back(directed(h, v));
      c.length += length(h);
      v = other_end(h, v);
      c.vertices.push_back(v);
      if (v == start || stop(v)) break;
      int next = -1;
      for (int i = first[v]; i < first[v + 1]; ++i)
        if (!used[adjacent[i]]) next = adjacent[i];
      if (next < 0) break;
      h = next;
    }
    c.closed = c.vertices.front() == c.vertices.back();
    return c;
  };

  // --- the noise and resolution rules, once, on the chains (split where the degree is not 2) ---
  std::vector<std::uint8_t> kept(nh, 0), short_edge(nh, 0);
  for (int h = 0; h < nh; ++h) kept[h] = detected[h] || user[h];
  const bool noise_rule = options.noise_min_edges > 0 && options.noise_min_length > 0;
  const double min_length = options.quad_size * options.min_quad_edges;
  if (noise_rule || min_length > 0) {
    build(kept);
    auto junction = [&](int v) { return degree(v) != 2; };
    auto consider = [&](const FeatureCurve& c) {
      bool has_user = false;
      for (int h : c.halfedges) has_user |= user[canonical(h)] != 0;
      if (has_user) return;
      const bool noise = noise_rule && static_cast<int>(c.halfedges.size()) < options.noise_min_edges &&
                         c.length < options.noise_min_length * diagonal;
      if (!noise) {
        if (c.length < min_length) {  // the resolution rule: kept, not followed
          ++out.stats.short_chains;
          out.stats.short_edges += static_cast<int>(c.halfedges.size());
          for (int h : c.halfedges) short_edge[canonical(h)] = 1;
        }
        return;
      }
      ++out.stats.dropped_chains;
      out.stats.dropped_edges += static_cast<int>(c.halfedges.size());
      for (int h : c.halfedges) kept[canonical(h)] = 0;
    };
    for (int v = 0; v < nv; ++v)
      if (junction(v))
        for (int i = first[v]; i < first[v + 1]; ++i)
          if (!used[adjacent[i]]) consider(walk(v, adjacent[i], junction));
    for (int h : edges)
      if (!used[h]) consider(walk(mesh.origin(h), h, junction));
  }

  // --- corners and curves on the kept edges ---
  build(kept);
  std::vector<std::uint8_t> corner(nv, 0);
  for (int v = 0; v < nv; ++v) {
    const int d = degree(v);
    if (d == 0) continue;
    if (d != 2) {
      corner[v] = 1;
    } else {
      const int a = other_end(adjacent[first[v]], v), b = other_end(adjacent[first[v] + 1], v);
      corner[v] = angle_at_least(sub(p[v], p[a]), sub(p[b], p[v]), cos_corner);
    }
    if (corner[v]) out.corners.push_back(v);
  }
  used.assign(nh, 0);
  auto at_corner = [&](int v) { return corner[v] != 0; };
  for (int v : out.corners)
    for (int i = first[v]; i < first[v + 1]; ++i)
      if (!used[adjacent[i]]) out.curves.push_back(walk(v, adjacent[i], at_corner));
  for (int h : edges)
    if (!used[h]) out.curves.push_back(walk(mesh.origin(h), h, at_corner));

  out.edges = edges;
  out.follow.assign(nh, 0);
  for (int h : edges) {
    out.halfedge[h] = 1;
    if (mesh.twin(h) >= 0) out.halfedge[mesh.twin(h)] = 1;
    if (!short_edge[h]) {
      out.follow[h] = 1;
      if (mesh.twin(h) >= 0) out.follow[mesh.twin(h)] = 1;
    }
    out.stats.length += length(h);
    out.stats.user_edges += user[h];
  }
  out.stats.edges = static_cast<int>(edges.size());
  out.stats.curves = static_cast<int>(out.curves.size());
  for (const FeatureCurve& c : out.curves) out.stats.closed_curves += c.closed;
  out.stats.corners = static_cast<int>(out.corners.size());
  return out;
}

std::vector<std::array<std::int64_t, 2>> parse_feature_edges(std::istream& in, const std::string& name) {
  std::vector<std::array<std::int64_t, 2>> pairs;
  std::string line;
  std::int64_t number = 0;
  while (std::getline(in, line)) {  // bound: the stream's lines
    ++number;
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    std::istringstream s(line);
    std::string a, b, extra;
    if (!(s >> a)) continue;  // blank or comment
    auto bad = [&](const std::string& why) {
      return Error(ErrorKind::Parse, name + ": line " + std::to_string(number) + ": " + why, {number});
    };
    if (!(s >> b)) throw bad("expected two vertex ids \"i j\", got one");
    if (s >> extra) throw bad("expected two vertex ids \"i j\", got more");
    std::array<std::int64_t, 2> pair{};
    const std::string* text[2] = {&a, &b};
    for (int k = 0; k < 2; ++k) {
      std::size_t used = 0;
      long long value = -1;
      try {
        value = std::stoll(*text[k], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != text[k]->size() || value < 0 || value > 2147483647)
        throw bad("'" + *text[k] + "' is not a vertex id (an integer in 0..2^31-1)");
      pair[k] = value;
    }
    pairs.push_back(pair);
  }
  if (in.bad()) throw Error(ErrorKind::Io, name + ": read error");
  return pairs;
}

std::vector<std::array<std::int64_t, 2>> read_feature_edges(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw Error(ErrorKind::Io, path.string() + ": cannot open the features file");
  return parse_feature_edges(in, path.string());
}

std::vector<std::array<int, 2>> input_feature_edges(const TriMesh& mesh, const std::vector<std::int64_t>& input_vertex,
                                                     const std::vector<std::array<std::int64_t, 2>>& pairs,
                                                     std::vector<std::uint8_t>& found) {
  if (found.size() < pairs.size()) found.resize(pairs.size(), 0);
  std::vector<std::array<int, 2>> out;
  if (pairs.empty()) return out;
  std::unordered_map<std::int64_t, std::vector<int>> local;  // input id -> this mesh's vertices
  for (std::size_t v = 0; v < input_vertex.size() && static_cast<int>(v) < mesh.num_vertices(); ++v)
    local[input_vertex[v]].push_back(static_cast<int>(v));
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const auto a = local.find(pairs[i][0]), b = local.find(pairs[i][1]);
    if (a == local.end() || b == local.end()) continue;
    for (int u : a->second)
      for (int w : b->second)
        if (u != w && (mesh.find_halfedge(u, w) >= 0 || mesh.find_halfedge(w, u) >= 0)) {
          out.push_back({u, w});
          found[i] = 1;
        }
  }
  return out;
}

void check_feature_edges_found(const std::vector<std::array<std::int64_t, 2>>& pairs,
                               const std::vector<std::uint8_t>& found) {
  for (std::size_t i = 0; i < pairs.size(); ++i)
    if (i >= found.size() || !found[i])
      throw Error(ErrorKind::InvalidArgument,
                  pair_name(pairs[i][0], pairs[i][1]) + " (pair " + std::to_string(i + 1) +
                      ") is not an edge of the mesh (vertex ids are 0-based, in the mesh file's order)",
                  {pairs[i][0], pairs[i][1]});
}

}  // namespace igm
