#pragma once
// An independent check of a loop system at a root, from the raw vertex lists (shared by the
// topology tests of the tightening and of the slides).
#include <string>
#include <vector>

#include "igm/mesh/trimesh.h"

namespace igm_test {

// Loops: 2g of them, from the root, along edges, simple and pairwise disjoint but at the root.
inline std::string loop_violation(const igm::TriMesh& M, const std::vector<std::vector<int>>& loops, int root,
                                  int genus) {
  if (static_cast<int>(loops.size()) != 2 * genus) return "loop count";
  std::vector<int> owner(M.num_vertices(), -1);
  for (std::size_t i = 0; i < loops.size(); ++i) {
    const auto& L = loops[i];
    if (L.size() < 3 || L[0] != root) return "loop " + std::to_string(i) + " does not start at the root";
    for (std::size_t j = 0; j < L.size(); ++j) {
      if (L[j] < 0 || L[j] >= M.num_vertices()) return "vertex out of range";
      if (M.find_halfedge(L[j], L[(j + 1) % L.size()]) < 0) return "loop step is not an edge";
      if (j == 0) continue;
      if (L[j] == root || owner[L[j]] != -1) return "loops not simple or not disjoint";
      owner[L[j]] = static_cast<int>(i);
    }
  }
  return "";
}

}  // namespace igm_test
