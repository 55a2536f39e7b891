#pragma once
// Combinatorics of a closed, oriented triangle mesh as half-edge index arrays.
// Face f owns half-edges 3f, 3f+1, 3f+2 (counter-clockwise); half-edge h runs from
// origin(h) to origin(next(h)); twin(h) runs the other way in the neighbouring face.
// Built with allow_boundary, a mesh may have boundary half-edges: twin(h) == -1 (the surface lies
// to their left); the rest of the class then assumes nothing about them (only from_triangles,
// the accessors and next_around_origin, which returns -1 across the boundary, are meant for it).
// Numbers (positions, UVs) live in separate arrays indexed by vertex or half-edge (corner).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace igm {

class TriMesh {
 public:
  TriMesh() = default;

  /// Builds from triangles over vertices 0..num_vertices-1. Pre: a closed, edge-manifold,
  /// consistently oriented surface (validate first: see mesh/validate.h); throws
  /// igm::Error(NonManifoldEdge/Boundary/IndexOutOfRange) if an edge has no unique twin.
  /// Vertices used by no face are allowed (they get vertex_halfedge = -1). Cost O(F log F).
  /// With allow_boundary an edge with one face is a boundary half-edge (twin -1) instead of an
  /// error, and a vertex with one leaving boundary half-edge gets it as its vertex_halfedge (the
  /// first corner of its fan, counter-clockwise); every other vertex as without the option.
  static TriMesh from_triangles(int num_vertices, const std::vector<std::array<int, 3>>& triangles,
                                bool allow_boundary = false);

  /// Builds from half-edge arrays (face f owns 3f, 3f+1, 3f+2): origin per half-edge over
  /// 0..num_vertices-1 and twin per half-edge, for a builder that has kept the pairing (edge
  /// collapses), where from_triangles would find it again by sorting. Each vertex's
  /// vertex_halfedge is its last outgoing half-edge, as from_triangles sets it, so that both give
  /// the same mesh for the same triangles. Checks that twin is an involution without fixed points
  /// and that twins run between the same two vertices in opposite directions; throws
  /// igm::Error(Internal) naming the half-edge if not (the caller's bookkeeping is broken), or
  /// igm::Error(IndexOutOfRange) for an origin out of range. Does not look for an edge with
  /// more than two faces paired as two edges. Cost O(F).
  static TriMesh from_halfedges(int num_vertices, std::vector<int> origin, std::vector<int> twin);

  int num_vertices() const { return static_cast<int>(out_.size()); }
  int num_faces() const { return static_cast<int>(origin_.size() / 3); }
  int num_halfedges() const { return static_cast<int>(origin_.size()); }
  int num_edges() const { return num_halfedges() / 2; }  // closed mesh: two half-edges per edge

  static int face(int h) { return h / 3; }
  static int next(int h) { return h % 3 == 2 ? h - 2 : h + 1; }
  static int prev(int h) { return h % 3 == 0 ? h + 2 : h - 1; }
  static int halfedge(int f, int i) { return 3 * f + i; }

  int origin(int h) const { return origin_[h]; }
  int target(int h) const { return origin_[next(h)]; }
  int twin(int h) const { return twin_[h]; }
  /// One half-edge leaving v, or -1 if v is isolated.
  int vertex_halfedge(int v) const { return out_[v]; }
  /// The three vertices of face f in counter-clockwise order.
  std::array<int, 3> face_vertices(int f) const {
    return {origin_[3 * f], origin_[3 * f + 1], origin_[3 * f + 2]};
  }
  /// Rotates around origin(h): the next outgoing half-edge counter-clockwise.
  int next_around_origin(int h) const { return twin_[prev(h)]; }
  /// Number of half-edges leaving v (its valence). Cost O(valence).
  int valence(int v) const;
  /// The half-edge from a to b, or -1. Cost O(valence(a)).
  int find_halfedge(int a, int b) const;

  /// Splits the edge of h (both faces) with a new vertex; returns the new vertex id.
  /// After the call h runs origin(h) -> new vertex; twin(h) runs back. Two faces are added.
  /// Amortized O(1). New face ids are num_faces()-2 and num_faces()-1.
  int split_edge(int h);

  /// Splits face f into three around a new vertex; returns the new vertex id. Amortized O(1).
  int split_face(int f);

  /// Room for `vertices` vertices and `faces` faces in all, so that splits up to those counts do
  /// not reallocate. O(the new capacity) when it grows.
  void reserve(int vertices, int faces) {
    out_.reserve(static_cast<std::size_t>(vertices));
    origin_.reserve(3 * static_cast<std::size_t>(faces));
    twin_.reserve(3 * static_cast<std::size_t>(faces));
  }

  /// Appends an isolated vertex (used by builders); returns its id.
  int add_vertex() {
    out_.push_back(-1);
    return num_vertices() - 1;
  }

  /// Checks every structural invariant (twin involution, origins consistent, vertex
  /// half-edges leave their vertex, each vertex has one fan). Returns an empty string if fine,
  /// else a description of the first violation. Cost O(F). For tests and debug checks.
  std::string check_invariants() const;

  const std::vector<int>& origins() const { return origin_; }
  const std::vector<int>& twins() const { return twin_; }

 private:
  void link(int a, int b) {
    twin_[a] = b;
    twin_[b] = a;
  }
  std::vector<int> origin_;  // per half-edge
  std::vector<int> twin_;    // per half-edge
  std::vector<int> out_;     // per vertex
};

}  // namespace igm
