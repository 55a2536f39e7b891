#include "igm/core/weight_sort.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>

using igm::sort_by_weight_descending;

namespace {

using Items = std::vector<std::pair<double, int>>;

Items by_std_sort(Items v) {
  std::sort(v.begin(), v.end(), [](const auto& x, const auto& y) {
    return x.first != y.first ? x.first > y.first : x.second < y.second;
  });
  return v;
}

}  // namespace

TEST_CASE("weighted half-edges are sorted heaviest first, ties by id, as std::sort orders them") {
  std::mt19937 rng(7);
  for (std::size_t n : {0, 1, 5, 127, 128, 4096, 50000, 262143, 262144}) {
    CAPTURE(n);
    // Few distinct weights (many ties), wide magnitudes, +inf, zeros of both signs, ids ascending
    // with gaps: the radix path from 128 items on, its 16-bit digits from 262,144.
    Items v;
    int id = 0;
    for (std::size_t i = 0; i < n; ++i) {
      id += 1 + static_cast<int>(rng() % 3);
      double w;
      switch (rng() % 6) {
        case 0: w = static_cast<double>(rng() % 8); break;
        case 1: w = INFINITY; break;
        case 2: w = (rng() % 2) ? 0.0 : -0.0; break;
        case 3: w = std::ldexp(static_cast<double>(rng()), static_cast<int>(rng() % 200) - 100); break;
        case 4: w = 1.0 + std::ldexp(static_cast<double>(rng() % 1000), -52); break;  // low bits only
        default: w = static_cast<double>(rng()) / 7.0;
      }
      v.push_back({w, id});
    }
    const Items expected = by_std_sort(v);
    Items got = v;
    sort_by_weight_descending(got);
    REQUIRE(got.size() == expected.size());
    const std::size_t first_diff =
        static_cast<std::size_t>(std::mismatch(got.begin(), got.end(), expected.begin()).first - got.begin());
    CAPTURE(first_diff);
    CHECK(first_diff == got.size());  // the same ids and weights at every position
  }
}

TEST_CASE("weights or ids outside the radix path's precondition still sort correctly") {
  std::mt19937 rng(11);
  Items v;
  for (int i = 0; i < 10000; ++i) v.push_back({static_cast<double>(rng() % 100) - 50.0, static_cast<int>(rng() % 5000)});
  Items got = v;
  sort_by_weight_descending(got);  // negative weights, ids neither ascending nor distinct
  CHECK(got == by_std_sort(v));
}
