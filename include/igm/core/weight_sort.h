#pragma once
// Sorting weighted half-edges heaviest first, for Kruskal's maximum spanning trees of the dual
// (the tree-cotree bases of the topology stage): (weight, id) pairs by weight descending, ties by
// id ascending. A stable least-significant-digit radix sort on the weights' IEEE-754 bits (for
// weights >= 0, +inf included, the bits order like the values): eight passes of 8 bits, or four of
// 16 bits from 2^18 items on.
#include <utility>
#include <vector>

namespace igm {

/// Sorts `items` by first descending, then second ascending: the same order as std::sort with that
/// comparator (a total order, so the result is unique). Radix sort when every weight is >= 0 or
/// +inf (-0.0 counts as 0) and the ids come in ascending order, as where the callers build them
/// (one pass over the half-edges); otherwise, or for fewer than 128 items, std::sort. O(n) for the
/// radix path (8 or 4 passes, n pairs of extra memory), O(n log n) otherwise.
void sort_by_weight_descending(std::vector<std::pair<double, int>>& items);

}  // namespace igm
