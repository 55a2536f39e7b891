#include "igm/extract/quad_defects.h"

#include <algorithm>
#include <map>
#include <set>
#include <utility>

#include "igm/core/union_find.h"

namespace igm {

namespace {

constexpr std::size_t kNamed = 3;   // defects named in the description
constexpr std::size_t kListed = 8;  // ids listed per kind of element

std::string id_list(const std::vector<int>& ids) {
  std::string s;
  for (std::size_t i = 0; i < ids.size() && i < kListed; ++i) {
    if (i) s += ' ';
    s += std::to_string(ids[i]);
  }
  if (ids.size() > kListed) s += " ...";
  return s;
}

}  // namespace

const char* to_string(QuadDefectKind kind) {
  switch (kind) {
    case QuadDefectKind::Loop: return "loop";
    case QuadDefectKind::MultiEdge: return "multi_edge";
    case QuadDefectKind::RepeatedVertex: return "repeated_vertex";
  }
  return "?";
}

std::vector<QuadDefect> find_quad_defects(const IsolineQuads& q, std::size_t max_defects) {
  const int nq = static_cast<int>(q.quads.size());
  // Per edge: its ends and its quads; components by shared vertices.
  std::vector<std::pair<int, int>> ends(static_cast<std::size_t>(q.num_edges), {-1, -1});
  std::vector<std::vector<int>> edge_quads(static_cast<std::size_t>(q.num_edges));
  UnionFind joined(q.vertices.size());
  for (int f = 0; f < nq; ++f)
    for (int k = 0; k < 4; ++k) {
      const int e = q.quad_edges[f][k], a = q.quads[f][k], b = q.quads[f][(k + 1) % 4];
      ends[e] = {std::min(a, b), std::max(a, b)};
      if (edge_quads[e].empty() || edge_quads[e].back() != f) edge_quads[e].push_back(f);
      joined.unite(a, b);
    }
  std::map<int, int> component_of_root;  // numbered by their first quad
  std::vector<int> component(q.vertices.size(), 0);
  for (int f = 0; f < nq; ++f) component_of_root.emplace(joined.find(q.quads[f][0]), static_cast<int>(component_of_root.size()));
  for (std::size_t v = 0; v < q.vertices.size(); ++v) {
    const auto it = component_of_root.find(joined.find(static_cast<int>(v)));
    component[v] = it == component_of_root.end() ? 0 : it->second;
  }
  std::vector<std::pair<int, QuadDefect>> found;  // (lowest quad, defect)
  auto finish = [&](QuadDefect d) {
    std::sort(d.quads.begin(), d.quads.end());
    d.quads.erase(std::unique(d.quads.begin(), d.quads.end()), d.quads.end());
    std::set<int> cones;
    for (int f : d.quads)
      for (int v : q.quads[f])
        if (q.vertices[v].valence != (q.vertices[v].boundary ? 3 : 4)) cones.insert(v);
    d.cones.assign(cones.begin(), cones.end());
    d.component = component[d.vertices.front()];
    const int first = d.quads.empty() ? nq : d.quads.front();
    found.push_back({first, std::move(d)});
  };
  std::map<std::pair<int, int>, std::vector<int>> by_ends;  // vertex pair -> its edges
  for (int e = 0; e < q.num_edges; ++e) {
    if (ends[e].first < 0) continue;
    if (ends[e].first == ends[e].second) {
      QuadDefect d;
      d.kind = QuadDefectKind::Loop;
      d.vertices = {ends[e].first};
      d.edges = {e};
      d.quads = edge_quads[e];
      finish(std::move(d));
    } else {
      by_ends[ends[e]].push_back(e);
    }
  }
  std::vector<char> in_defect(static_cast<std::size_t>(nq), 0);
  for (const auto& [pair, edges] : by_ends) {
    if (edges.size() < 2) continue;
    QuadDefect d;
    d.kind = QuadDefectKind::MultiEdge;
    d.vertices = {pair.first, pair.second};
    d.edges = edges;
    for (int e : edges) d.quads.insert(d.quads.end(), edge_quads[e].begin(), edge_quads[e].end());
    finish(std::move(d));
  }
  for (const auto& [first, d] : found)
    for (int f : d.quads) in_defect[f] = 1;
  for (int f = 0; f < nq; ++f) {
    if (in_defect[f]) continue;
    const auto& Q = q.quads[f];
    for (int k = 0; k < 4; ++k)
      if (Q[k] == Q[(k + 2) % 4] || Q[k] == Q[(k + 1) % 4]) {
        QuadDefect d;
        d.kind = QuadDefectKind::RepeatedVertex;
        d.vertices = {Q[k]};
        d.quads = {f};
        finish(std::move(d));
        break;
      }
  }
  std::stable_sort(found.begin(), found.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<QuadDefect> out;
  for (auto& [first, d] : found) {
    if (max_defects > 0 && out.size() >= max_defects) break;
    out.push_back(std::move(d));
  }
  return out;
}

std::string describe_quad_defects(const IsolineQuads& q, const std::vector<QuadDefect>& defects) {
  if (defects.empty()) return "";
  bool several = false;
  for (const QuadDefect& d : defects) several = several || d.component != defects.front().component;
  std::string s = "the integer isolines are no manifold quad mesh (the grid is too coarse for its cones): ";
  for (std::size_t i = 0; i < defects.size() && i < kNamed; ++i) {
    const QuadDefect& d = defects[i];
    if (i) s += "; ";
    if (several || d.component > 0) s += "component " + std::to_string(d.component) + ": ";
    switch (d.kind) {
      case QuadDefectKind::Loop:
        s += "edge " + std::to_string(d.edges[0]) + " is a loop at vertex " + std::to_string(d.vertices[0]);
        break;
      case QuadDefectKind::MultiEdge:
        s += std::to_string(d.edges.size()) + " edges (" + id_list(d.edges) + ") join vertices " +
             std::to_string(d.vertices[0]) + " and " + std::to_string(d.vertices[1]);
        break;
      case QuadDefectKind::RepeatedVertex:
        s += "quad " + std::to_string(d.quads[0]) + " has vertex " + std::to_string(d.vertices[0]) + " twice";
        break;
    }
    s += ", in quads " + id_list(d.quads);
    if (d.cones.empty()) {
      s += " (no cone among them)";
    } else {
      s += ", which share the cone" + std::string(d.cones.size() == 1 ? " " : "s ");
      for (std::size_t c = 0; c < d.cones.size() && c < kListed; ++c) {
        const IsolineQuadVertex& v = q.vertices[d.cones[c]];
        if (c) s += ", ";
        s += std::to_string(d.cones[c]) + " (valence " + std::to_string(v.valence) + ")";
      }
      if (d.cones.size() > kListed) s += ", ...";
    }
  }
  if (defects.size() > kNamed) s += "; " + std::to_string(defects.size() - kNamed) + " more";
  s += "; more quads separate them";
  return s;
}

}  // namespace igm
