#pragma once
// The curvature guide of a cross field: per face, the principal curvature directions raised to
// the 4th power (Knoeppel, Crane, Pinkall, Schroeder 2013, "Globally optimal direction fields",
// alignment with a guidance field), weighted by how strongly the surface bends more one way than
// the other.
//
// Per edge e of the surface its bending beta_e |e| (e_hat (x) e_hat), beta_e the signed dihedral
// angle (Cohen-Steiner & Morvan 2003, the normal-cycle curvature measure; 0 on a boundary edge);
// per face f the sum over the edges with an end at one of f's corners (each edge once), its
// traceless part written in f's frame (face_frames.h) as the complex number
// t_f = sum beta_e |e| exp(2 i phi_e) / (2 * area of those edges' faces), phi_e the angle of e
// projected onto f's plane. t_f = |t_f| exp(2 i phi_f) with phi_f a principal direction (either
// one: they differ by a quarter turn), |t_f| the anisotropy |k1 - k2| / 2 of the averaged
// curvature. The guide is q_f = t_f^2 / |t_f| = |t_f| exp(4 i phi_f) (0 where t_f = 0): umbilic and
// flat regions give no guidance. The paper's representation of a cross field is exp(4 i theta);
// a field aligned with q is aligned with the principal directions where they are well defined.
#include <complex>
#include <vector>

#include "igm/field/face_frames.h"

namespace igm {

/// The curvature guide q_f per face (see the top of the file). Pre: frames is
/// face_frames(mesh, positions). Deterministic (edges summed in half-edge order); cost
/// O(sum over faces of the edges around their corners), about 36 F on a regular mesh.
std::vector<std::complex<double>> curvature_cross_guide(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                                                        const FaceFrames& frames);

}  // namespace igm
