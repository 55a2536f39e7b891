#pragma once
// Sizing a quad layout: an integer length for every chord (the class of layout edges that opposite
// sides of a quad and the gluing of paired sides force to be equal), so that each layout quad
// becomes an a x b rectangle of unit quads (docs/layouts.md).
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "igm/layout/quad_layout.h"

namespace igm {

struct SizingOptions {
  /// Exactly one of these is used, in this order: resolution > 0 gives every chord that count (the
  /// paper's N quads per layout edge); edge_length > 0 is the target 3D edge length H; quads > 0 a
  /// target quad count, for which H is searched.
  int resolution = 0;
  double edge_length = 0;
  std::int64_t quads = 0;
};

struct Sizing {
  std::vector<int> chord_count;                // per chord, >= chord_minimum
  std::vector<int> chord_minimum;              // per chord: the least count giving a simple quad mesh
  std::vector<int> edge_count;                 // per surface edge: its chord's count
  std::vector<std::array<int, 2>> quad_size;   // per layout quad: (a, b) = counts of its sides 0 and 1
  std::int64_t quads = 0;                      // sum of a b
  double edge_length = 0;                      // the H used (0 with resolution)
};

/// The least count of every chord for which the quad mesh has no loop, no two edges between the
/// same two vertices and no quad with a repeated vertex: 3 for a chord with a layout edge from a
/// layout vertex to itself (subdivided in two it would still give two edges between the same two
/// vertices), 2 for a chord with an edge parallel to another one (both ends the same layout
/// vertices) or with a side of a quad whose opposite corners are one layout vertex, 1 otherwise.
/// Cost O(E log E).
std::vector<int> minimum_chord_counts(const QuadLayout& layout);

/// The edge length H whose quad count `count(H)` (non-increasing in H) is nearest to `target`:
/// bisection on log H over [lo, hi] (0 < lo < hi, finite; at most 200 steps), keeping the nearer of
/// the two ends of the last bracket (the larger H on ties). Cost: the steps' calls of `count`.
double edge_length_for_quads(const std::function<std::int64_t(double)>& count, double lo, double hi,
                             std::int64_t target);

/// Counts every chord. With an edge length H: count = max(minimum, round(mean / H)), mean the mean
/// 3D length of the chord's surface edges (`surface_edge_length`, one per surface edge; a glued
/// pair counts once). With a quad count Q: H is found by bisection on log H (at most 200 steps;
/// the total is non-increasing in H) and the H whose total is nearest to Q is kept (the larger H
/// on ties). With a resolution N: N for every chord. Throws igm::Error(InvalidArgument) for no
/// positive option, non-finite lengths or sizes, a resolution past 2^20 or below a chord's minimum
/// (naming the chord). Counts are capped at 2^20. Cost O(E + steps x quads).
Sizing size_layout(const QuadLayout& layout, const std::vector<double>& surface_edge_length, const SizingOptions& options);

}  // namespace igm
