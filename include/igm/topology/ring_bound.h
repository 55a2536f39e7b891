#pragma once
// Ring-capacity lower bound on the vertices a system of loops through one root must add: a yardstick
// for the topology stage's growth (cut_to_canonical_disk.h), not a step of the pipeline. Its hop
// rings (HopRings) also rank the root candidates of cut_to_canonical_disk.h (step 1).
//
// Let f be the piecewise-linear interpolation of the hop distance from the root over the input
// triangles, V_k the input vertices at distance k, and D_k the closed faces with a vertex at
// distance <= k. Take 2g loops through the root, simple, pairwise disjoint except at the root and
// each non-contractible (true of every cut into a 4g-gon), drawn on a refinement whose constructed
// vertices lie on input edges or faces and whose edges each lie in one input face. If D_k is a
// closed disk, every loop leaves it, so it reaches f = k + 1; a refined edge lies in one input face,
// where f spans [j, j + 1] for an integer j, so the loop meets f = k at a refined vertex on its way
// out and at another on its way back. That makes 4g distinct vertices with f = k (disjoint loops),
// of which at most |V_k| are input vertices. Summed over levels (a vertex has one f):
//     constructed vertices >= sum over k >= 1 with D_k a disk of max(0, 4g - |V_k|).
// With a valence-6 root and 4g = 36 (couplingdown, g = 9) the first rings alone ask for ~70 vertices.
#include <vector>

#include "igm/mesh/trimesh.h"

namespace igm {

/// The hop rings around a root, one at a time: ring 0 is {root}, ring k + 1 the vertices adjacent
/// to ring k that are in no earlier ring (breadth-first). For searches that stop early, from many
/// roots: the marks are kept between starts, so a start costs O(1), not O(V). Pre: `mesh` outlives
/// this object and every vertex has a half-edge (validate first).
class HopRings {
 public:
  explicit HopRings(const TriMesh& mesh) : mesh_(mesh), mark_(mesh.num_vertices(), -1) {}
  /// Starts at `root` (in range): ring() = {root}, level() = 0.
  void start(int root);
  /// Moves to the next ring; false (and the ring is empty) once every vertex is reached.
  /// O(sum of the valences of the ring left).
  bool next();
  const std::vector<int>& ring() const { return ring_; }
  int level() const { return level_; }

 private:
  const TriMesh& mesh_;
  std::vector<int> mark_;  // the start (counted from 0) that reached the vertex last
  std::vector<int> ring_, next_;
  int starts_ = -1, level_ = 0;
};

struct RingBound {
  int genus = 0;
  long long new_vertices = 0;  // the bound: constructed vertices any such loop system needs
  int levels_counted = 0;      // levels k that contributed (D_k a disk and |V_k| < 4g)
  int max_level = 0;           // the largest hop distance from the root
};

/// The bound above for loops through `root`. Pre: `mesh` closed, connected and oriented (validate
/// first). Genus 0 gives 0 (no loops). Throws igm::Error(InvalidArgument) naming the root if it is
/// out of range. Cost O(F) for the distances plus O(F) per level with |V_k| < 4g (the disk test).
RingBound ring_capacity_bound(const TriMesh& mesh, int root);

}  // namespace igm
