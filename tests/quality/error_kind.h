#pragma once
// The kind of the igm::Error a call throws, for the quality tests (fails the case if none).
#include <doctest/doctest.h>

#include "igm/core/error.h"

namespace igm_test {

inline igm::ErrorKind kind_of(auto&& f) {
  try {
    f();
  } catch (const igm::Error& e) {
    return e.kind();
  }
  FAIL("no igm::Error thrown");
  return igm::ErrorKind::Internal;
}

}  // namespace igm_test
