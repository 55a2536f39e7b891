#pragma once
// Quantization of a surface layout (layout/surface_layout.h): an integer length >= 1 for every
// arc such that the opposite sides of every patch have equal sums (the patch becomes an a x b
// rectangle of unit quads), close to the arc's 3D length divided by the target edge length H. An
// integer program solved by COIN-OR CBC (Lyon, Campen & Kobbelt 2021 "Quad layouts via constrained
// T-mesh quantization"; QuadWild, Pietroni et al. 2021, sizes sides alike).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "igm/layout/surface_layout.h"

namespace igm {

/// The weight w_a of an arc's deviation |x_a - t_a| in the objective (measured in docs/layouts.md:
/// on arcs that the patches force to one length, as the canonical layouts' chords, the absolute
/// deviation keeps that length at their median and the relative one drags it toward the shortest;
/// on random T-meshes the two are within 15 %).
enum class QuantizeWeight {
  Absolute,  // 1: the deviation in edges (the default)
  Relative,  // 1 / max(t_a, 1): the relative deviation
};

struct QuantizeOptions {
  /// Exactly one is used, in this order (as SizingOptions): resolution N > 0 gives every arc the
  /// target N (so a layout without T-junctions, whose opposite sides are single arcs, gets exactly
  /// N on every arc: the paper's N quads per layout edge; with T-junctions the integer program
  /// keeps every arc as close to N as the patches allow); edge_length H > 0 the target
  /// (3D length) / H; quads Q > 0: H = sqrt(area / Q) first, then up to `quad_corrections` more
  /// H by the secant on log total against log H (the first step as if the total went as H^-2),
  /// each judged by the LP relaxation's total (Clp only), stopping within 0.2 % of Q; the H whose
  /// total was nearest to Q (the first on ties) gets the one integer solve.
  int resolution = 0;
  double edge_length = 0;
  std::int64_t quads = 0;
  int quad_corrections = 6;
  /// Per arc: its least length (empty: minimum_arc_lengths(layout)); every entry >= 1. The side
  /// sums that minimum_arc_lengths' patch rules ask for hold in either case.
  std::vector<int> minimum;
  /// 3D lengths and the area are computed on the positions times this (mesh/scale.h); H is in
  /// these units too.
  double length_scale = 1;
  /// CBC's branch-and-bound node bound (per solve; one thread, no time limit, so the result does
  /// not depend on the machine or its load).
  int max_nodes = 2000;
  QuantizeWeight weight = QuantizeWeight::Absolute;
};

enum class QuantizeStatus {
  Optimal,     // CBC proved the solution optimal
  Feasible,    // the node bound stopped the search: a valid solution, maybe not the best
  Infeasible,  // no lengths >= the minima satisfy the patches (proved by CBC)
  NoSolution,  // the node bound stopped the search before any solution was found
};

/// "optimal", "feasible", "infeasible", "no_solution".
const char* to_string(QuantizeStatus status);

struct QuantizeStats {
  int arcs = 0, patches = 0;
  int rows = 0;                 // equality rows of the integer program (after dropping empty ones)
  int solves = 0;               // integer programs solved (1)
  int relaxations = 0;          // LP relaxations solved alone to choose H (quads Q > 0)
  std::int64_t nodes = 0;       // branch-and-bound nodes, over all solves
  double deviation = 0;         // the kept solution's objective: sum_a w_a |x_a - t_a|
  double seconds = 0;
};

struct Quantization {
  QuantizeStatus status = QuantizeStatus::NoSolution;
  std::string reason;                          // why there is no solution ("" with one)
  std::vector<int> arc_length;                 // per arc (empty without a solution)
  std::vector<std::array<int, 2>> patch_size;  // per patch: (a, b) = sums of sides 0 and 1
  std::int64_t quads = 0;                      // sum of a b
  double edge_length = 0;                      // the H of the kept solution (0 with a resolution)
  QuantizeStats stats;

  bool ok() const { return status == QuantizeStatus::Optimal || status == QuantizeStatus::Feasible; }
};

/// The least arc lengths for which the quad mesh of the layout's IGM has no loop edge, no two edges
/// between the same two vertices and no quad with a repeated vertex, as far as single arcs decide
/// it (the conditions of sizing.h's minimum_chord_counts on the canonical layouts, which these
/// reproduce there): 3 for an arc from a node to itself (1 would be a loop, 2 a double edge);
/// 2 for two arcs joining the same two nodes (1 each would be a double edge); for a patch whose
/// opposite corners are one surface vertex, or whose opposite sides share an arc, its sides'
/// sums must be >= 2, resp. >= 3 across (a grid line across it would close on one vertex) and the
/// lone arc of such a side gets that minimum; 1 otherwise. Sums over several arcs are at least
/// their count already. The certifier's check 5 judges the final quad mesh in any case.
/// Pre: check_surface_layout(layout) == "". Cost O(arcs log arcs + patches).
std::vector<int> minimum_arc_lengths(const SurfaceLayout& layout);

/// Solves: minimize sum_a w_a |x_a - t_a| over integers x_a >= minimum_a (<= 2^20) with, for every
/// patch, sum(side 0) = sum(side 2) and sum(side 1) = sum(side 3) (an arc on two opposite sides of
/// one patch cancels) and the side sums minimum_arc_lengths names (>= 2 or >= 3 across a patch
/// whose opposite corners are one vertex or whose opposite sides share an arc); t_a = (3D length
/// of arc a) / H (or N), w_a by options.weight. CBC (CbcMain with presolve, cuts and the
/// heuristics but the feasibility pump; one thread; at most options.max_nodes nodes per solve); the solution is rounded
/// and checked in integers. Never throws for an infeasible layout or a bound hit: the status says
/// so, with the reason, so that the caller can fall back. Throws igm::Error(InvalidArgument) for a
/// layout check_surface_layout rejects, no or a bad size option, bad minima or options.
/// Cost: O(F + arcs) set-up, then the solves (measured in bench/README.md: layouts_bench).
Quantization quantize_layout(const SurfaceLayout& layout, const QuantizeOptions& options);

}  // namespace igm
