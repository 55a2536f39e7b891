#pragma once
// The curvature guide of a cross field: per face, the principal curvature directions raised to
// the 4th power (Knoeppel, Crane, Pinkall, Schroeder 2013, "Globally optimal direction fields",
// alignment with a guidance field), weighted by how strongly the surface bends more one way than
// the other.
//
// Per interior edge e its bending tensor beta_e |e| (e_hat e_hat^T), beta_e the signed dihedral
// angle (the normal-cycle curvature measure, Cohen-Steiner & Morvan 2003; boundary edges bend
// nothing); per face f the sum T_f over the edges with an end at one of f's corners (each once),
// restricted to f's plane and divided by the area of the faces around f's corners (summed per
// corner). Its traceless part in f's frame (face_frames.h) is the complex number
// t_f = ((T_xx - T_yy) + 2 i T_xy) / 2 = |t_f| exp(2 i phi_f): phi_f a principal direction (either
// one: they differ by a quarter turn), |t_f| the anisotropy |k1 - k2| / 2 of the averaged
// curvature. The guide is q_f = t_f^2 / |t_f| = |t_f| exp(4 i phi_f) (0 where t_f = 0): umbilic
// and flat regions give no guidance. A field aligned with q (exp(4 i theta) = q / |q|, the
// paper's representation) is aligned with the principal directions where they are defined.
#include <complex>
#include <vector>

#include "igm/field/face_frames.h"

namespace igm {

/// The curvature guide q_f per face (see the top of the file). Pre: frames is
/// face_frames(mesh, positions). Deterministic (sums in half-edge and face order); cost O(F)
/// (per-vertex tensors, then three per face).
std::vector<std::complex<double>> curvature_cross_guide(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                                                        const FaceFrames& frames);

}  // namespace igm
