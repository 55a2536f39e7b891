// The certifier's own OBJ reader: exact vt, index forms, and errors naming the line.
#include <doctest/doctest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "certify/certify.h"
#include "certify/obj.h"

using namespace igm::certify;

namespace {
const char* kTetra =
    "# tetrahedron, one vt per corner\n"
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
    "vt 0 0\nvt 1 0\nvt 0 1\n";

std::string err_of(const std::string& text) { return read_obj(text).error; }
std::int64_t line_of(const std::string& text) { return read_obj(text).error_line; }
}  // namespace

TEST_CASE("obj: index forms, negative indices, comments, forward references") {
  const std::string text = std::string(kTetra) +
                           "f 1/1 2/2 3/3 # trailing comment\n"
                           "f -4/-3/1 -1/-2/1 -3/-1/1\n"
                           "vn 0 0 1\n"
                           "f 2/1 4/2 3/3\n"
                           "g group\ns off\no name\nusemtl m\n"
                           "f 5/1 1/1 2/1\n"  // forward reference to a vertex defined below
                           "v 2 2 2\n";
  ObjReadResult r = read_obj(text);
  INFO(r.error);
  REQUIRE(r.ok);
  CHECK(r.mesh.num_vertices == 5);
  CHECK(r.mesh.num_faces() == 4);
  CHECK(r.mesh.corner_vertex[3] == 0);
  CHECK(r.mesh.corner_vertex[4] == 3);
  CHECK(r.mesh.corner_vertex[5] == 1);
  CHECK(r.mesh.corner_uv[3] == 0);
  CHECK(r.mesh.corner_uv[5] == 2);
  CHECK(r.mesh.corner_vertex[9] == 4);
  CHECK(r.mesh.face_line[3] == 17);
}

TEST_CASE("obj: vt read exactly, p/q accepted, w ignored") {
  ObjReadResult r = read_obj("vt 0.1 -2.5e-3 0.7\nvt 1/3 -22/7\n");
  REQUIRE(r.ok);
  CHECK(r.mesh.uv[0][0] == mpq_class(1, 10));
  CHECK(r.mesh.uv[0][1] == mpq_class(-1, 400));
  CHECK(r.mesh.uv[1][0] == mpq_class(1, 3));
  CHECK(r.mesh.uv[1][1] == mpq_class(-22, 7));
}

TEST_CASE("obj: errors name the line") {
  const std::string t = kTetra;  // 8 lines
  CHECK(line_of(t + "f 1/1 2/2 9/3\n") == 9);
  CHECK(err_of(t + "f 1/1 2/2 9/3\n").find("vertex index 9 out of range") != std::string::npos);
  CHECK(line_of(t + "f 1/1 2/2 3/4\n") == 9);
  CHECK(line_of(t + "f 0/1 2/2 3/3\n") == 9);
  CHECK(line_of(t + "f -5/1 2/2 3/3\n") == 9);
  CHECK(line_of(t + "f 1/1 2/2\n") == 9);
  CHECK(line_of(t + "f 1/1 2/2 3/x\n") == 9);
  CHECK(line_of(t + "f 1/1/1/1 2/2 3/3\n") == 9);
  CHECK(line_of(t + "f 1/1/1 2/2 3/3\n") == 9);  // no vn defined
  CHECK(line_of(t + "f 99999999999/1 2/2 3/3\n") == 9);
  CHECK(line_of(t + "vt nan 0\n") == 9);
  CHECK(line_of(t + "vt inf 0\n") == 9);
  CHECK(line_of(t + "vt 1\n") == 9);
  CHECK(line_of(t + "vt 1 2 3 4\n") == 9);
  CHECK(line_of(t + "vt 1/0 2\n") == 9);
  CHECK(line_of(t + "v 1 2\n") == 9);
  CHECK(line_of(t + "v 1 2 NaN\n") == 9);
  CHECK(line_of(t + "vn 1 2\n") == 9);
  CHECK(line_of(t + "curv 0 1 2\n") == 9);
  CHECK(line_of(t + "\x01\x02\n") == 9);
  CHECK(line_of("v 1 2 3\r\nv 1 2 3x\r\n") == 2);
}

TEST_CASE("obj: IGM mode needs triangles with a UV on every corner") {
  const std::string t = kTetra;
  Report r = certify_igm_text(t + "f 1/1 2/2 3/3 4/1\n");
  CHECK(r.verdict == Verdict::Unreadable);
  CHECK(r.error_line == 9);
  CHECK(r.error.find("4 corners") != std::string::npos);
  r = certify_igm_text(t + "f 1 2 3\n");
  CHECK(r.verdict == Verdict::Unreadable);
  CHECK(r.error.find("without a UV") != std::string::npos);
  r = certify_igm_text(t);
  CHECK(r.verdict == Verdict::Unreadable);
  CHECK(r.error == "no faces");
  r = certify_igm_text("");
  CHECK(r.verdict == Verdict::Unreadable);
  r = certify_igm_file("/nonexistent/dir/x.obj");
  CHECK(r.verdict == Verdict::Unreadable);
  CHECK(r.error.find("cannot read") != std::string::npos);
}

TEST_CASE("obj: a valid tetrahedron IGM from text is judged, not refused") {
  // faces of a tetrahedron with one UV triple per face: closed, genus 0, but the transitions
  // between these arbitrary charts are not rigid.
  const std::string t = std::string(kTetra) + "f 1/1 3/2 2/3\nf 1/1 2/2 4/3\nf 2/1 3/2 4/3\nf 1/1 4/2 3/3\n";
  Report r = certify_igm_text(t);
  CHECK(r.verdict == Verdict::Invalid);
  REQUIRE(r.genus.has_value());
  CHECK(*r.genus == 0);
  CHECK(r.check(1)->passed());
}

// Regression (issue 40): OBJ files with backslash continuations were refused ("bad vertex index
// in '\'"). The smallest case: one face split over three lines, LF and CRLF, spaces after the
// backslash, a continued vt.
TEST_CASE("obj: backslash line continuations, also before CRLF") {
  for (const std::string eol : {"\n", "\r\n"}) {
    CAPTURE(eol.size());
    const std::string text = "v 0 0 0" + eol + "v 1 0 0" + eol + "v 0 1 0" + eol + "v 0 0 1" + eol +
                             "vt 1/3 \\" + eol + "  -22/7" + eol + "f 1/1 \\" + eol + "2/1\\  \t" + eol +
                             "  3/1" + eol + "f 1 3 4" + eol;
    const ObjReadResult r = read_obj(text);
    INFO(r.error);
    REQUIRE(r.ok);
    REQUIRE(r.mesh.uv.size() == 1);
    CHECK(r.mesh.uv[0][0] == mpq_class(1, 3));
    CHECK(r.mesh.uv[0][1] == mpq_class(-22, 7));
    REQUIRE(r.mesh.num_faces() == 2);
    CHECK(r.mesh.corner_vertex == std::vector<int>{0, 1, 2, 0, 2, 3});
    CHECK(r.mesh.corner_uv == std::vector<int>{0, 0, 0, -1, -1, -1});
    CHECK(r.mesh.face_line == std::vector<std::int64_t>{7, 10});  // a statement's first line
  }
  // A backslash inside a comment continues nothing: the next line is a statement of its own.
  ObjReadResult r = read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0 # C:\\models\\\nf 1 2 3\n");
  INFO(r.error);
  REQUIRE(r.ok);
  CHECK(r.mesh.num_faces() == 1);
  // A backslash at the very end of the file continues into nothing.
  CHECK(read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 \\").ok);
  // Still refused: a backslash that does not end its line, errors on the statement's first line.
  CHECK(line_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 \\ 2 3\n") == 4);
  CHECK(line_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 \\\n2 \\\n x\n") == 4);
}
