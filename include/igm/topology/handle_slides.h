#pragma once
// Combinatorics of handle slides on the gluing word of a one-vertex polygonal schema (Fulton,
// Algebraic Topology, ch. 17b; Livesu, C&G 2023). A word lists the 4g sides of the disk boundary
// counter-clockwise; each loop occurs twice, once forward and once inverse; corner i is the polygon
// corner just before letter i (every corner is a copy of the root).
//
// A slide {i, j, x} draws a new loop c inside the disk from corner i to corner j, where the chord
// separates the two occurrences of loop x, cuts the disk along c and glues the two pieces back
// along x. The new loop takes x's id. With alpha = letters i..j-1 = a1 X a2 and beta = letters
// j..i-1 = b1 X' b2 (X, X' the two occurrences of x), the new word is  a2 c^-1 a1 b2 c b1,
// where c runs from corner i to corner j.
#include <string>
#include <vector>

namespace igm {

struct Letter {
  int loop = -1;
  bool inverse = false;
  bool operator==(const Letter& o) const { return loop == o.loop && inverse == o.inverse; }
  bool operator!=(const Letter& o) const { return !(*this == o); }
};
using Word = std::vector<Letter>;

struct Slide {
  int from_corner = -1;  // corner i (before letter i)
  int to_corner = -1;    // corner j
  int loop = -1;         // the loop x that is replaced by the new loop c (c takes x's id)
};

/// True if w has 4g letters, ids 0..2g-1 each occurring once forward and once inverse.
bool is_valid_word(const Word& w);

/// The word after one slide (formula above). Throws igm::Error(InvalidArgument) if the corners are
/// out of range or equal, or the chord does not separate the two occurrences of s.loop. O(|w|).
Word apply_slide(const Word& w, const Slide& s);

/// True if w = L0 L1 L0^-1 L1^-1 L2 L3 L2^-1 L3^-1 ... exactly (ids and orientations as written).
bool is_canonical_word(const Word& w);

/// True if letters p, p+1, p+2, p+3 of w (cyclically, p any integer) read x y x^-1 y^-1 for two
/// different loops x, y (any orientations). Pre: w non-empty. O(1).
bool block_at(const Word& w, int p);

/// A rotation r such that w[r], w[r+1], ... consists of g consecutive commutator blocks
/// p q p^-1 q^-1 (any ids and orientations), or -1.
int commutator_rotation(const Word& w);

/// Marks in `done` (per loop id, size |w|/2) both loops of each commutator block of w whose loops
/// are both unmarked, scanning block_at from position 0 on. O(|w|).
void mark_blocks(const Word& w, std::vector<char>& done);

/// A two-slide formation of a handle (plan_handle_slides): `first` = {p1, p3+1, Y} for a linked
/// pair X (letters p1, p3) and Y (letter p2 strictly between them, its other letter outside).
struct Formation {
  Slide first;
  int x = -1;  // X, the loop the second slide replaces
};

/// The formations of w among loops not `done`, in plan_handle_slides' order: every letter p1 of
/// such a loop X, then every letter p2 after it (cyclically, before X's other letter p3) of such a
/// loop Y whose other letter lies outside. O(|w|^2).
std::vector<Formation> formations(const Word& w, const std::vector<char>& done);

/// The second slide of formation f, on the word w1 = apply_slide(w, f.first): from the corner
/// before the new Y^-1 to the corner before the new Y, replacing X. O(|w|).
Slide second_slide(const Word& w1, const Formation& f);

/// Plans slides that bring a one-vertex word into commutator blocks: for a linked pair
/// X .. Y .. X^-1 .. Y^-1 (positions p1 < p2 < p3 < p4 cyclically), slide {p1, p3+1, Y} gives
/// Q X^-1 c^-1 X P S c R, then the slide from the corner before c^-1 to the corner before c,
/// replacing X, gives the block d^-1 c^-1 d c next to R Q P S. Handles already in block form are
/// left alone. Returns at most 2g slides (two per handle not yet a block); *final_word receives the
/// result. Pre: is_valid_word(w) and all corners of w are one vertex (true for the words of
/// cut_to_canonical_disk); throws igm::Error(Internal) if no linked pair exists. O(g^3): the
/// formations of each iteration, the first taken.
std::vector<Slide> plan_handle_slides(const Word& w, Word* final_word = nullptr);

/// "L0 L1 L0' L1'": for messages and tests.
std::string to_string(const Word& w);

}  // namespace igm
