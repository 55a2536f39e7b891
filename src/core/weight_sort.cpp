#include "igm/core/weight_sort.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace igm {

namespace {

bool heavier_first(const std::pair<double, int>& x, const std::pair<double, int>& y) {
  return x.first != y.first ? x.first > y.first : x.second < y.second;
}

// The radix key: ascending keys are descending weights. -0.0 is mapped to +0.0 first (they compare
// equal as doubles; their bits differ).
std::uint64_t key_of(double w) {
  if (w == 0.0) w = 0.0;
  std::uint64_t bits;
  std::memcpy(&bits, &w, sizeof bits);
  return ~bits;
}

}  // namespace

void sort_by_weight_descending(std::vector<std::pair<double, int>>& items) {
  const std::size_t n = items.size();
  bool radix = n >= 4096;
  for (std::size_t i = 0; radix && i < n; ++i)
    radix = items[i].first >= 0.0 && (i == 0 || items[i - 1].second < items[i].second);  // NaN fails >= 0
  if (!radix) {
    std::sort(items.begin(), items.end(), heavier_first);
    return;
  }
  // Stable passes from the lowest digit: equal keys keep the ids' ascending input order.
  std::vector<std::pair<double, int>> tmp(n);
  for (int pass = 0; pass < 4; ++pass) {
    const int shift = 16 * pass;
    auto digit = [shift](const std::pair<double, int>& x) { return (key_of(x.first) >> shift) & 0xffff; };
    std::vector<std::size_t> start(65537, 0);
    for (const auto& x : items) ++start[digit(x) + 1];
    if (std::find(start.begin() + 1, start.end(), n) != start.end()) continue;  // one digit for all
    for (std::size_t d = 1; d <= 65536; ++d) start[d] += start[d - 1];
    for (const auto& x : items) tmp[start[digit(x)]++] = x;
    items.swap(tmp);
  }
}

}  // namespace igm
