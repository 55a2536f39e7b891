// ns per orient2d call: double (filtered, exact path forced), rational (filtered, exact integer
// path forced, plain mpq determinant) on dyadic coordinates of ~60 and ~200 bits in [0, 1], on
// general rationals, and on exactly collinear dyadic triples (where the filter must fall back).
// Usage: igm_bench_predicates [calls_per_case [distinct_inputs]]   (defaults 400000, 256: in cache)
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "thread_cpu.h"
#include "igm/exact/predicates.h"

using namespace igm;

namespace {

volatile long g_sink = 0;

using igm_bench::thread_cpu_ns;

// The minimum over 5 rounds of calls/5 calls each (the least disturbed round).
template <class F>
double ns_per_call(std::size_t calls, F&& f) {
  const std::size_t per_round = calls / 5 + 1;
  double best = 1e300;
  for (int round = 0; round < 5; ++round) {
    const double t0 = thread_cpu_ns();
    long sum = 0;
    for (std::size_t i = 0; i < per_round; ++i) sum += f(i);
    const double t1 = thread_cpu_ns();
    g_sink = g_sink + sum;
    best = std::min(best, (t1 - t0) / static_cast<double>(per_round));
  }
  return best;
}

Sign plain_mpq(const Point2q& a, const Point2q& b, const Point2q& c) {
  const Rational det = (a.x - c.x) * (b.y - c.y) - (a.y - c.y) * (b.x - c.x);
  return sign(det);
}

// n / 2^bits with n uniform in [0, 2^bits): a dyadic number in [0, 1) with ~bits significant bits.
Rational dyadic(gmp_randclass& g, unsigned long bits) {
  return make_rational(g.get_z_bits(bits), mpz_class(1) << bits);
}

struct Triple {
  Point2q a, b, c;
};

}  // namespace

int main(int argc, char** argv) {
  const std::size_t calls = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 400000;
  const std::size_t kSet = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 256;  // distinct inputs, cycled
  std::mt19937_64 rng(1);
  gmp_randclass g(gmp_randinit_default);
  g.seed(1);

  std::vector<Vec2d> pd(3 * kSet);
  std::uniform_real_distribution<double> u(0, 1);
  for (auto& p : pd) p = {u(rng), u(rng)};
  auto D = [&](std::size_t i, int k) -> const Vec2d& { return pd[3 * (i % kSet) + k]; };

  std::printf("orient2d, ns per call, thread CPU time, best of 5 rounds (%zu calls per case, %zu distinct inputs)\n", calls, kSet);
  std::printf("%-52s %10.1f\n", "double, filtered (random in [0,1]^2)",
              ns_per_call(calls, [&](std::size_t i) { return static_cast<long>(orient2d(D(i, 0), D(i, 1), D(i, 2))); }));
  std::printf("%-52s %10.1f\n", "double, exact path forced (orient2d_exact)",
              ns_per_call(calls / 4, [&](std::size_t i) { return static_cast<long>(orient2d_exact(D(i, 0), D(i, 1), D(i, 2))); }));

  auto make_set = [&](auto gen) {
    std::vector<Triple> t(kSet);
    for (auto& x : t) x = gen();
    return t;
  };
  auto run = [&](const char* name, const std::vector<Triple>& t) {
    auto T = [&](std::size_t i) -> const Triple& { return t[i % kSet]; };
    int answered = 0;
    for (const auto& x : t) answered += orient2d_filter(x.a, x.b, x.c).has_value();
    const double f = ns_per_call(calls, [&](std::size_t i) { return static_cast<long>(orient2d(T(i).a, T(i).b, T(i).c)); });
    const double e = ns_per_call(calls / 2, [&](std::size_t i) { return static_cast<long>(orient2d_exact(T(i).a, T(i).b, T(i).c)); });
    const double m = ns_per_call(calls / 4, [&](std::size_t i) { return static_cast<long>(plain_mpq(T(i).a, T(i).b, T(i).c)); });
    std::printf("%s (filter decides %.1f%%)\n", name, 100.0 * answered / kSet);
    std::printf("  %-50s %10.1f\n", "rational, filtered (orient2d)", f);
    std::printf("  %-50s %10.1f\n", "rational, exact integer path (orient2d_exact)", e);
    std::printf("  %-50s %10.1f\n", "rational, plain mpq determinant", m);
  };
  for (unsigned long bits : {60UL, 200UL}) {
    char name[96];
    std::snprintf(name, sizeof name, "dyadic %lu-bit coordinates in [0,1)", bits);
    run(name, make_set([&] {
          return Triple{{dyadic(g, bits), dyadic(g, bits)}, {dyadic(g, bits), dyadic(g, bits)}, {dyadic(g, bits), dyadic(g, bits)}};
        }));
    std::snprintf(name, sizeof name, "dyadic %lu-bit, exactly collinear triples", bits);
    run(name, make_set([&] {
          const Point2q a{dyadic(g, bits), dyadic(g, bits)}, b{dyadic(g, bits), dyadic(g, bits)};
          const Rational t = dyadic(g, 8);
          return Triple{a, b, {Rational(a.x + t * (b.x - a.x)), Rational(a.y + t * (b.y - a.y))}};
        }));
  }
  run("general rationals, 60-bit numerators and denominators in [0,1)", make_set([&] {
        auto q = [&] {
          mpz_class d = g.get_z_bits(60) + 1;
          mpz_class n = g.get_z_bits(60) % d;
          return make_rational(n, d);
        };
        return Triple{{q(), q()}, {q(), q()}, {q(), q()}};
      }));
  return 0;
}
