#pragma once
// The flat n x n square torus as an IGM, shared by the output and smooth tests: vertex (i, j) at
// (i, j, 0), each unit square split along its diagonal into two triangles, every corner UV the
// integer point of its square's corner (so corners on the seams u = n, v = n differ from the other
// copies of their vertex by integer translations; no rotations, no cones: a valid IGM).
#include "igm/output/igm_mesh.h"

namespace igm_test {

inline igm::IgmMesh square_torus(int n) {
  using igm::Point2q;
  using igm::Rational;
  igm::IgmMesh m;
  auto id = [n](int i, int j) { return ((j % n + n) % n) * n + ((i % n + n) % n); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) m.positions.push_back({double(i), double(j), 0});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      auto P = [](int a, int b) { return Point2q{Rational(a), Rational(b)}; };
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.corner_uv.push_back({P(i, j), P(i + 1, j), P(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      m.corner_uv.push_back({P(i, j), P(i + 1, j + 1), P(i, j + 1)});
    }
  return m;
}

}  // namespace igm_test
