"""igm: certified Integer Grid Maps of closed orientable triangle meshes.

compute(V, F, **options)  a certified IGM, its quad mesh, the certificate and statistics
certify(V, F, UV, FUV)     the independent certifier's verdict on anyone's IGM
read_mesh(path)            (V, F) of an OBJ, OFF, PLY or STL file
generate(genus, faces)     (V, F) of a generated closed mesh

Bad input raises igm.Error (a ValueError) with .kind (e.g. "boundary") and .elements (ids).
"""


class Error(ValueError):
    """Invalid input or options (igm::Error): .kind names the problem (igm::ErrorKind, e.g.
    "non_manifold_edge"), .elements lists the offending ids (vertices, faces or a line)."""

    def __init__(self, message, kind="", elements=()):
        super().__init__(message)
        self.kind = kind
        self.elements = list(elements)


from ._igm import __version__, certify, compute, generate, read_mesh  # noqa: E402

__all__ = ["Error", "compute", "certify", "read_mesh", "generate", "__version__"]
