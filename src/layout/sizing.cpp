#include "igm/layout/sizing.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "igm/core/det_math.h"
#include "igm/core/error.h"

namespace igm {

namespace {

constexpr int kMaxCount = 1 << 20;

std::int64_t total_quads(const QuadLayout& L, const std::vector<int>& chord_count) {
  std::int64_t n = 0;
  for (std::size_t q = 0; q < L.quads.size(); ++q)
    n += static_cast<std::int64_t>(chord_count[L.chord[L.surface_edge[L.quad_edge[q][0]]]]) *
         chord_count[L.chord[L.surface_edge[L.quad_edge[q][1]]]];
  return n;
}

// Counts for edge length H (H > 0, finite).
std::vector<int> counts_for(const std::vector<double>& mean, const std::vector<int>& minimum, double H) {
  std::vector<int> c(mean.size());
  for (std::size_t k = 0; k < mean.size(); ++k) {
    const double x = std::nearbyint(mean[k] / H);
    c[k] = std::max(minimum[k], static_cast<int>(std::min<double>(kMaxCount, std::max(0.0, x))));
  }
  return c;
}

}  // namespace

double edge_length_for_quads(const std::function<std::int64_t(double)>& count, double lo, double hi,
                             std::int64_t target) {
  if (!(lo > 0) || !(hi > lo) || !std::isfinite(hi))
    throw Error(ErrorKind::InvalidArgument, "edge_length_for_quads: needs 0 < lo < hi, finite");
  // det_log / det_exp: libm's differ in the last bit between machines (core/det_math.h), and
  // the edge length decides the quad counts.
  double a = det_log(lo), b = det_log(hi);
  for (int step = 0; step < 200 && b - a > 1e-12; ++step) {
    const double mid = 0.5 * (a + b);
    if (count(det_exp(mid)) > target) a = mid;
    else b = mid;
  }
  // count(exp(a)) > target >= count(exp(b)), or an end of [lo, hi]: keep the nearer.
  const std::int64_t na = count(det_exp(a)), nb = count(det_exp(b));
  return std::llabs(na - target) < std::llabs(nb - target) ? det_exp(a) : det_exp(b);
}

std::vector<int> minimum_chord_counts(const QuadLayout& L) {
  std::vector<int> minimum(L.num_chords, 1);
  std::map<std::pair<int, int>, std::vector<int>> by_ends;  // layout vertex pair -> surface edges
  std::vector<char> seen(L.num_surface_edges, 0);
  for (std::size_t e = 0; e < L.edges.size(); ++e) {
    const int s = L.surface_edge[e];
    if (seen[s]) continue;
    seen[s] = 1;
    const int a = L.layout_vertex[L.edges[e].a], b = L.layout_vertex[L.edges[e].b];
    if (a == b) minimum[L.chord[s]] = 3;
    by_ends[{std::min(a, b), std::max(a, b)}].push_back(s);
  }
  for (std::size_t q = 0; q < L.quads.size(); ++q) {
    const auto& Q = L.quads[q];
    if (L.layout_vertex[Q[0]] == L.layout_vertex[Q[2]] || L.layout_vertex[Q[1]] == L.layout_vertex[Q[3]])
      for (int k = 0; k < 2; ++k) {
        int& m = minimum[L.chord[L.surface_edge[L.quad_edge[q][k]]]];
        m = std::max(m, 2);
      }
  }
  // Parallel edges (one pair of layout vertices): at most one of them may stay a single quad edge.
  // Two in one chord force it to 2; the others are raised, then lowered back to 1 chord by chord
  // (those sizing the most layout quads first) while no pair has two single edges left.
  std::vector<std::vector<int>> groups;  // per pair with several edges: its edges' chords
  std::vector<char> parallel(L.num_chords, 0);
  for (const auto& [ends, list] : by_ends) {
    if (list.size() < 2) continue;
    std::vector<int> chords;
    for (int s : list) chords.push_back(L.chord[s]);
    std::sort(chords.begin(), chords.end());
    for (std::size_t i = 0; i + 1 < chords.size(); ++i)
      if (chords[i] == chords[i + 1]) minimum[chords[i]] = std::max(minimum[chords[i]], 2);
    for (int c : chords) parallel[c] = 1;
    groups.push_back(std::move(chords));
  }
  std::vector<int> quads_sized(L.num_chords, 0), candidates;
  for (std::size_t q = 0; q < L.quads.size(); ++q)
    for (int k = 0; k < 2; ++k) ++quads_sized[L.chord[L.surface_edge[L.quad_edge[q][k]]]];
  for (int c = 0; c < L.num_chords; ++c)
    if (parallel[c] && minimum[c] == 1) minimum[c] = 2, candidates.push_back(c);
  std::stable_sort(candidates.begin(), candidates.end(), [&](int x, int y) { return quads_sized[x] > quads_sized[y]; });
  std::vector<std::vector<int>> chord_groups(L.num_chords);
  for (std::size_t g = 0; g < groups.size(); ++g)
    for (int c : groups[g]) chord_groups[c].push_back(static_cast<int>(g));
  for (int c : candidates) {  // bound: the chords; each group scanned per chord in it
    bool free = true;
    for (int g : chord_groups[c])
      for (int d : groups[g]) free = free && (d == c || minimum[d] > 1);
    if (free) minimum[c] = 1;
  }
  return minimum;
}

std::array<int, 2> pillowcase_grid_floor(std::array<int, 2> n) {
  if ((n[0] == 1) != (n[1] == 1)) n = {std::max(n[0], 2), std::max(n[1], 2)};
  return n;
}

Sizing size_layout(const QuadLayout& L, const std::vector<double>& length, const SizingOptions& o) {
  if (static_cast<int>(length.size()) != L.num_surface_edges)
    throw Error(ErrorKind::InvalidArgument, "size_layout: one length per surface edge is needed");
  Sizing s;
  s.chord_minimum = minimum_chord_counts(L);
  if (o.resolution > 0) {
    if (o.resolution > kMaxCount) throw Error(ErrorKind::InvalidArgument, "size_layout: resolution past 2^20");
    s.chord_count.assign(L.num_chords, o.resolution);
    for (int c = 0; c < L.num_chords; ++c)
      if (o.resolution < s.chord_minimum[c]) s.chord_count[c] = s.chord_minimum[c], ++s.raised_chords;
  } else {
    std::vector<double> mean(L.num_chords, 0.0);
    std::vector<int> members(L.num_chords, 0);
    for (int e = 0; e < L.num_surface_edges; ++e) {
      if (!std::isfinite(length[e]) || length[e] < 0)
        throw Error(ErrorKind::InvalidArgument, "size_layout: surface edge " + std::to_string(e) + " has length " +
                                                    std::to_string(length[e]),
                    {e});
      mean[L.chord[e]] += length[e];
      ++members[L.chord[e]];
    }
    double lo = HUGE_VAL, hi = 0;
    for (int c = 0; c < L.num_chords; ++c) {
      mean[c] /= std::max(1, members[c]);
      if (mean[c] > 0) lo = std::min(lo, mean[c]), hi = std::max(hi, mean[c]);
    }
    if (o.edge_length > 0) {
      if (!std::isfinite(o.edge_length)) throw Error(ErrorKind::InvalidArgument, "size_layout: the edge length is not finite");
      s.edge_length = o.edge_length;
    } else if (o.quads > 0) {
      if (hi <= 0) {
        s.edge_length = 1;  // no length: every chord at its minimum, whatever H
      } else {
        // Below lo / 2^21 every count is at its cap or past any target; above 2 hi at its minimum.
        s.edge_length = edge_length_for_quads(
            [&](double H) { return total_quads(L, counts_for(mean, s.chord_minimum, H)); }, std::ldexp(lo, -21), 2 * hi,
            o.quads);
      }
    } else {
      throw Error(ErrorKind::InvalidArgument, "size_layout: needs a resolution, an edge length or a quad count");
    }
    s.chord_count = counts_for(mean, s.chord_minimum, s.edge_length);
    const std::vector<int> ones(L.num_chords, 1);
    const std::vector<int> asked = counts_for(mean, ones, s.edge_length);
    for (int c = 0; c < L.num_chords; ++c) s.raised_chords += s.chord_minimum[c] > asked[c];
  }
  s.edge_count.resize(L.num_surface_edges);
  for (int e = 0; e < L.num_surface_edges; ++e) s.edge_count[e] = s.chord_count[L.chord[e]];
  s.quad_size.resize(L.quads.size());
  for (std::size_t q = 0; q < L.quads.size(); ++q)
    s.quad_size[q] = {s.edge_count[L.surface_edge[L.quad_edge[q][0]]], s.edge_count[L.surface_edge[L.quad_edge[q][1]]]};
  s.quads = total_quads(L, s.chord_count);
  s.floor_quads = total_quads(L, s.chord_minimum);
  return s;
}

}  // namespace igm
