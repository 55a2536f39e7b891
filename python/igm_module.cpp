// The Python module igm._igm (pybind11), re-exported by python/igm/__init__.py: compute,
// certify, read_mesh, generate. The GIL is released while C++ computes; igm::Error becomes
// igm.Error (a ValueError) with .kind and .elements.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "certify/certify.h"
#include "certify/exact.h"
#include "igm/core/error.h"
#include "igm/exact/rational.h"
#include "igm/io/read_mesh.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"
#include "igm/mesh/validate_surfaces.h"
#include "igm/pipeline/pipeline.h"

namespace py = pybind11;
using namespace pybind11::literals;

namespace {

using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
using IndexArray = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;

// --- options: one line per PipelineOptions field ---
using Setter = std::function<void(igm::PipelineOptions&, py::handle)>;
template <class T>
Setter field(T igm::PipelineOptions::*member) {
  return [member](igm::PipelineOptions& o, py::handle v) { o.*member = v.cast<T>(); };
}
// A string option naming one of `names` (in the order of the enum's values).
template <class E>
Setter choice(E igm::PipelineOptions::*member, std::vector<std::pair<std::string, E>> names) {
  return [member, names](igm::PipelineOptions& o, py::handle v) {
    const std::string s = v.cast<std::string>();
    for (const auto& [name, value] : names)
      if (name == s) {
        o.*member = value;
        return;
      }
    std::string all;
    for (const auto& [name, value] : names) all += (all.empty() ? "" : ", ") + name;
    throw igm::Error(igm::ErrorKind::InvalidArgument, "'" + s + "' is not one of " + all);
  };
}
const std::map<std::string, Setter>& option_setters() {
  static const std::map<std::string, Setter> setters = {
      {"resolution", field(&igm::PipelineOptions::resolution)},
      {"edge_length", field(&igm::PipelineOptions::edge_length)},
      {"quads", field(&igm::PipelineOptions::quads)},
      {"layout", choice(&igm::PipelineOptions::layout, {{"field", igm::LayoutKind::Field},
                                                         {"spread", igm::LayoutKind::Spread},
                                                         {"kite", igm::LayoutKind::Kite},
                                                         {"paper", igm::LayoutKind::Paper}})},
      {"map", choice(&igm::PipelineOptions::patch_map,
                     {{"tutte", igm::PatchMapKind::Tutte}, {"affine", igm::PatchMapKind::Affine}})},
      {"quality", field(&igm::PipelineOptions::quality)},
      {"root", field(&igm::PipelineOptions::root)},
      {"normal_form", field(&igm::PipelineOptions::normal_form)},
      {"restarts", field(&igm::PipelineOptions::restarts)},
      {"cones", field(&igm::PipelineOptions::cones)},
      {"memory_limit_bytes", field(&igm::PipelineOptions::memory_limit_bytes)},
      {"max_witnesses", field(&igm::PipelineOptions::max_witnesses)},
      {"smooth", field(&igm::PipelineOptions::smooth)},
      {"smooth_iterations", field(&igm::PipelineOptions::smooth_iterations)},
      {"smooth_work", field(&igm::PipelineOptions::smooth_work)},
      {"smooth_seconds", field(&igm::PipelineOptions::smooth_seconds)},
      {"smooth_min_decrease", field(&igm::PipelineOptions::smooth_min_decrease)},
      {"smooth_stall_step", field(&igm::PipelineOptions::smooth_stall_step)},
      {"quality_distance", field(&igm::PipelineOptions::quality_distance)},
      {"threads", field(&igm::PipelineOptions::threads)},
      {"feature_angle", [](igm::PipelineOptions& o, py::handle v) { o.features.angle_degrees = v.cast<double>(); }},
      {"feature_min_quads", [](igm::PipelineOptions& o, py::handle v) { o.features.min_quad_edges = v.cast<double>(); }},
      {"no_features", [](igm::PipelineOptions& o, py::handle v) { o.features.enabled = !v.cast<bool>(); }},
      {"features", [](igm::PipelineOptions& o, py::handle v) {
         const IndexArray a = IndexArray::ensure(v);
         if (!a || a.ndim() != 2 || a.shape(1) != 2)
           throw igm::Error(igm::ErrorKind::InvalidArgument, "features must be an integer array of shape (k, 2)");
         const auto e = a.unchecked<2>();
         o.feature_edges.clear();
         for (py::ssize_t i = 0; i < e.shape(0); ++i) o.feature_edges.push_back({e(i, 0), e(i, 1)});
       }},
  };
  return setters;
}

// --- arrays ---
std::vector<igm::Vec3d> points_of(const DoubleArray& v) {
  if (v.ndim() != 2 || v.shape(1) != 3)
    throw igm::Error(igm::ErrorKind::InvalidArgument, "V must be an array of shape (n, 3)");
  const auto a = v.unchecked<2>();
  std::vector<igm::Vec3d> out(static_cast<std::size_t>(a.shape(0)));
  for (py::ssize_t i = 0; i < a.shape(0); ++i) out[static_cast<std::size_t>(i)] = {a(i, 0), a(i, 1), a(i, 2)};
  return out;
}

// Faces of shape (m, k), k >= 3 (the same polygon size for all).
igm::PolygonSoup soup_of(const DoubleArray& v, const IndexArray& f) {
  igm::PolygonSoup soup;
  soup.positions = points_of(v);
  if (f.ndim() != 2 || f.shape(1) < 3)
    throw igm::Error(igm::ErrorKind::InvalidArgument, "F must be an integer array of shape (m, k), k >= 3");
  const auto a = f.unchecked<2>();
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    for (py::ssize_t k = 0; k < a.shape(1); ++k) soup.corners.push_back(a(i, k));
    soup.face_begin.push_back(soup.corners.size());
  }
  return soup;
}

template <class T, std::size_t N>
py::array_t<T> array_of(const std::vector<std::array<T, N>>& rows) {
  py::array_t<T> out({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(N)});
  auto a = out.template mutable_unchecked<2>();
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t k = 0; k < N; ++k) a(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(k)) = rows[i][k];
  return out;
}

py::array_t<double> points_array(const std::vector<igm::Vec3d>& ps) {
  std::vector<std::array<double, 3>> rows(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) rows[i] = {ps[i].x, ps[i].y, ps[i].z};
  return array_of(rows);
}

py::object json_dict(const std::string& json) { return py::module_::import("json").attr("loads")(json); }

void warn_all(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings)
    if (PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 1) != 0) throw py::error_already_set();
}

// --- compute ---
py::dict stats_dict(const igm::PipelineStats& st) {
  py::list stages;
  for (const igm::StageEvent& e : st.stages)
    stages.append(py::dict("stage"_a = e.stage, "seconds"_a = e.seconds, "detail"_a = e.detail, "peak_mb"_a = e.peak_mb,
                           "cpu_seconds"_a = e.cpu_seconds));
  return py::dict("genus"_a = st.genus, "boundary_loops"_a = st.boundary_loops, "input_vertices"_a = st.input_vertices,
                  "input_faces"_a = st.input_faces, "refined_vertices"_a = st.refined_vertices,
                  "refined_faces"_a = st.refined_faces, "output_vertices"_a = st.output_vertices,
                  "output_triangles"_a = st.output_triangles, "layout_quads"_a = st.layout_quads, "quads"_a = st.quads,
                  "chords"_a = st.chords, "edge_length"_a = st.edge_length, "max_uv_bits"_a = st.max_uv_bits,
                  "smooth_iterations"_a = st.smooth.iterations, "smooth_stop"_a = igm::to_string(st.smooth.stop),
                  "layout"_a = st.layout,
                  "layout_fallback"_a = st.layout_fallback.empty() ? py::object(py::none()) : py::object(py::str(st.layout_fallback)),
                  "feature_walls"_a = st.feature_walls, "features_dropped"_a = st.features_dropped,
                  "floor_quads"_a = st.floor_quads, "quads_asked"_a = st.quads_asked,
                  "raised_by_floor"_a = st.raised_by_floor(), "floor_note"_a = igm::floor_note(st),
                  "quad_defects"_a = st.quad_defects, "stages"_a = stages);
}

// The outputs as NumPy arrays and dicts (one surface, or several merged).
py::dict result_dict(const igm::IgmMesh& igm, const igm::QuadMesh& quads, const igm::certify::Report& igm_report,
                     const igm::certify::Report& quad_report, const igm::IgmQuality& igm_quality,
                     const igm::QuadQuality& quad_quality, const igm::FeatureQuality& feature_quality, bool quality,
                     bool exact, py::dict stats,
                     const std::vector<std::string>& warnings) {
  const std::size_t nt = igm.triangles.size();
  py::array_t<double> uv({static_cast<py::ssize_t>(nt), py::ssize_t{3}, py::ssize_t{2}});
  auto u = uv.mutable_unchecked<3>();
  for (std::size_t t = 0; t < nt; ++t)
    for (py::ssize_t c = 0; c < 3; ++c) {
      const igm::Point2q& p = igm.corner_uv[t][static_cast<std::size_t>(c)];
      u(static_cast<py::ssize_t>(t), c, 0) = igm::to_double(p.x);
      u(static_cast<py::ssize_t>(t), c, 1) = igm::to_double(p.y);
    }
  py::dict igm_out("vertices"_a = points_array(igm.positions), "faces"_a = array_of(igm.triangles), "uv"_a = uv);
  if (exact) {
    py::array uv_exact(py::dtype("O"), {static_cast<py::ssize_t>(nt), py::ssize_t{3}, py::ssize_t{2}});
    auto* cells = static_cast<PyObject**>(uv_exact.mutable_data());
    for (std::size_t t = 0; t < nt; ++t)
      for (std::size_t c = 0; c < 3; ++c)
        for (std::size_t d = 0; d < 2; ++d) {
          const igm::Rational& q = d == 0 ? igm.corner_uv[t][c].x : igm.corner_uv[t][c].y;
          PyObject*& cell = cells[6 * t + 2 * c + d];
          Py_XDECREF(cell);
          cell = py::str(igm::to_string(q)).release().ptr();
        }
    igm_out["uv_exact"] = uv_exact;
  }
  const bool certified = igm_report.valid() && quad_report.valid();
  return py::dict("igm"_a = igm_out,
                  "quads"_a = py::dict("vertices"_a = points_array(quads.positions), "quads"_a = array_of(quads.quads)),
                  "certificate"_a = py::dict("igm"_a = json_dict(igm::certify::to_json(igm_report)),
                                             "quad"_a = json_dict(igm::certify::to_json(quad_report))),
                  "quality"_a = quality ? py::object(py::dict("igm"_a = json_dict(igm::to_json(igm_quality)),
                                                              "quads"_a = json_dict(igm::to_json(quad_quality)),
                                                              "features"_a = json_dict(igm::to_json(feature_quality))))
                                        : py::object(py::none()),
                  "certified"_a = certified, "stats"_a = stats, "warnings"_a = warnings);
}

py::dict compute(const DoubleArray& v, const IndexArray& f, const py::kwargs& kwargs) {
  igm::PipelineOptions options;
  bool exact = false;
  igm::SurfaceOptions surface_options;
  for (const auto& [k, value] : kwargs) {
    const std::string key = py::str(k);
    try {
      if (key == "exact") {
        exact = value.cast<bool>();
        continue;
      }
      if (key == "split_nonmanifold") {
        surface_options.split_nonmanifold = value.cast<bool>();
        continue;
      }
      const auto it = option_setters().find(key);
      if (it == option_setters().end())
        throw py::type_error("compute() got an unexpected keyword argument '" + key + "'");
      it->second(options, value);
    } catch (const py::cast_error&) {
      throw py::type_error("compute(): option '" + key + "' has the wrong type (" +
                           std::string(py::str(py::type::of(value).attr("__name__"))) + ")");
    }
  }
  const igm::PolygonSoup soup = soup_of(v, f);
  igm::SurfaceSet set;
  igm::ValidMesh mesh;
  igm::PipelineResult r;
  igm::SurfacesResult surfaces;
  bool several = false;  // open or several components: compute_igms and the merged outputs
  {
    py::gil_scoped_release release;
    try {
      set = igm::validate_surfaces(soup, surface_options);
    } catch (const igm::Error& e) {  // with how to go on, where split_nonmanifold would help
      const std::string hint = igm::split_nonmanifold_hint(soup, surface_options, e, "split_nonmanifold=True");
      if (hint.empty()) throw;
      throw igm::Error(e.kind(), e.message() + "; " + hint, e.elements());
    }
    several = set.components.size() != 1 || !set.components[0].boundary_loops.empty();
    if (several) {
      surfaces = igm::compute_igms(set, options);
    } else {
      mesh = igm::to_valid_mesh(set.components[0], set.warnings);
      r = igm::compute_igm(mesh, options);
    }
  }
  warn_all(set.warnings);
  if (!several)
    return result_dict(r.igm, r.quads, r.igm_report, r.quad_report, r.igm_quality, r.quad_quality, r.feature_quality, options.quality,
                       exact, stats_dict(r.stats), set.warnings);
  py::list per_surface;
  bool raised = false;
  for (const igm::PipelineResult& c : surfaces.components) {
    per_surface.append(stats_dict(c.stats));
    raised = raised || c.stats.raised_by_floor();
  }
  return result_dict(surfaces.igm, surfaces.quads, surfaces.igm_report, surfaces.quad_report, surfaces.igm_quality,
                     surfaces.quad_quality, surfaces.feature_quality, options.quality, exact,
                     py::dict("surfaces"_a = per_surface, "quads"_a = surfaces.quads_total,
                              "quads_asked"_a = surfaces.quads_asked, "raised_by_floor"_a = raised),
                     set.warnings);
}

// --- certify ---
// One UV coordinate, exactly: a str ("p/q" or a decimal), an int, a float (its exact value), or
// anything with numerator and denominator (fractions.Fraction).
mpq_class exact_of(py::handle x) {
  mpq_class q;
  std::string text;
  if (py::isinstance<py::str>(x)) {
    text = x.cast<std::string>();
  } else if (py::isinstance<py::float_>(x) || py::isinstance(x, py::module_::import("numpy").attr("floating"))) {
    const double d = x.cast<double>();
    if (!std::isfinite(d)) throw igm::Error(igm::ErrorKind::NonFinite, "a UV coordinate is not finite");
    return mpq_class(d);
  } else if (py::hasattr(x, "numerator") && py::hasattr(x, "denominator")) {
    text = std::string(py::str(x.attr("numerator"))) + "/" + std::string(py::str(x.attr("denominator")));
  } else {
    throw igm::Error(igm::ErrorKind::InvalidArgument, "a UV coordinate must be a str, int, float or Fraction");
  }
  if (!igm::certify::parse_exact(text, q))
    throw igm::Error(igm::ErrorKind::Parse, "not an exact number (decimal or p/q): '" + text + "'");
  return q;
}

py::dict certify(const DoubleArray& v, const IndexArray& f, const py::object& uv, const IndexArray& fuv,
                 std::size_t max_witnesses, bool boundary, bool components) {
  igm::certify::IgmInput in;
  in.num_vertices = static_cast<std::int64_t>(points_of(v).size());
  if (f.ndim() != 2 || f.shape(1) != 3) throw igm::Error(igm::ErrorKind::InvalidArgument, "F must have shape (m, 3)");
  if (fuv.ndim() != 2 || fuv.shape(0) != f.shape(0) || fuv.shape(1) != 3)
    throw igm::Error(igm::ErrorKind::InvalidArgument, "FUV must have the shape of F");
  // The UV table, exactly.
  std::vector<std::array<mpq_class, 2>> table;
  const py::array uv_array = py::array::ensure(uv);
  const char kind = uv_array ? uv_array.dtype().kind() : 'O';
  if (kind == 'f' || kind == 'i' || kind == 'u') {
    const DoubleArray d = DoubleArray::ensure(uv_array);
    if (d.ndim() != 2 || d.shape(1) != 2)
      throw igm::Error(igm::ErrorKind::InvalidArgument, "UV must have shape (k, 2)");
    const auto a = d.unchecked<2>();
    for (py::ssize_t i = 0; i < a.shape(0); ++i) {
      if (!std::isfinite(a(i, 0)) || !std::isfinite(a(i, 1)))
        throw igm::Error(igm::ErrorKind::NonFinite, "UV row " + std::to_string(i) + " is not finite", {i});
      table.push_back({mpq_class(a(i, 0)), mpq_class(a(i, 1))});
    }
  } else {
    for (py::handle row : uv) {
      const py::sequence pair = py::reinterpret_borrow<py::sequence>(row);
      if (py::len(pair) != 2) throw igm::Error(igm::ErrorKind::InvalidArgument, "UV rows must have 2 entries");
      table.push_back({exact_of(pair[0]), exact_of(pair[1])});
    }
  }
  const auto fa = f.unchecked<2>();
  const auto ta = fuv.unchecked<2>();
  for (py::ssize_t t = 0; t < fa.shape(0); ++t) {
    std::array<int, 3> face{};
    for (py::ssize_t c = 0; c < 3; ++c) {
      face[static_cast<std::size_t>(c)] = static_cast<int>(fa(t, c));
      const std::int64_t k = ta(t, c);
      if (k < 0 || k >= static_cast<std::int64_t>(table.size()))
        throw igm::Error(igm::ErrorKind::IndexOutOfRange, "FUV row " + std::to_string(t) + " indexes no UV row", {t});
      in.corner_uv.push_back(table[static_cast<std::size_t>(k)]);
    }
    in.faces.push_back(face);
  }
  igm::certify::Options options;
  options.max_witnesses = max_witnesses;
  options.allow_boundary = boundary;
  options.allow_components = components;
  igm::certify::Report report;
  {
    py::gil_scoped_release release;
    report = igm::certify::certify_igm(std::move(in), options);
  }
  return py::dict("valid"_a = report.valid(), "verdict"_a = igm::certify::to_string(report.verdict),
                  "report"_a = json_dict(igm::certify::to_json(report)));
}

// --- meshes ---
py::tuple read_mesh(const std::string& path, bool validate) {
  igm::PolygonSoup soup;
  std::vector<igm::Vec3d> positions;  // validated: the surfaces' vertices and triangles, one after the other
  std::vector<std::array<int, 3>> tris;
  std::vector<std::string> warnings;
  {
    py::gil_scoped_release release;
    soup = igm::read_soup(std::filesystem::path(path));
    if (validate) {
      try {
        const igm::SurfaceSet set = igm::validate_surfaces(soup);
        for (const igm::SurfaceComponent& c : set.components) {
          const int base = static_cast<int>(positions.size());
          positions.insert(positions.end(), c.positions.begin(), c.positions.end());
          for (const auto& t : c.triangles) tris.push_back({t[0] + base, t[1] + base, t[2] + base});
        }
        warnings = set.warnings;
      } catch (const igm::Error& e) {
        throw igm::with_path(e, path);
      }
    }
  }
  if (!validate) {
    warn_all(soup.warnings);
    py::list faces;
    const auto corner = [&](std::size_t k) { return soup.corners.begin() + static_cast<std::ptrdiff_t>(k); };
    for (std::size_t i = 0; i < soup.num_faces(); ++i)
      faces.append(py::cast(std::vector<std::int64_t>(corner(soup.face_begin[i]), corner(soup.face_begin[i + 1]))));
    return py::make_tuple(points_array(soup.positions), faces);
  }
  warn_all(warnings);
  return py::make_tuple(points_array(positions), array_of(tris));
}

py::tuple generate(int genus, std::int64_t faces, std::uint64_t seed, int boundaries) {
  igm::GenerateOptions g;
  g.genus = genus;
  g.faces = faces;
  g.seed = seed;
  g.boundaries = boundaries;
  igm::SurfaceSet set;
  {
    py::gil_scoped_release release;
    set = igm::validate_surfaces(igm::generate_mesh(g));
  }
  const igm::SurfaceComponent& c = set.components.at(0);
  return py::make_tuple(points_array(c.positions), array_of(c.triangles));
}

}  // namespace

PYBIND11_MODULE(_igm, m) {
  m.doc() = "igm: certified Integer Grid Maps (the C++ library igm::core through pybind11)";
  m.attr("__version__") = IGM_VERSION;
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const igm::Error& e) {
      const py::object cls = py::module_::import("igm").attr("Error");
      const py::object err = cls(e.what(), igm::to_string(e.kind()), e.elements());
      PyErr_SetObject(cls.ptr(), err.ptr());
    }
  });
  m.def("compute", &compute, "V"_a, "F"_a,
        "compute(V, F, **options) -> dict: a certified IGM of the orientable mesh (V: (n, 3) floats,\n"
        "F: (m, k) vertex ids, k >= 3), closed or open (boundaries on integer isolines), one or several\n"
        "components (one IGM each, merged; stats['surfaces'] per surface). Options: quads, edge_length,\n"
        "resolution, layout ('field', the default, falling back to 'spread'; 'spread', 'kite', 'paper'), map ('tutte', 'affine'), smooth, smooth_iterations,\n"
        "smooth_min_decrease, smooth_stall_step, smooth_seconds, quality, quality_distance, root, normal_form,\n"
        "restarts, cones, memory_limit_bytes, max_witnesses, feature_angle (degrees, default 35),\n"
        "feature_min_quads (detected chains shorter than this many quad edges not followed, default 6), no_features,\n"
        "features (a (k, 2) int array of vertex-id pairs, more feature edges; measured in\n"
        "result['quality']['features'], followed by the field layout), threads (0: all cores; the outputs are the same\n"
        "for any count) (igm::PipelineOptions), split_nonmanifold (cut\n"
        "non-manifold elements apart first), exact (also the UVs as 'p/q' strings).\n"
        "Returns {'igm': {'vertices', 'faces', 'uv' (t, 3, 2) [, 'uv_exact']}, 'quads': {'vertices', 'quads'},\n"
        "'certificate': {'igm', 'quad'} (the certifier's JSON), 'certified', 'stats', 'warnings'}.\n"
        "Raises igm.Error for bad input or options, TypeError for an unknown option. Releases the GIL.");
  m.def("certify", &certify, "V"_a, "F"_a, "UV"_a, "FUV"_a, "max_witnesses"_a = 20, "boundary"_a = false,
        "components"_a = false,
        "certify(V, F, UV, FUV) -> {'valid', 'verdict', 'report'}: the independent certifier on anyone's IGM:\n"
        "triangles F (m, 3), UV (k, 2) floats (taken exactly) or str/Fraction values (e.g. '1/3'), FUV (m, 3)\n"
        "rows of UV per face corner; boundary=True: surfaces with boundary (every boundary edge on an integer\n"
        "isoline), components=True: several components. Releases the GIL.");
  m.def("read_mesh", &read_mesh, "path"_a, "validate"_a = true,
        "read_mesh(path, validate=True) -> (V, F): OBJ, OFF, PLY or STL; validated and triangulated (F: (m, 3);\n"
        "open surfaces and several components one after the other),\n"
        "repairs and skipped lines as warnings; validate=False: the file's polygons as a list of lists.");
  m.def("generate", &generate, "genus"_a, "faces"_a = 2000, "seed"_a = 1, "boundaries"_a = 0,
        "generate(genus, faces=2000, seed=1, boundaries=0) -> (V, F): a generated mesh of that genus, closed\n"
        "or with that many boundary loops.");
}
