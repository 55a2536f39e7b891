#pragma once
// Smoothing of a certified IGM without ever leaving the set of valid IGMs: the UV of every
// non-cone vertex moves (in its reference chart, seamless.h), every corner follows by its fixed
// rigid map, cones stay at their integer points. Transitions are fixed by construction; each
// accepted iterate is checked exactly to have every triangle positive and every angle unchanged
// (dyadic.h, check_map), so each is a valid IGM. The pipeline's map is only an initialization
// (paper §7); this lowers its distortion. On a surface with boundary (seamless.h) boundary
// corners stay fixed like cones and straight boundary vertices slide along their isolines (one
// unknown each), so every boundary edge stays on its isoline; several components are smoothed
// together, each on its own.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "certify/certify.h"
#include "igm/output/igm_mesh.h"
#include "igm/smooth/dyadic.h"

namespace igm {

/// Reported after each accepted iteration (SmoothOptions::progress).
struct SmoothProgress {
  int iteration = 0;   // 1, 2, ...
  double energy = 0;   // after the iteration
  double step = 0;     // the accepted step length along the Newton direction
  double seconds = 0;  // since the start of smooth_igm
};

/// Every accepted iterate (SmoothOptions::on_iterate), iteration 0 being the starting map.
struct SmoothIterate {
  int iteration = 0;
  double energy = 0;
  const std::vector<std::array<Vec2d, 3>>* corner_uv = nullptr;  // three per face, exact doubles
};

struct SmoothOptions {
  int max_iterations = 100;  // Newton iterations (>= 0)
  /// Stop (SmallDecrease) after an iteration that lowered the energy by less than this fraction
  /// of it (0: never).
  double min_relative_decrease = 0;
  /// Stop after the iteration that ends past this many seconds since smooth_igm began (wall
  /// time, the set-up included); 0: no limit. The only rule that makes the result depend on the
  /// machine's speed and load: off unless asked for.
  double time_budget_seconds = 0;
  /// Stop when the Newton decrement -g.d / 2 (the model's predicted decrease) is at most this
  /// times the energy.
  double tolerance = 1e-6;
  /// Reference regularization (see SmoothStats::enlarged_references, fattened_references), in
  /// units of sqrt(mean 3D triangle area) and of the reference's larger singular value.
  double min_reference_size = 1e-6;
  double min_reference_aspect = 1e-3;
  /// The first step is this fraction (< 1) of the step at which the first triangle degenerates.
  double step_fraction = 0.8;
  /// Stop (Stalled) after stall_iterations consecutive iterations whose accepted step along the
  /// Newton direction is below stall_step: the map is pressed against its barrier and each
  /// iteration buys almost nothing (0: never). Steps are 1 near convergence, so this does not cut
  /// a converging run short.
  double stall_step = 0;
  int stall_iterations = 2;
  /// Run the independent certifier (certify_igm) on the returned map, with this many threads (0:
  /// all cores; certify::Options::threads).
  bool certify = true;
  int threads = 0;
  /// Interior edges (vertex pairs of the IGM) held on their integer isolines (issue 45: feature
  /// edges), each already on one: their vertices slide along them (seamless.h,
  /// hold_isoline_edges); InvalidArgument if an edge is missing or off every integer isoline.
  std::vector<std::pair<int, int>> isoline_edges;
  std::function<void(const SmoothProgress&)> progress;   // optional
  std::function<void(const SmoothIterate&)> on_iterate;  // optional, for tests
};

enum class SmoothStop {
  Converged,        // the Newton decrement fell below the tolerance
  IterationBudget,  // max_iterations reached
  SmallDecrease,    // the last iteration lowered the energy by less than min_relative_decrease
  TimeBudget,       // time_budget_seconds passed
  NoDescent,        // the (regularized) Newton system gave no descent direction
  LineSearch,       // no step along the direction lowered the energy and passed the exact checks
  Stalled,          // stall_iterations steps in a row below stall_step (SmoothOptions)
  NothingToMove,    // every vertex is a cone or a boundary corner
  NotStarted,       // the input does not round onto a double grid (see SmoothStats::dyadic), or
                    // its energy is not finite in doubles
};
const char* to_string(SmoothStop stop);

enum class SmoothReturned {
  Smoothed,     // the last accepted iterate (after at least one iteration)
  InputOnGrid,  // no iteration accepted: the input rounded onto the grid
  InputExact,   // the input could not be placed on a double grid: its exact UVs, unchanged
};
const char* to_string(SmoothReturned returned);

struct SmoothStats {
  int iterations = 0;
  std::vector<double> energy;  // energy[0] of the starting map, energy[i] after iteration i
  double seconds = 0;          // all of smooth_igm, of which:
  double setup_seconds = 0;    //   the structure, the grid, the references, the Hessian's pattern
                               //   and its analysis (before the first iteration), of which:
  double structure_seconds = 0;  //     the seamless structure and the map on its grid
  double certify_seconds = 0;  //   the independent certifier
  SmoothStop stop = SmoothStop::NotStarted;
  SmoothReturned returned = SmoothReturned::InputExact;
  std::string reason;  // a sentence on why it stopped (and what was returned)
  int free_vertices = 0;     // interior regular vertices: two unknowns each
  int sliding_vertices = 0;  // straight boundary vertices: one unknown each (along the isoline)
  int cones = 0;             // interior cones: fixed
  int boundary_corners = 0;  // boundary vertices of boundary angle != pi: fixed
  int enlarged_references = 0;  // 3D triangles below the size floor (zero area included)
  int fattened_references = 0;  // 3D triangles thinner than the aspect floor
  int factorizations = 0;       // of the Newton systems (more than iterations where one failed)
  bool supernodal = false;      // SparseCholesky's supernodal factorization (else simplicial)
  std::size_t factor_entries = 0;  // entries of the Cholesky factor
  double analyze_seconds = 0;      // the factorization's ordering and analysis (once)
  double factorize_seconds = 0;    // all numeric factorizations
  int step_halvings = 0;        // trial steps halved in all line searches
  int exact_rejections = 0;     // trial steps whose map the exact checks rejected (check_map)
  DyadicStats dyadic;           // the grid, and the exact certification of the returned map
  bool certified = false;       // the independent certifier accepted the returned map
};

struct SmoothResult {
  /// Three per face of the input, for its triangles, positions and vertex ids: every coordinate
  /// exactly a double (dyadic.stats.on_grid) unless returned == InputExact. Always a valid IGM:
  /// every triangle strictly positive by exact orient2d, every angle, transition and cone the
  /// input's, every boundary edge on the input's isoline, every boundary corner where it was.
  std::vector<std::array<Point2q, 3>> corner_uv;
  SmoothStats stats;
  /// The independent certifier on corner_uv (when options.certify), with allow_boundary when the
  /// input has boundary loops and allow_components when it has several components.
  certify::Report report;
};

/// Lowers the symmetric Dirichlet energy of the IGM: per triangle s1^2 + s2^2 + s1^-2 + s2^-2
/// of the map from the 3D triangle (scaled by sqrt(total UV area / total 3D area), regularized
/// where degenerate: src/smooth/symmetric_dirichlet.h) to its UV triangle, area weighted and
/// normalized (4 at best). The total UV area does not change when non-cone vertices move (nor
/// when a straight boundary vertex slides: the area's gradient there is normal to its isoline),
/// so the scale is fixed. Projected Newton: per-triangle Hessians made positive semi-definite
/// through the analytic eigensystem (the one eigenvalue that can be negative replaced by its
/// absolute value), a sparse Cholesky solve of the system with its diagonal raised by 1e-9 of itself
/// (more where the factorization fails; embed/sparse_cholesky.h, its analysis done once: the
/// pattern does not change), a line search
/// that starts at step_fraction of the first degeneracy (Smith & Schaefer 2015) and halves until
/// the energy decreases enough (Armijo) and the new map, rounded onto the dyadic grid (dyadic.h),
/// passes the exact checks (check_map). So every accepted iterate is a certified map in doubles,
/// the energy never increases, and the last one is returned.
/// Pre: `igm` is a valid IGM, closed or with boundary, with one component or several
/// (seamless_structure checks it and throws igm::Error naming the element otherwise), finite
/// positions (igm::Error(NonFinite) naming the vertex otherwise).
/// A trial step that would take a vertex UV beyond the grid's bound (8 times the largest input
/// coordinate, dyadic.h) is halved like one that fails the checks.
/// Bounds: max_iterations iterations, each at most 64 trial steps. Cost per iteration: O(F) for
/// the energy, gradient and Hessian, one sparse factorization (about O(V^1.5) on a surface), O(F)
/// per trial step. The faces' terms, the trial steps' energies and exact checks run in parallel
/// (igm/core/threads.h) and are summed in a fixed order: the result does not depend on the
/// threads, nor, unless time_budget_seconds is set, on the machine's speed.
SmoothResult smooth_igm(const IgmMesh& igm, const SmoothOptions& options = {});

/// smooth_igm that takes the input's exact UVs: igm.corner_uv is freed (left empty) as soon as the
/// map is on its double grid, or moved into the result when it stays exact, so that they do not
/// occupy memory during the iterations (the pipeline's use: about half of it on large meshes).
/// Post: igm.corner_uv is empty; the result as smooth_igm's.
SmoothResult smooth_igm_releasing(IgmMesh& igm, const SmoothOptions& options = {});

}  // namespace igm
