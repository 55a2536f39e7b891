#pragma once
// Equality of outputs bit for bit, for the tests that run the same computation on different
// thread counts (igm/core/threads.h): exact UVs equal as rationals, doubles equal as bits.
#include <array>
#include <cstring>
#include <vector>

#include "igm/exact/predicates.h"

namespace igm_test {

inline bool same_uv(const std::vector<std::array<igm::Point2q, 3>>& a, const std::vector<std::array<igm::Point2q, 3>>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t f = 0; f < a.size(); ++f)
    for (int i = 0; i < 3; ++i)
      if (a[f][i].x != b[f][i].x || a[f][i].y != b[f][i].y) return false;
  return true;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), sizeof(T) * a.size()) == 0);
}

}  // namespace igm_test
