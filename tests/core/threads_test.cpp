#include <doctest/doctest.h>

#include <cstdlib>
#include <stdexcept>
#include <thread>

#include "igm/core/error.h"
#include "igm/core/threads.h"

using namespace igm;

TEST_CASE("resolve_threads: a count as given, 0 from IGM_THREADS or every core, negative an error") {
  CHECK(resolve_threads(3) == 3);
  const char* saved = std::getenv("IGM_THREADS");
  const std::string keep = saved ? saved : "";
  unsetenv("IGM_THREADS");
  const unsigned cores = std::thread::hardware_concurrency();
  CHECK(resolve_threads(0) == (cores > 0 ? static_cast<int>(cores) : 1));
  setenv("IGM_THREADS", "5", 1);
  CHECK(resolve_threads(0) == 5);
  CHECK(resolve_threads(2) == 2);  // an explicit count wins
  for (const char* bad : {"", "0", "-2", "3x", "abc", "99999"}) {
    CAPTURE(bad);
    setenv("IGM_THREADS", bad, 1);
    CHECK(resolve_threads(0) == (cores > 0 ? static_cast<int>(cores) : 1));
  }
  if (saved)
    setenv("IGM_THREADS", keep.c_str(), 1);
  else
    unsetenv("IGM_THREADS");
  CHECK_THROWS_AS(resolve_threads(-1), Error);
}

TEST_CASE("with_threads runs the function and passes its exceptions on") {
  int ran = 0;
  with_threads(2, [&] { ++ran; });
  CHECK(ran == 1);
  CHECK_THROWS_AS(with_threads(1, [] { throw std::runtime_error("x"); }), std::runtime_error);
  CHECK_THROWS_AS(with_threads(-3, [] {}), Error);
}
