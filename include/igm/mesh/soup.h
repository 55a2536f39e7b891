#pragma once
// A polygon soup as read from a file: positions and polygons (CSR layout), before validation.
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include "igm/exact/predicates.h"

namespace igm {

struct PolygonSoup {
  std::vector<Vec3d> positions;
  std::vector<std::int64_t> corners;           // vertex ids, polygon after polygon (may be out of range before validation)
  std::vector<std::size_t> face_begin = {0};   // polygon f is corners[face_begin[f] .. face_begin[f+1])
  std::vector<std::string> warnings;           // what a reader skipped (validation passes them on)

  std::size_t num_faces() const { return face_begin.size() - 1; }
  std::size_t face_size(std::size_t f) const { return face_begin[f + 1] - face_begin[f]; }
  void add_face(std::initializer_list<std::int64_t> vs) {
    corners.insert(corners.end(), vs);
    face_begin.push_back(corners.size());
  }
  template <class It>
  void add_face(It first, It last) {
    corners.insert(corners.end(), first, last);
    face_begin.push_back(corners.size());
  }
};

}  // namespace igm
