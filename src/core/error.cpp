#include "igm/core/error.h"

namespace igm {

const char* to_string(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::Io: return "io";
    case ErrorKind::Parse: return "parse";
    case ErrorKind::TooLarge: return "too_large";
    case ErrorKind::Empty: return "empty";
    case ErrorKind::NoFaces: return "no_faces";
    case ErrorKind::IndexOutOfRange: return "index_out_of_range";
    case ErrorKind::NonFinite: return "non_finite";
    case ErrorKind::RepeatedVertex: return "repeated_vertex";
    case ErrorKind::NonManifoldEdge: return "non_manifold_edge";
    case ErrorKind::NonManifoldVertex: return "non_manifold_vertex";
    case ErrorKind::Boundary: return "boundary";
    case ErrorKind::SeveralComponents: return "several_components";
    case ErrorKind::NonOrientable: return "non_orientable";
    case ErrorKind::InvalidArgument: return "invalid_argument";
    case ErrorKind::Unsupported: return "unsupported";
    case ErrorKind::Internal: return "internal";
  }
  return "unknown";
}

}  // namespace igm
