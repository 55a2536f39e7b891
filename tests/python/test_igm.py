"""The Python module igm (python/igm_module.cpp), run by CTest python/pytest:
PYTHONPATH=BUILD/python python3 -m pytest tests/python."""
import threading
import time
import warnings
from fractions import Fraction

import numpy as np
import pytest

import igm


def square_torus(n):
    """The flat n x n torus split into 2 n^2 triangles, one UV row per corner with integer UVs:
    a valid IGM (every transition a translation by an integer vector)."""
    vid = lambda i, j: (j % n) * n + (i % n)  # noqa: E731
    V = np.array([[i, j, 0.0] for j in range(n) for i in range(n)])
    F, UV = [], []
    for j in range(n):
        for i in range(n):
            for tri in (((i, j), (i + 1, j), (i + 1, j + 1)), ((i, j), (i + 1, j + 1), (i, j + 1))):
                F.append([vid(a, b) for a, b in tri])
                UV.extend([a, b] for a, b in tri)
    F = np.array(F)
    return V, F, np.array(UV, dtype=float), np.arange(3 * len(F)).reshape(-1, 3)


def test_compute_on_a_generated_torus():
    V, F = igm.generate(1, 200)
    assert V.shape[1] == 3 and F.shape[1] == 3
    r = igm.compute(V, F, resolution=3, layout="spread")  # the topological layout: one square
    assert r["certified"] is True
    st = r["stats"]
    assert st["genus"] == 1 and st["input_vertices"] == len(V) and st["input_faces"] == len(F)
    assert st["layout_quads"] == 1 and st["quads"] == 9  # one layout quad, 3 x 3
    m = r["igm"]
    assert m["faces"].shape == (st["output_triangles"], 3)
    assert m["vertices"].shape == (st["output_vertices"], 3)
    assert m["uv"].shape == (st["output_triangles"], 3, 2)
    assert "uv_exact" not in m
    assert r["quads"]["quads"].shape == (9, 4)
    cert = r["certificate"]
    assert cert["igm"]["verdict"] == "valid" and cert["quad"]["verdict"] == "valid"
    assert cert["igm"]["mesh"]["genus"] == 1
    assert [s["stage"] for s in st["stages"]][0] == "topology"


def test_exact_uvs_are_the_rationals_the_doubles_round():
    V, F = igm.generate(2, 300, seed=3)
    r = igm.compute(V, F, exact=True)
    assert r["certified"]
    exact, uv = r["igm"]["uv_exact"], r["igm"]["uv"]
    assert exact.shape == uv.shape and exact.dtype == object
    for t in range(0, len(uv), 7):
        for c in range(3):
            for d in range(2):
                q = Fraction(exact[t, c, d])
                assert abs(float(q) - uv[t, c, d]) <= 1e-15 * max(1.0, abs(float(q)))
    # The certifier's own reading of the exact UVs (one row per corner) accepts them.
    T = len(r["igm"]["faces"])
    verdict = igm.certify(r["igm"]["vertices"], r["igm"]["faces"], exact.reshape(-1, 2),
                          np.arange(3 * T).reshape(-1, 3))
    assert verdict["valid"] and verdict["report"]["mesh"]["genus"] == 2


def test_options_map_and_unknown_or_mistyped_ones_raise_type_error():
    V, F = igm.generate(1, 200)
    assert igm.compute(V, F, resolution=5, layout="spread")["stats"]["quads"] == 25
    with pytest.raises(TypeError, match="unexpected keyword argument 'resolutoin'"):
        igm.compute(V, F, resolutoin=5)
    with pytest.raises(TypeError, match="option 'resolution'"):
        igm.compute(V, F, resolution="five")
    with pytest.raises(igm.Error) as e:
        igm.compute(V, F, resolution=-1)
    assert e.value.kind == "invalid_argument"
    assert isinstance(e.value, ValueError)


def test_bad_meshes_raise_igm_error_with_kind_and_elements():
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [0, -1, 0]], dtype=float)
    with pytest.raises(igm.Error) as e:  # three faces on edge (0, 1)
        igm.compute(V, np.array([[0, 1, 2], [1, 0, 3], [0, 1, 4]]))
    assert e.value.kind == "non_manifold_edge"
    assert e.value.elements == [0, 1, 2]  # the edge's faces
    V = V[:3]
    with pytest.raises(igm.Error) as e:
        igm.compute(V, np.array([[0, 1, 7]]))
    assert e.value.kind == "index_out_of_range" and e.value.elements == [0]
    with pytest.raises(igm.Error) as e:
        igm.compute(V[:, :2], np.array([[0, 1, 2]]))
    assert e.value.kind == "invalid_argument"


def test_a_non_manifold_error_says_how_to_go_on():
    # Two tetrahedra sharing vertex 0: a non-manifold vertex; split_nonmanifold=True cuts it apart
    # into two closed spheres, which the error says.
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [-1, 0, 0], [0, -1, 0], [0, 0, -1]], dtype=float)
    F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3], [0, 4, 5], [0, 6, 4], [0, 5, 6], [4, 6, 5]])
    with pytest.raises(igm.Error) as e:
        igm.compute(V, F)
    assert e.value.kind == "non_manifold_vertex" and e.value.elements == [0]
    assert "split_nonmanifold=True cuts its non-manifold vertices and edges apart: 2 surfaces" in str(e.value)
    with pytest.warns(UserWarning, match="cut 1 non-manifold vertex into one copy per fan"):
        r = igm.compute(V, F, split_nonmanifold=True, quality=False)
    assert r["certified"] and [s["genus"] for s in r["stats"]["surfaces"]] == [0, 0]


def test_certify_floats_strings_and_fractions():
    V, F, UV, FUV = square_torus(4)
    ok = igm.certify(V, F, UV, FUV)
    assert ok["valid"] and ok["verdict"] == "valid" and ok["report"]["mesh"]["genus"] == 1
    strings = [[str(int(u)), f"{int(v) * 3}/3"] for u, v in UV]
    assert igm.certify(V, F, strings, FUV)["valid"]
    # One corner moved by 1/3: the transitions across its edges are no longer integer.
    moved = [[Fraction(int(u)), Fraction(int(v))] for u, v in UV]
    moved[1][0] += Fraction(1, 3)
    bad = igm.certify(V, F, moved, FUV, max_witnesses=3)
    assert not bad["valid"] and bad["verdict"] == "invalid"
    transitions = [c for c in bad["report"]["checks"] if c["name"] == "transitions"][0]
    assert transitions["status"] == "fail" and 1 <= len(transitions["witnesses"]) <= 3
    with pytest.raises(igm.Error) as e:
        igm.certify(V, F, [["1/0", "0"]] * len(UV), FUV)
    assert e.value.kind == "parse"


def test_read_mesh(tmp_path):
    off = tmp_path / "tet.off"
    off.write_text("OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n")
    V, F = igm.read_mesh(str(off))
    assert V.shape == (4, 3) and F.shape == (4, 3)
    assert V[1].tolist() == [1.0, 0.0, 0.0]
    ply = tmp_path / "tet.ply"
    ply.write_text("ply\nformat ascii 1.0\nCreated by hand\nelement vertex 4\nproperty float x\nproperty float y\n"
                   "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
                   "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n")
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        V, F = igm.read_mesh(str(ply))
    assert [str(x.message) for x in w] == ["PLY header line 3 skipped (unknown keyword 'Created')"]
    quad = tmp_path / "q.obj"
    quad.write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n")
    V, F = igm.read_mesh(str(quad), validate=False)
    assert F == [[0, 1, 2, 3]]
    V, F = igm.read_mesh(str(quad))  # an open surface: triangulated
    assert V.shape == (4, 3) and F.shape == (2, 3)
    fin = tmp_path / "fin.obj"  # three faces on one edge: refused, the file named
    fin.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 -1 0\nf 1 2 3\nf 2 1 4\nf 1 2 5\n")
    with pytest.raises(igm.Error) as e:
        igm.read_mesh(str(fin))
    assert e.value.kind == "non_manifold_edge" and str(fin) in str(e.value)
    bad = tmp_path / "bad.off"
    bad.write_text("OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n")
    with pytest.raises(igm.Error) as e:
        igm.read_mesh(str(bad))
    assert e.value.kind == "parse" and e.value.elements == [4]  # the line


def test_compute_releases_the_gil():
    V, F = igm.generate(3, 8000, seed=2)
    done = {}

    def run():
        t0 = time.perf_counter()
        done["result"] = igm.compute(V, F)
        done["seconds"] = time.perf_counter() - t0

    worker = threading.Thread(target=run)
    last = time.perf_counter()
    worker.start()
    longest_gap = 0.0
    while worker.is_alive():  # this thread runs on while the worker computes: short gaps only
        now = time.perf_counter()
        longest_gap = max(longest_gap, now - last)
        last = now
    worker.join()
    assert done["result"]["certified"]
    assert done["seconds"] > 0.1
    assert longest_gap < done["seconds"] / 2


def test_sizes_layouts_and_the_quality_report():
    V, F = igm.generate(2, 600, seed=4)
    r = igm.compute(V, F, quads=800, layout="spread")
    assert r["certified"]
    st = r["stats"]
    assert abs(st["quads"] - 800) <= 200 and st["layout_quads"] == 20
    q = r["quality"]
    assert q["quads"]["quads"] == st["quads"] and q["igm"]["triangles"] == st["output_triangles"]
    assert -1.0 <= q["quads"]["sj_median"] <= 1.0
    k = igm.compute(V, F, layout="kite", map="affine", edge_length=1.0, quality=False)
    assert k["certified"] and k["quality"] is None and k["stats"]["layout_quads"] == 8
    assert st["layout"] == "spread" and st["layout_fallback"] is None
    f = igm.compute(V, F, quads=800)  # the default layout: the field one
    assert f["certified"] and f["stats"]["layout"] == "field" and f["stats"]["layout_fallback"] is None
    assert f["quality"]["quads"]["irregular_vertices"] >= 8  # a genus-2 field: at least 8 valence-5 cones
    with pytest.raises(igm.Error) as e:
        igm.compute(V, F, layout="round")
    assert e.value.kind == "invalid_argument"
    with pytest.raises(TypeError):
        igm.compute(V, F, quads="many")


def test_open_surfaces_and_several_components():
    # one triangle: a disk (its boundary split so that it has four corners), certified
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=float)
    r = igm.compute(V, np.array([[0, 1, 2]]), quads=50)
    assert r["certified"] is True
    assert r["certificate"]["quad"]["mesh"]["boundary_loops"] == 1
    # a generated genus-1 surface with two holes beside a torus: two surfaces, one output
    Va, Fa = igm.generate(1, 1500, seed=3, boundaries=2)
    Vb, Fb = igm.generate(1, 800)
    V = np.vstack([Va, Vb + [10.0, 0, 0]])
    F = np.vstack([Fa, Fb + len(Va)])
    r = igm.compute(V, F, quads=1200, smooth_iterations=5)
    assert r["certified"] is True
    assert [(s["genus"], s["boundary_loops"]) for s in r["stats"]["surfaces"]] == [(1, 2), (1, 0)]
    assert r["stats"]["quads"] == len(r["quads"]["quads"])
    mesh = r["certificate"]["quad"]["mesh"]
    assert mesh["boundary_loops"] == 2 and mesh["connected_components"] == 2
    # the certifier judges the merged IGM in boundary and components mode only
    T = len(r["igm"]["faces"])
    args = (r["igm"]["vertices"], r["igm"]["faces"], r["igm"]["uv"].reshape(-1, 2), np.arange(3 * T).reshape(-1, 3))
    assert igm.certify(*args, boundary=True, components=True)["valid"]
    assert not igm.certify(*args)["valid"]
    assert not igm.certify(*args, boundary=True)["valid"]


def test_every_surface_gets_its_floor():
    # A genus-3 surface beside a sphere 100 times smaller: the sphere's share of 600 quads by area
    # is far below the 2 x 2 grid it needs (2 x 1 would be 4 quads on 6 vertices with a double edge).
    Va, Fa = igm.generate(3, 800, seed=2)
    Vb, Fb = igm.generate(0, 60, seed=5)
    V = np.vstack([Va, 0.01 * Vb + [10.0, 0, 0]])
    F = np.vstack([Fa, Fb + len(Va)])
    r = igm.compute(V, F, quads=600, smooth_iterations=3, quality=False, layout="spread")
    assert r["certified"] is True
    small = r["stats"]["surfaces"][1]
    assert small["genus"] == 0 and small["raised_by_floor"] and small["quads"] == small["floor_quads"] == 2
    assert small["quads_asked"] < 2 and "at the floor of 2 quads" in small["floor_note"]
    assert r["stats"]["raised_by_floor"] and r["stats"]["quads_asked"] == 600
    assert r["stats"]["quads"] == len(r["quads"]["quads"])
    # One surface: a resolution below the torus's floor (3 along its two sides) is raised to it.
    V, F = igm.generate(1, 300)
    t = igm.compute(V, F, resolution=1, smooth_iterations=3, quality=False, layout="spread")
    assert t["certified"] and t["stats"]["quads"] == 9 and t["stats"]["raised_by_floor"]
    assert t["stats"]["quad_defects"] == ""


def test_smoothing_options():
    V, F = igm.generate(2, 1500)
    plain = igm.compute(V, F, quads=800, smooth=False)
    smoothed = igm.compute(V, F, quads=800, smooth_iterations=10, smooth_seconds=0)
    assert plain["certified"] and smoothed["certified"]
    assert plain["stats"]["smooth_iterations"] == 0
    assert 0 < smoothed["stats"]["smooth_iterations"] <= 10
    assert smoothed["quality"]["igm"]["symmetric_dirichlet"] < plain["quality"]["igm"]["symmetric_dirichlet"]
    assert smoothed["stats"]["smooth_stop"] in ("iteration_budget", "small_decrease", "stalled", "converged")
    # the same bytes for any thread count; stages with their CPU time
    one = igm.compute(V, F, quads=800, smooth_iterations=10, threads=1)
    two = igm.compute(V, F, quads=800, smooth_iterations=10, threads=2)
    assert (one["igm"]["uv"] == two["igm"]["uv"]).all() and (one["quads"]["quads"] == two["quads"]["quads"]).all()
    assert all(s["cpu_seconds"] >= 0 for s in one["stats"]["stages"])
    with pytest.raises(igm.Error):
        igm.compute(V, F, quads=800, threads=-1)


def unit_cube():
    V = np.array([[i & 1, (i >> 1) & 1, (i >> 2) & 1] for i in range(8)], dtype=float)
    F = []
    for a, b, c, d in ((0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)):
        F += [[a, b, c], [a, c, d]]
    return V, np.array(F)


def test_features_are_measured_and_bad_feature_options_raise():
    V, F = unit_cube()
    r = igm.compute(V, F, quads=200)
    assert r["certified"]
    f = r["quality"]["features"]
    assert f["edges"] == 12 and f["curves"] == 12 and f["corners"] == 8 and f["length"] == 12
    assert 0 <= f["covered_fraction"] <= 1
    # At 200 quads on a unit cube (quad edge about 0.17) every crease (length 1) is shorter than
    # 6 quad edges: measured, but a layout would not follow them; feature_min_quads=0 follows all.
    assert f["short_edges"] == 12
    z = igm.compute(V, F, quads=200, feature_min_quads=0)
    assert z["certified"] and z["quality"]["features"]["short_edges"] == 0
    n = igm.compute(V, F, quads=200, no_features=True)
    assert n["certified"] and n["quality"]["features"]["edges"] == 0
    # One user edge (a face diagonal of the triangulation) with detection off.
    u = igm.compute(V, F, quads=200, no_features=True, features=np.array([[0, 3]]))
    assert u["quality"]["features"]["edges"] == 1
    with pytest.raises(igm.Error) as e:
        igm.compute(V, F, features=np.array([[0, 7]]))  # opposite corners: not an edge
    assert e.value.kind == "invalid_argument" and "(0, 7)" in str(e.value)
    with pytest.raises(igm.Error) as e:
        igm.compute(V, F, feature_angle=-1.0)
    assert e.value.kind == "invalid_argument"
