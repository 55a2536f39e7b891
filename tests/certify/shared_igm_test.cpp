// Third-party IGMs (libQEx test data, made with MIQ and another method) against the independent
// exact counts of /work/shared/meshes/README.md.
#include <doctest/doctest.h>

#include "certify/certify.h"
#include "test_data.h"

using namespace igm::certify;

namespace {
struct Expect {
  const char* file;
  std::int64_t V, F, flipped, non_rigid, off_integer_total;
};
}  // namespace

TEST_CASE("shared third-party IGMs: invalid, with the independently measured counts") {
  IGM_REQUIRE_DATA(dir);
  const Expect cases[] = {{"duck_miq_4_param.obj", 9862, 19720, 18, 323, 7},
                          {"duck_qc_8_param.obj", 9862, 19720, 193, 319, 120},
                          {"fandisk_param.obj", 7229, 14454, 9, 242, 3}};
  for (const auto& e : cases) {
    CAPTURE(e.file);
    const Report r = certify_igm_file((dir / "igm" / e.file).string());
    INFO(summary(r));
    REQUIRE(r.verdict == Verdict::Invalid);
    CHECK(r.num_vertices == e.V);
    CHECK(r.num_faces == e.F);
    REQUIRE(r.genus.has_value());
    CHECK(*r.genus == 0);
    CHECK(r.check(1)->passed());
    CHECK(r.check(2)->count("flipped") == e.flipped);
    CHECK(r.check(2)->count("degenerate") == 0);
    CHECK(r.check(3)->count("non_rigid") == e.non_rigid);
    CHECK(r.check(4)->count("cones_off_integer_total") == e.off_integer_total);
    CHECK(r.check(4)->count("vertices_undetermined") == 0);
    CHECK(r.check(4)->count("transport_inconsistent") == 0);
    // witnesses name elements
    CHECK(r.check(2)->witnesses.size() == std::min<std::size_t>(20, std::size_t(e.flipped)));
    CHECK(r.check(3)->witnesses.size() == 20);
    CHECK(r.check(3)->witnesses[0].kind == "edge");
  }
}

TEST_CASE("shared third-party IGMs: exact breakdown of the cone counts") {
  IGM_REQUIRE_DATA(dir);
  // cones off integer points on rings whose edges all passed check 3 (exact index) versus rings
  // crossing non-rigid edges (index with the nearest rotation there): 7+0, 95+25, 3+0.
  const std::int64_t exact[] = {7, 95, 3}, nonrigid[] = {0, 25, 0};
  const char* files[] = {"duck_miq_4_param.obj", "duck_qc_8_param.obj", "fandisk_param.obj"};
  for (int i = 0; i < 3; ++i) {
    CAPTURE(files[i]);
    const Report r = certify_igm_file((dir / "igm" / files[i]).string());
    CHECK(r.check(4)->count("cones_off_integer") == exact[i]);
    CHECK(r.check(4)->count("nonrigid_ring_cones_off_integer") == nonrigid[i]);
  }
}
