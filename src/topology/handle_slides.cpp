#include "igm/topology/handle_slides.h"

#include <string>

#include "igm/core/error.h"

namespace igm {

namespace {
Letter inv(Letter l) { return {l.loop, !l.inverse}; }
int mod(int a, int n) { return ((a % n) + n) % n; }
}  // namespace

bool is_valid_word(const Word& w) {
  const int n = static_cast<int>(w.size());
  if (n == 0 || n % 4 != 0) return false;
  std::vector<int> fwd(n / 2, 0), bwd(n / 2, 0);
  for (const auto& l : w) {
    if (l.loop < 0 || l.loop >= n / 2) return false;
    ++(l.inverse ? bwd : fwd)[l.loop];
  }
  for (int i = 0; i < n / 2; ++i)
    if (fwd[i] != 1 || bwd[i] != 1) return false;
  return true;
}

Word apply_slide(const Word& w, const Slide& s) {
  const int n = static_cast<int>(w.size());
  if (s.from_corner < 0 || s.from_corner >= n || s.to_corner < 0 || s.to_corner >= n || s.from_corner == s.to_corner)
    throw Error(ErrorKind::InvalidArgument, "slide corners out of range or equal");
  Word alpha, beta;
  for (int k = s.from_corner; k != s.to_corner; k = (k + 1) % n) alpha.push_back(w[k]);
  for (int k = s.to_corner; k != s.from_corner; k = (k + 1) % n) beta.push_back(w[k]);
  int a = -1, b = -1, count = 0;
  for (int k = 0; k < static_cast<int>(alpha.size()); ++k)
    if (alpha[k].loop == s.loop) a = k, ++count;
  for (int k = 0; k < static_cast<int>(beta.size()); ++k)
    if (beta[k].loop == s.loop) b = k, ++count;
  if (a < 0 || b < 0 || count != 2)
    throw Error(ErrorKind::InvalidArgument, "slide chord does not separate the two sides of loop " + std::to_string(s.loop));
  Word out;
  out.insert(out.end(), alpha.begin() + a + 1, alpha.end());
  out.push_back({s.loop, true});
  out.insert(out.end(), alpha.begin(), alpha.begin() + a);
  out.insert(out.end(), beta.begin() + b + 1, beta.end());
  out.push_back({s.loop, false});
  out.insert(out.end(), beta.begin(), beta.begin() + b);
  return out;
}

bool is_canonical_word(const Word& w) {
  if (w.size() % 4 != 0 || w.empty()) return false;
  for (std::size_t k = 0; k < w.size() / 4; ++k) {
    int p = static_cast<int>(2 * k), q = p + 1;
    if (w[4 * k] != Letter{p, false} || w[4 * k + 1] != Letter{q, false} || w[4 * k + 2] != Letter{p, true} ||
        w[4 * k + 3] != Letter{q, true})
      return false;
  }
  return true;
}

bool block_at(const Word& w, int p) {
  const int n = static_cast<int>(w.size());
  Letter a = w[mod(p, n)], b = w[mod(p + 1, n)];
  return a.loop != b.loop && w[mod(p + 2, n)] == inv(a) && w[mod(p + 3, n)] == inv(b);
}

int commutator_rotation(const Word& w) {
  const int n = static_cast<int>(w.size());
  if (n == 0 || n % 4 != 0) return -1;
  for (int r = 0; r < 4; ++r) {  // blocks tile the word, so only 4 phases exist
    bool ok = true;
    for (int k = 0; k < n / 4 && ok; ++k) ok = block_at(w, r + 4 * k);
    if (ok) return r;
  }
  return -1;
}

void mark_blocks(const Word& w, std::vector<char>& done) {
  const int n = static_cast<int>(w.size());
  for (int p = 0; p < n; ++p)
    if (!done[w[p].loop] && !done[w[mod(p + 1, n)].loop] && block_at(w, p))
      done[w[p].loop] = done[w[mod(p + 1, n)].loop] = 1;
}

std::vector<Formation> formations(const Word& w, const std::vector<char>& done) {
  const int n = static_cast<int>(w.size());
  std::vector<int> pos_f(n / 2), pos_b(n / 2);
  for (int p = 0; p < n; ++p) (w[p].inverse ? pos_b : pos_f)[w[p].loop] = p;
  auto partner = [&](int p) { return w[p].inverse ? pos_f[w[p].loop] : pos_b[w[p].loop]; };
  std::vector<Formation> out;
  for (int p = 0; p < n; ++p) {
    if (done[w[p].loop]) continue;
    const int q = partner(p), span = mod(q - p, n);
    for (int k = 1; k < span; ++k) {
      const int y = mod(p + k, n);
      if (!done[w[y].loop] && mod(partner(y) - p, n) > span)
        out.push_back({Slide{p, mod(q + 1, n), w[y].loop}, w[p].loop});
    }
  }
  return out;
}

Slide second_slide(const Word& w1, const Formation& f) {
  int c_inv = -1, c_fwd = -1;
  for (int p = 0; p < static_cast<int>(w1.size()); ++p)
    if (w1[p].loop == f.first.loop) (w1[p].inverse ? c_inv : c_fwd) = p;
  return Slide{c_inv, c_fwd, f.x};
}

std::vector<Slide> plan_handle_slides(const Word& w0, Word* final_word) {
  if (!is_valid_word(w0)) throw Error(ErrorKind::InvalidArgument, "not a valid gluing word: " + to_string(w0));
  Word w = w0;
  const int n = static_cast<int>(w.size());
  std::vector<Slide> slides;
  std::vector<char> done(n / 2, 0);
  // Each iteration turns at least one handle into a block: at most g iterations.
  for (int iter = 0; iter <= n / 4; ++iter) {
    mark_blocks(w, done);  // existing blocks of unfinished loops
    int remaining = 0;
    for (char d : done) remaining += d ? 0 : 1;
    if (remaining == 0) break;
    if (iter == n / 4) throw Error(ErrorKind::Internal, "handle slides did not converge: " + to_string(w));
    const std::vector<Formation> all = formations(w, done);
    if (all.empty()) throw Error(ErrorKind::Internal, "no linked pair in word " + to_string(w));
    const Formation& f = all.front();
    const int x = f.x, y = f.first.loop;
    w = apply_slide(w, f.first);
    slides.push_back(f.first);
    const Slide s2 = second_slide(w, f);
    w = apply_slide(w, s2);
    slides.push_back(s2);
    bool formed = false;
    for (int p = 0; p < n; ++p)
      if ((w[p].loop == x || w[p].loop == y) && block_at(w, p) &&
          (w[mod(p + 1, n)].loop == x || w[mod(p + 1, n)].loop == y))
        formed = true;
    if (!formed) throw Error(ErrorKind::Internal, "slide pair did not form a handle: " + to_string(w));
  }
  if (final_word) *final_word = w;
  return slides;
}

std::string to_string(const Word& w) {
  std::string s;
  for (const auto& l : w) {
    if (!s.empty()) s += ' ';
    s += 'L' + std::to_string(l.loop);
    if (l.inverse) s += '\'';
  }
  return s;
}

}  // namespace igm
