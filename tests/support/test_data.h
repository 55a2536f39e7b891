#pragma once
// Where the shared test data lives: $IGM_DATA_DIR, else ../shared beside the source tree.
// Tests that need it call data_dir(); when it is absent they print why and skip.
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

namespace igm_test {

inline std::optional<std::filesystem::path> data_dir() {
  const char* env = std::getenv("IGM_DATA_DIR");
  std::filesystem::path p = env && *env ? std::filesystem::path(env) : std::filesystem::path(IGM_DEFAULT_DATA_DIR);
  std::error_code ec;
  if (std::filesystem::is_directory(p / "meshes", ec)) return p;
  return std::nullopt;
}

#ifdef IGM_SANITIZED
inline constexpr bool kSanitized = true;  // built with -DIGM_SANITIZE=ON (tests/CMakeLists.txt)
#else
inline constexpr bool kSanitized = false;
#endif

}  // namespace igm_test

// Use at the top of a TEST_CASE: binds `dir` or skips the case with a message.
#define IGM_REQUIRE_DATA(dir)                                                                   \
  auto dir##_opt = igm_test::data_dir();                                                        \
  if (!dir##_opt) {                                                                             \
    MESSAGE("skipped: shared test data not found (set IGM_DATA_DIR to the shared/ folder)");    \
    return;                                                                                     \
  }                                                                                             \
  const std::filesystem::path dir = *dir##_opt
