#pragma once
// The whole pipeline on a validated mesh: topology -> embed -> arrange -> igm -> extract ->
// certify (design.md). Returns the IGM, the quad mesh and the certifier's reports on both.
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "certify/certify.h"
#include "igm/embed/orbifold_tutte.h"
#include "igm/embed/tutte.h"
#include "igm/mesh/validate.h"
#include "igm/output/igm_mesh.h"
#include "igm/output/schema_svg.h"
#include "igm/topology/cut_to_canonical_disk.h"

namespace igm {

/// Peak resident memory per IGM triangle of the genus >= 1 pipeline after its arrangement, as
/// measured by `igm run` (couplingdown with the normal form: 22k triangles, 51 MB; cheese: 423k
/// triangles, 875 MB; a generated 1M-face torus: 1.0M triangles, 2065 MB): the basis of
/// PipelineOptions::memory_limit_bytes.
inline constexpr double kBytesPerIgmTriangle = 2048;

/// Reported after each stage through PipelineOptions::progress (the library never prints).
struct StageEvent {
  std::string stage;   // "topology", "embed", "arrange", "igm", "extract", "certify"
  double seconds = 0;  // wall time of the stage
  std::string detail;  // one line of numbers for humans
};

struct PipelineOptions {
  /// N: the quad mesh has N x N quads per layout quad (N >= 1). For N < 3 the quad mesh has
  /// loops and multi-edges at the root (inherent to the layout, paper §6.2: every polygon corner
  /// is the root); the certifier identifies edges by their end points and rejects such a mesh,
  /// so only N >= 3 gives a certified quad mesh. Genus 0: 2 N^2 quads, certified for every N >= 1.
  int resolution = 4;
  int root = -1;       // root vertex of the loops (-1: deterministic default); genus 0 has no root (ignored)
  /// Bring the gluing word to the normal form a1 b1 a1^-1 b1^-1 ... (topology step 3).
  /// Validity does not need it: every polygon side is a whole edge of one layout quad mapped onto
  /// a unit-square edge, so any pairing of sides glues by R^k x + t with integer t (the certifier
  /// checks it). Off by default: its loops are longer and grow the mesh more (couplingdown g9:
  /// 2.37k instead of 2.19k refined vertices; a 1M-face g20 mesh 0.54M instead of 0.51M vertices,
  /// in ~9 s instead of ~3 s; cheese g133 ~150k instead of 27k, by the crosses construction).
  bool normal_form = false;
  /// With normal_form: CutOptions::restarts, the topology stage run again on this many copies of
  /// the mesh with shuffled vertex ids where it added more than 2 %, the fewest vertices kept
  /// (couplingdown with 15: 87 vertices added instead of 129, in 15x the time). 0: none; -1:
  /// automatic, clamp(5e6 / (F g^2), 0, 15) (`igm run --restarts auto`).
  int restarts = 0;
  /// Genus 0 only: the four cone vertices (input vertex ids) in path order A, B, C, D; empty: the
  /// deterministic default (topology/sphere_cut.h). Bad lists give igm::Error(InvalidArgument).
  std::vector<int> cones;
  /// Refinement bounds of the embedding (Tutte for g >= 1, orbifold Tutte for g = 0).
  TutteOptions tutte;
  std::size_t max_witnesses = 20;
  /// Genus >= 1: the memory the stages after the arrangement may need, in bytes (0: this machine's
  /// physical memory; no check where that is unknown). They need about kBytesPerIgmTriangle per
  /// IGM triangle (exact locations, UVs, charts, quads, the certifier's copy); an arrangement
  /// that would need more is igm::Error(Unsupported), raised by the overlay itself as soon as its
  /// lower bound passes the limit (OverlayOptions::max_triangles), instead of running out of
  /// memory minutes later (cheese with the normal form: 36.7M triangles, ~70 GB).
  std::uint64_t memory_limit_bytes = 0;
  std::function<void(const StageEvent&)> progress;  // optional
};

struct PipelineStats {
  int genus = 0;
  int input_vertices = 0, input_faces = 0;
  int refined_vertices = 0, refined_faces = 0;  // after the topology stage's splits
  int output_vertices = 0, output_triangles = 0;  // the IGM triangle mesh
  int layout_quads = 0, quads = 0;  // genus 0: the 2 cells of the domain [0,2] x [0,1]
  std::size_t max_uv_bits = 0;  // largest bit_size of an exact UV coordinate
  CutStats cut;
  TutteStats tutte;
  // genus 0 (orbifold Tutte): the cones (vertex ids of the input and of the IGM), the cut, the embedding
  std::array<int, 4> cones{-1, -1, -1, -1};
  SphereCutStats sphere_cut;
  OrbifoldTutteStats orbifold;
  std::vector<StageEvent> stages;
};

struct PipelineResult {
  IgmMesh igm;                       // refinement of the input: exact per-corner UV, exact vertex locations
  QuadMesh quads;                    // N x N quads per layout quad
  certify::Report igm_report;        // certifier checks 1-4 on `igm`
  certify::Report quad_report;       // certifier check 5 on `quads` (expected genus = input genus)
  SchemaDrawing schema;              // the polygonal schema, for the SVG picture
  PipelineStats stats;
  bool certified() const { return igm_report.valid() && quad_report.valid(); }
};

/// Computes a certified IGM of a closed orientable mesh (paper §4–5). Genus g >= 1: loops and
/// cut (topology), rational convex 4g-gon and exact Tutte map (embed), exact overlay of the quad
/// template (arrange), piecewise-affine map of each layout quad to the unit square (igm), quad
/// extraction at the requested resolution (extract). Genus 0: cut along a path through four
/// cones (topology/sphere_cut.h), orbifold Tutte map onto the pillowcase [0,2] x [0,1] with four
/// pi-cones at integer points (embed/orbifold_tutte.h; the map is the IGM), the 2 N^2 grid cells of
/// the domain as quads (extract/orbifold_quads.h; valid for every N >= 1). Then the independent
/// certifier on both outputs. Throws igm::Error(InvalidArgument) for resolution < 1, a bad root or
/// a bad cone list. Cost: dominated by the embedding and the overlay, about O(n log n) plus the
/// exact arithmetic.
PipelineResult compute_igm(const ValidMesh& mesh, const PipelineOptions& options = {});

}  // namespace igm
