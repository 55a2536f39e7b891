#include <doctest/doctest.h>

#include <random>
#include <vector>

#include "igm/core/union_find.h"

using igm::UnionFind;

TEST_CASE("union-find agrees with a naive labelling on random unions") {
  // The naive reference relabels a whole set on every union: O(n) per union, obviously right.
  std::mt19937 rng(7);
  for (int n : {1, 2, 10, 300}) {
    CAPTURE(n);
    UnionFind uf(static_cast<std::size_t>(n));
    std::vector<int> label(n);
    for (int i = 0; i < n; ++i) label[i] = i;
    std::uniform_int_distribution<int> pick(0, n - 1);
    int sets = n;
    for (int step = 0; step < 3 * n; ++step) {
      const int a = pick(rng), b = pick(rng);
      const bool separate = label[a] != label[b];
      CHECK(uf.unite(a, b) == separate);
      if (separate) {
        const int old = label[b];
        for (int& l : label)
          if (l == old) l = label[a];
        --sets;
      }
      CHECK(uf.find(a) == uf.find(b));
    }
    int roots = 0;
    for (int x = 0; x < n; ++x) {
      roots += uf.find(x) == x;
      for (int y = 0; y < n; y += 7) CHECK((uf.find(x) == uf.find(y)) == (label[x] == label[y]));
    }
    CHECK(roots == sets);
  }
}
