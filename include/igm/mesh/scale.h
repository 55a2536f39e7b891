#pragma once
// Lengths of hostile geometry: coordinates may be 1e300 (squares overflow) or 1e-300 (squares
// underflow). Scaling every position by one power of two brings them to about 1, exactly.
#include <vector>

#include "igm/exact/predicates.h"

namespace igm {

/// 2^-k for the least k with every finite |coordinate| of `positions` below 2^k (1 if all are zero or
/// none is finite). Multiplying by it is exact unless it underflows; afterwards every coordinate is
/// below 1, so differences, lengths and squared lengths stay finite. O(n).
double unit_scale(const std::vector<Vec3d>& positions);

/// |scale p - scale q| (the distance in scaled units). O(1).
double scaled_distance(const Vec3d& p, const Vec3d& q, double scale);

/// The positions multiplied by `scale`. O(n).
std::vector<Vec3d> scaled_positions(const std::vector<Vec3d>& positions, double scale);

}  // namespace igm
