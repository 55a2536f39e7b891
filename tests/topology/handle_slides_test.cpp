#include <doctest/doctest.h>

#include <algorithm>
#include <functional>
#include <random>

#include "igm/core/error.h"
#include "igm/topology/handle_slides.h"

using namespace igm;

namespace {
Word canonical(int g) {
  Word w;
  for (int k = 0; k < g; ++k) w.insert(w.end(), {{2 * k, false}, {2 * k + 1, false}, {2 * k, true}, {2 * k + 1, true}});
  return w;
}
// Number of vertex classes of the polygon: corner i (before letter i) is glued to corners by the
// side identifications. An independent check that generated words are one-vertex words.
int vertex_classes(const Word& w) {
  const int n = static_cast<int>(w.size());
  std::vector<int> p(n);
  for (int i = 0; i < n; ++i) p[i] = i;
  std::function<int(int)> f = [&](int x) { return p[x] == x ? x : p[x] = f(p[x]); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (i != j && w[i].loop == w[j].loop) {
        // side i runs corner i -> corner i+1 in direction (inverse? end->start : start->end)
        int si = w[i].inverse ? (i + 1) % n : i, ti = w[i].inverse ? i : (i + 1) % n;
        int sj = w[j].inverse ? (j + 1) % n : j, tj = w[j].inverse ? j : (j + 1) % n;
        p[f(si)] = f(sj);
        p[f(ti)] = f(tj);
      }
  int c = 0;
  for (int i = 0; i < n; ++i) c += f(i) == i;
  return c;
}
// A random one-vertex word: random slides and relabelling applied to the canonical word.
Word random_word(int g, std::mt19937& rng) {
  Word w = canonical(g);
  const int n = 4 * g;
  for (int step = 0; step < 6 * g; ++step) {
    int i = rng() % n, j = rng() % n;
    if (i == j) continue;
    std::vector<int> candidates;
    for (int x = 0; x < 2 * g; ++x) {
      int in = 0;
      for (int k = i; k != j; k = (k + 1) % n) in += w[k].loop == x;
      if (in == 1) candidates.push_back(x);
    }
    if (candidates.empty()) continue;
    w = apply_slide(w, {i, j, candidates[rng() % candidates.size()]});
  }
  std::vector<int> perm(2 * g);
  for (int i = 0; i < 2 * g; ++i) perm[i] = i;
  std::shuffle(perm.begin(), perm.end(), rng);
  std::vector<char> flip(2 * g);
  for (auto& f : flip) f = rng() % 2;
  for (auto& l : w) l = {perm[l.loop], static_cast<bool>(l.inverse ^ flip[l.loop])};
  std::rotate(w.begin(), w.begin() + rng() % n, w.end());
  return w;
}
}  // namespace

TEST_CASE("apply_slide follows the cut-and-paste formula") {
  // x P y Q x^-1 R y^-1 S with single-letter blocks P=2,Q=3,R=4,S=5 is not a valid word; use a
  // genus-1 word and check the two planned slides by hand.
  Word w = {{0, false}, {1, false}, {0, true}, {1, true}};
  CHECK(is_valid_word(w));
  CHECK(is_canonical_word(w));
  CHECK(vertex_classes(w) == 1);
  // chord from corner 0 to corner 3 separating loop 1: alpha = L0 L1 L0', beta = L1'
  Word v = apply_slide(w, {0, 3, 1});
  CHECK(to_string(v) == "L0' L1' L0 L1");
  CHECK_THROWS_AS(apply_slide(w, {0, 1, 1}), Error);
  CHECK_THROWS_AS(apply_slide(w, {0, 0, 0}), Error);
  CHECK(plan_handle_slides(w).empty());
}

TEST_CASE("planned slides reach commutator blocks in at most 2g steps on random words") {
  std::mt19937 rng(7);
  int total = 0;
  for (int trial = 0; trial < 300; ++trial) {
    int g = 1 + trial % 12;
    if (trial % 50 == 0) g = 40 + trial / 10;
    Word w = random_word(g, rng);
    REQUIRE(is_valid_word(w));
    REQUIRE(vertex_classes(w) == 1);
    Word fin;
    auto slides = plan_handle_slides(w, &fin);
    CHECK(static_cast<int>(slides.size()) <= 2 * g);
    Word cur = w;
    for (const auto& s : slides) {
      cur = apply_slide(cur, s);
      CHECK(vertex_classes(cur) == 1);
    }
    CHECK(cur == fin);
    CHECK(is_valid_word(fin));
    CHECK(commutator_rotation(fin) >= 0);
    total += static_cast<int>(slides.size());
  }
  MESSAGE("total slides over 300 random words: " << total);
}

TEST_CASE("words that are not one-vertex words are refused, not looped on") {
  // a a^-1 b b^-1: two pairs, no linked pair.
  Word w = {{0, false}, {0, true}, {1, false}, {1, true}};
  CHECK_THROWS_AS(plan_handle_slides(w), Error);
  Word bad = {{0, false}, {0, false}, {1, false}, {1, true}};
  CHECK_FALSE(is_valid_word(bad));
  CHECK_THROWS_AS(plan_handle_slides(bad), Error);
}
