#pragma once
// The cross field of a surface and its singularities (issue 46, steps 1-2): the smoothest
// 4-direction field per face (Knoeppel, Crane, Pinkall, Schroeder 2013, "Globally optimal
// direction fields"), optionally aligned with the principal curvature directions
// (curvature.h), with boundary edges as hard constraints; its matchings across edges, the
// field valence of every vertex (exact integers; Poincare-Hopf holds by construction and is
// checked), the cones, and the close pairs of opposite cones. docs/field.md explains each step.
//
// Representation. Per face f an angle theta_f in [0, pi/2) in f's frame (face_frames.h: angle 0
// along the reference half-edge, counter-clockwise); the field's four directions in f are
// theta_f + k pi/2, k = 0..3. The field is computed as the complex number u_f = exp(4 i theta_f)
// (the paper's power representation), which does not see the choice of k.
//
// Matching. Across the interior edge of half-edge h (f = face(h), g = face(twin h)), with rho_h
// the transport angle (face_frames.h: unfold g onto f's plane across the edge), the period
// p_h = round((theta_g - theta_f - rho_h) / (pi/2)) (p_twin = -p_h): direction k of f transported
// into g is direction k - p_h of g up to the field's rotation delta_h in [-pi/4, pi/4]. The
// matching m_h = (-p_h) mod 4 in {0,1,2,3}: direction k in face(h) corresponds to direction
// k + m_h (mod 4) in face(twin h); m_twin = (-m_h) mod 4.
//
// Valence. Interior vertex v with faces f_0..f_{n-1} counter-clockwise around it, crossing from
// f_i to f_{i+1} over the half-edge h_i of f_i entering v: the index of the field at v is
// (K_v + sum_i delta_{h_i}) / 2 pi, K_v the angle defect, an exact multiple of 1/4 written in the
// integers of the frames and the periods:
//   valence(v) = 4 - 4 index = 4 + 4 (n - 1 - #{i : the reference half-edge of f_i leaves v}
//                                        + sum_i w_{h_i}) + sum_i p_{h_i}
// (w: face_frames.h transport_turns). 4 is regular; 3 / 5 are cones of index +1/4 / -1/4; 2 / 6
// of index +1/2 / -1/2. Boundary vertex v (faces f_0..f_{n-1} from its outgoing boundary
// half-edge b_out in f_0 to its incoming one b_in in f_{n-1}): k(v) is the angle between its two
// boundary edges in quarter turns of the field, (interior angle - sum_i delta_{h_i} - delta_in +
// delta_out) / (pi/2), delta_b the angle from the nearest field direction q_b to the boundary
// edge b (0 on a constrained edge):
//   k(v) = 4 (n - 1 - #{i : reference of f_i leaves v} + sum_i w_{h_i}) + sum_i p_{h_i}
//          + q(b_in) + 2 - q(b_out),  q(b) = round((a_b - theta_face(b)) / (pi/2))
// 2 is a straight boundary, 1 a convex corner (a quarter turn), 3 a concave one, 0 a cusp (an
// interior angle below 45 degrees: rare, reported). Poincare-Hopf,
//   sum over interior v of (4 - valence) + sum over boundary v of (2 - k) = 4 (V - E + F),
// holds for any field by the integer identities (docs/field.md) and is checked by
// check_poincare_hopf.
//
// Boundary constraints. A face with a boundary edge (of non-zero length) has that edge as its
// reference half-edge and theta_f = 0: one field direction along the boundary edge, exactly.
// Feature edges given in CrossFieldOptions::constrained_edges are treated the same way. A
// face with two or three boundary edges is aligned with the longest of them (ties: the first of
// 3f, 3f+1, 3f+2); its other boundary edges are then off the field by their delta (rounded to a
// quarter turn in k).
#include <array>
#include <complex>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "igm/field/face_frames.h"

namespace igm {

enum class FieldSolver {
  InverseIteration,   // inverse power iteration with one sparse factorization (the paper's)
  ShiftInvertLanczos  // Spectra's shift-invert Lanczos on the same factorization
};
const char* to_string(FieldSolver solver);

struct CrossFieldOptions {
  /// Curvature alignment weight w >= 0. 0: the smoothest field (closed surface: the smallest
  /// eigenvector of A u = lambda M u; open surface: the smoothest field with the boundary
  /// values). w > 0: the minimizer of E(u) + (w / S) |u - q|^2_M (with the boundary values), S
  /// the surface area and q the curvature guide (curvature.h) scaled to unit mean square, i.e.
  /// the linear system (A + c M) u = c M q, c = w / S: the guide wins over the smoothness on
  /// regions larger than about sqrt(S / w). Invariant under rigid motions and scaling. On a
  /// surface whose guide is 0 everywhere the field is computed as for w = 0. Default: measured
  /// (docs/field.md).
  double alignment = 100.0;
  FieldSolver solver = FieldSolver::InverseIteration;
  /// Closed surfaces with w = 0. Inverse iteration: at most this many iterations (each one solve
  /// with the factor) from u = 1 in every frame, stopping earlier when the energy (Rayleigh
  /// quotient) changes by at most `tolerance` relative (measured: the cones no longer change
  /// from about 1e-4 on; docs/field.md). Lanczos: Spectra's maximum of restarts, and its
  /// tolerance on the Ritz values.
  int max_iterations = 100;
  double tolerance = 1e-5;
  /// Surfaces with more faces than this (>= 0) have the field's system factorized in its real
  /// form by embed/sparse_cholesky.h (METIS, supernodal, its analysis kept in a CrossFieldCache),
  /// smaller ones by CHOLMOD's simplicial complex LDL^T (the analysis is cheap there). Measured:
  /// bench/README.md, "Issue 44, stop 55". The two agree to rounding.
  int real_form_above = 200000;
  /// Cones of opposite index (valence sum 8: 3 with 5, 2 with 6) closer than this many mean edge
  /// lengths (shortest path along the edges) are reported as close pairs.
  double close_pair_distance = 3.0;
  /// Cone cleanup: moves of a quarter turn of index from one vertex to another. Each move
  /// carries a quarter turn of period along the shortest path of interior edges between its two
  /// vertices (avoiding every other cone: only the two ends change valence), then the field
  /// angles are re-solved by least squares with every period fixed on the faces within r of the
  /// paths, r = (round + 2) * max(distance, 1) mean edges (Ray et al. 2008, the angle form),
  /// boundary-aligned faces kept. The moves:
  ///  - remove_close_pairs: each close +-1/4 pair (3 with 5 -> 4 and 4); and every vertex no
  ///    seamless map allows (interior valence < 1, boundary k < 1: seen at spikes when the field
  ///    is aligned) gets a quarter turn from the nearest interior cone of valence >= 5 within 8
  ///    mean edges, or else from its nearest regular interior vertex;
  ///  - split_valence2: each interior cone of valence 2 becomes two cones of valence 3, the
  ///    second at the regular interior vertex nearest to split_distance mean edges away (at
  ///    least that far, within 8);
  ///  - split_valence7: each interior cone of valence >= 7 gives a quarter turn to the nearest
  ///    interior cone of valence <= 3 within 8 mean edges, else to a regular vertex as for
  ///    split_valence6;
  ///  - split_valence6: each interior cone of valence 6 becomes two of valence 5, as a valence 2
  ///    into two of valence 3;
  ///  - split_valence1: each interior cone of valence 1 (a sharp tip: cow horns, a needle; no
  ///    patch layout has one) gives a quarter turn to such a vertex (valence 2 and 3), and the
  ///    valence 2 is split in the next round: three cones of valence 3 (needs 2 rounds).
  /// A move whose re-solve leaves a vertex further from regular and outside valence 3..5
  /// (rounding put the quarter turn elsewhere) is dropped, and so is one whose two ends did not
  /// both change; a dropped move is not tried again: the next round takes the next partner
  /// (a round where only moves were dropped does not end the cleanup). A round is kept if it
  /// lowers (vertices of valence < 1, splits still to do (2 for a valence 1, 1 for a 2, a 6 as
  /// asked or a valence >= 7), sum |4 - valence| + sum |2 - k|) lexicographically; at most
  /// `cleanup_rounds` rounds. docs/field.md has the counts.
  bool remove_close_pairs = true;
  bool split_valence1 = true;
  bool split_valence2 = true;
  bool split_valence6 = false;
  bool split_valence7 = true;
  double split_distance = 2.0;
  int cleanup_rounds = 6;
  /// Feature edges as hard constraints (issue 45): empty, or one flag per half-edge, set on both
  /// half-edges of each constrained interior edge. A face with a flagged edge is aligned with it
  /// exactly as with a boundary edge (the longest of its constrained edges; face_frames.h), on
  /// both sides of the edge, so one field direction runs along every constrained edge.
  std::vector<char> constrained_edges;
};

/// An interior vertex of valence != 4, or a boundary vertex with k != 2.
struct Cone {
  int vertex = -1;
  int valence = 4;  // interior: the field valence; boundary: k
};

/// Two interior cones of opposite index and their distance along the edges.
struct ConePair {
  int positive = -1, negative = -1;  // vertices: valence < 4 and valence > 4
  double distance = 0;               // in mean edge lengths
};

struct CrossFieldStats {
  FieldSolver solver = FieldSolver::InverseIteration;
  bool linear = false;         // the field came from one linear solve (boundary or alignment)
  int iterations = 0;          // inverse iterations / Lanczos operator applications
  bool converged = true;       // the iteration met its tolerance (always for a linear solve)
  double energy = 0;           // S u* A u / u* M u, u_f = exp(4 i theta_f) the field returned, S the
                               // area: dimensionless, invariant under rigid motions and scaling
  double seconds = 0;          // wall time of compute_cross_field (reporting only)
  double factor_seconds = 0;   // of which the factorizations
  double mean_edge_length = 0;
  int degenerate_faces = 0;    // faces whose frame took a fallback (face_frames.h)
  int constrained_faces = 0;   // faces aligned with a boundary or feature edge
  /// Interior vertices by valence 0..8 (index 8: valence >= 8; valence <= 0 counts as 0),
  /// and boundary vertices by k 0..8 (the same capping).
  std::array<int, 9> valence_count{};
  std::array<int, 9> boundary_count{};
  int cones_before_cleanup = 0;  // interior cones before the cleanup (== cones without it)
  int pairs_before_cleanup = 0;  // close pairs before the cleanup
  int cleanup_rounds = 0;        // rounds kept
  int cleanup_rejected = 0;      // moves dropped: their re-solve made a vertex worse (see above)
};

struct CrossField {
  FaceFrames frames;                        // per-face frames and transport
  std::vector<double> theta;                // per face, in [0, pi/2)
  std::vector<std::uint8_t> matching;       // per half-edge: m_h (0 on a boundary half-edge)
  std::vector<int> period;                  // per half-edge: p_h (0 on a boundary half-edge)
  std::vector<int> valence;                 // per vertex: interior valence, or boundary k
  std::vector<std::uint8_t> on_boundary;    // per vertex: 1 on a boundary vertex
  std::vector<Cone> cones;                  // interior vertices of valence != 4, by vertex id
  std::vector<Cone> corners;                // boundary vertices with k != 2, by vertex id
  std::vector<ConePair> close_pairs;        // by distance, then vertex ids (each cone once)
  CrossFieldStats stats;
};

/// The cross field of one connected orientable surface (closed, or with boundary: built with
/// allow_boundary). Pre: positions.size() == mesh.num_vertices(). Throws igm::Error:
/// InvalidArgument (positions size, options out of range), Empty / NoFaces, NonFinite naming the
/// vertex, SeveralComponents naming a face or an unused vertex, NonManifoldVertex naming the
/// vertex (a vertex with more than one fan), Internal naming the half-edge if twins are
/// inconsistent, Internal if the sparse factorization fails (not numerically positive definite)
/// or gives a non-finite field. Deterministic: the same bytes for the same input on any machine
/// and thread count (serial code, CHOLMOD's simplicial factorization without BLAS, a fixed start
/// vector, no randomness). Cost: one sparse LDL^T factorization of the F x F complex system, one
/// solve (alignment or boundary) or at most max_iterations (the smoothest closed field); the
/// cleanup one real factorization on the faces around its moves per attempt (docs/field.md:
/// 0.4 s for armadillo's 52k faces, about 20 s of CPU and 1.1 GB for 1M faces). Above
/// options.real_form_above faces the system is factorized in its real form by
/// embed/sparse_cholesky.h (METIS, supernodal; the same bits for any thread count), whose
/// analysis `cache` keeps between calls.
class CrossFieldCache;
CrossField compute_cross_field(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                               const CrossFieldOptions& options = {}, CrossFieldCache* cache = nullptr);

/// What compute_cross_field calls on one mesh share: the pipeline's rounds and attempts change
/// the feature constraints and the alignment, not the mesh. Above real_form_above faces it keeps the
/// analysis (fill-reducing order, symbolic factorization) of the field's system, which depends
/// only on the mesh's edges; a call on another mesh analyzes again. The results are the same
/// bytes with or without a cache. One call at a time.
class CrossFieldCache {
 public:
  CrossFieldCache();
  ~CrossFieldCache();
  CrossFieldCache(const CrossFieldCache&) = delete;
  CrossFieldCache& operator=(const CrossFieldCache&) = delete;
  /// Analyses done so far (0 while every mesh seen had at most real_form_above faces).
  int analyses() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  friend CrossField compute_cross_field(const TriMesh&, const std::vector<Vec3d>&, const CrossFieldOptions&,
                                        CrossFieldCache*);
};

/// Recomputes matchings, periods, valences, cones and stats.valence_count / boundary_count from
/// field.theta and field.frames (used by compute_cross_field, and by a caller that edits theta).
/// Does not touch close_pairs. Cost O(F).
void derive_singularities(const TriMesh& mesh, CrossField& field);

/// "" if Poincare-Hopf holds exactly for the field's valences, else a description of the
/// violation (the two sides). chi = V - E + F counts every vertex and edge of the mesh. O(F).
std::string check_poincare_hopf(const TriMesh& mesh, const CrossField& field);

/// "" if a seamless map whose cones are the field's can exist, else why (naming a vertex): every
/// interior vertex of valence >= 1 (cone angle k pi/2 with k >= 1) and every boundary vertex of
/// k >= 1, and not the one exception of Campen, Shen, Zhou, Zorin 2019 ("Seamless parametrization
/// with arbitrary cones for arbitrary genus": with Poincare-Hopf, any such cone set of a closed
/// surface has a seamless map except) a closed torus whose only cones are one of valence 3 and
/// one of valence 5. Necessary conditions, checked in integers; the rotations along the homology
/// loops (field_rotation) and the integer translations of an IGM are the layout's to satisfy
/// (docs/field.md). O(V + E).
std::string seamless_obstruction(const TriMesh& mesh, const CrossField& field);

/// The close pairs of opposite-index interior cones (valence sum 8) within max_distance mean edge
/// lengths along the edges (CrossFieldOptions::close_pair_distance): each cone in at most one
/// pair, the closest first (greedy, ties by vertex ids). Cost O(cones * the vertices within the
/// bound, times its log).
std::vector<ConePair> close_cone_pairs(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                                       const CrossField& field, double max_distance);

/// The field's rotation along a closed path of faces, given as the half-edges it crosses in
/// order (each from face(h) into face(twin h), the next one in face(twin h)): sum of m_h mod 4,
/// the quarter turns by which a field direction comes back relabelled (0: it comes back to
/// itself). Around an interior vertex this is (4 - valence) mod 4. Throws
/// igm::Error(InvalidArgument) naming the half-edge if the path is not closed and connected
/// or crosses a boundary half-edge.
int field_rotation(const TriMesh& mesh, const CrossField& field, const std::vector<int>& crossed);

/// The 3D unit vector of field direction k (0..3) in face f.
Vec3d field_direction(const CrossField& field, int f, int k);

}  // namespace igm
