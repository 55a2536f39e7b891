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
  std::vector<int> chord_minimum;              // per chord: the floor (minimum_chord_counts)
  std::vector<int> edge_count;                 // per surface edge: its chord's count
  std::vector<std::array<int, 2>> quad_size;   // per layout quad: (a, b) = counts of its sides 0 and 1
  std::int64_t quads = 0;                      // sum of a b
  double edge_length = 0;                      // the H used (0 with resolution)
  std::int64_t floor_quads = 0;                // sum a b at the floor: the least manifold grid
  /// Chords whose floor (> 1) is above what the size option alone gives them (the resolution,
  /// or round(mean / H)): the floor raised them.
  int raised_chords = 0;
};

/// The floor of the sizing: the least count of every chord for which the quad mesh is manifold
/// (no loop, no two edges between the same two vertices, no quad with a repeated vertex; the
/// certifier's quad check): 3 for a chord with a layout edge from a layout vertex to itself (in two
/// pieces it would still give two edges between the same two vertices); 2 for a chord with a side
/// of a quad whose opposite corners are one layout vertex, or with two parallel edges (both ends
/// the same layout vertices); of parallel edges in different chords all but one must be
/// subdivided: their chords get 2, then, those sizing the most layout quads first, go back to 1
/// while no two parallel edges are single quad edges (the kite's spokes); 1 otherwise. At these
/// counts the quad count is the least of any manifold grid of the layout (tested on every layout
/// of genus 1-4, closed and open, against all counts 1..3: tests/layout/layout_grid_test.cpp); the
/// totals are in docs/layouts.md ("The floor"). Cost O(E log E).
std::vector<int> minimum_chord_counts(const QuadLayout& layout);

/// The floor of the genus-0 grid (the pillowcase, extract/orbifold_quads.h: 2 nx ny quads): `n`
/// if it is (1, 1) (two quads on the four cones) or both counts are >= 2; otherwise the count 1 is
/// raised to 2 (a single row or column around the pillowcase would join two vertices by two
/// edges: nx = 2, ny = 1 is a pillow of 4 quads on 6 vertices with a double edge). Monotone in
/// each count. O(1).
std::array<int, 2> pillowcase_grid_floor(std::array<int, 2> n);

/// The edge length H whose quad count `count(H)` (non-increasing in H) is nearest to `target`:
/// bisection on log H over [lo, hi] (0 < lo < hi, finite; at most 200 steps), keeping the nearer of
/// the two ends of the last bracket (the larger H on ties). Cost: the steps' calls of `count`.
double edge_length_for_quads(const std::function<std::int64_t(double)>& count, double lo, double hi,
                             std::int64_t target);

/// Counts every chord. With an edge length H: count = max(minimum, round(mean / H)), mean the mean
/// 3D length of the chord's surface edges (`surface_edge_length`, one per surface edge; a glued
/// pair counts once). With a quad count Q: H is found by bisection on log H (at most 200 steps;
/// the total is non-increasing in H) and the H whose total is nearest to Q is kept (the larger H
/// on ties); below floor_quads, the floor. With a resolution N: max(minimum, N) for every chord.
/// Whatever the option, every chord gets at least its floor (minimum_chord_counts; raised_chords
/// says where that raised one). Throws igm::Error(InvalidArgument) for no positive option,
/// non-finite lengths or sizes or a resolution past 2^20. Counts are capped at 2^20. Cost
/// O(E + steps x quads).
Sizing size_layout(const QuadLayout& layout, const std::vector<double>& surface_edge_length, const SizingOptions& options);

}  // namespace igm
