// SPDX-License-Identifier: MIT
// Model: pieces built from numpy arrays (without the GIL), stats and read-only views
// of the stored meshes.
#include <pybind11/stl.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bindings.h"

namespace scpy {
namespace {

/// A str or os.PathLike as a path; None as no cache. Anything else is a TypeError.
std::string pathOf(const py::object& path) {
  if (path.is_none()) return {};
  const py::object p = py::module_::import("os").attr("fspath")(path);
  if (!py::isinstance<py::str>(p)) throw py::type_error("cache file: a str or os.PathLike path");
  return p.cast<std::string>();
}

sc::PiecePtr build(sc::ModelKind kind, sc::MeshData mesh, const std::string& cache_file,
                   int threads) {
  sc::BuildOptions options;
  options.cache_file = cache_file;
  options.threads = threads;
  sc::Result<sc::PiecePtr> piece = [&] {
    py::gil_scoped_release release;
    return sc::buildPiece(kind, std::move(mesh), options);
  }();
  if (!piece.hasValue()) check(piece.status());
  if (!piece.status().ok()) {
    // A cache file that could not be written: the piece is good, say so and go on.
    PyErr_WarnEx(py::module_::import("smartcollision").attr("CacheFileWarning").ptr(),
                 piece.status().message().c_str(), 2);
  }
  return piece.value();
}

PyModel fromPieces(const py::sequence& pieces, sc::ModelKind kind, const py::object& cache_files,
                   int threads) {
  std::vector<sc::PiecePtr> built;
  for (size_t i = 0; i < py::len(pieces); ++i) {
    const py::sequence vf = pieces[i].cast<py::sequence>();
    if (py::len(vf) != 2) fail(sc::ErrorCode::InvalidArgument, "a piece is (vertices, triangles)");
    const std::string cache =
        cache_files.is_none() ? std::string() : pathOf(cache_files[py::int_(i)]);
    built.push_back(build(kind, meshFrom(vf[0], vf[1]), cache, threads));
  }
  return {std::make_shared<const sc::Model>(kind, std::move(built))};
}

const sc::Piece& pieceOf(const PyModel& m, int piece) {
  const auto& pieces = m.model->pieces();
  if (piece < 0 || piece >= static_cast<int>(pieces.size())) {
    throw py::index_error("piece " + std::to_string(piece) + " of a model with " +
                          std::to_string(pieces.size()));
  }
  return *pieces[static_cast<size_t>(piece)];
}

/// A read-only (n, 3) view of `count` rows of T starting at `data`, kept alive by `owner`.
template <class T>
py::array view(const T* data, size_t count, const py::object& owner) {
  py::array a(py::dtype::of<T>(), {static_cast<py::ssize_t>(count), py::ssize_t{3}},
              {static_cast<py::ssize_t>(3 * sizeof(T)), static_cast<py::ssize_t>(sizeof(T))}, data,
              owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

/// A read-only view of one piece's stored rows (`rows`: MeshData::vertices or
/// ::triangles), kept alive by the model `self`.
template <class Rows>
py::array meshView(const py::object& self, int piece, Rows sc::MeshData::*rows) {
  const Rows& r = pieceOf(self.cast<const PyModel&>(), piece).mesh().*rows;
  return view(r.empty() ? nullptr : r[0].data(), r.size(), self);
}

void bindStats(py::module_& m) {
  py::class_<sc::PieceStats>(m, "PieceStats", "What preprocessing made of one piece.")
      .def_readonly("vertices", &sc::PieceStats::vertices, "Input vertices.")
      .def_readonly("triangles", &sc::PieceStats::triangles, "Input triangles.")
      .def_readonly("flipped", &sc::PieceStats::flipped,
                    "Closed piece given inside out, stored flipped.")
      .def_readonly("convex", &sc::PieceStats::convex, "Closed piece that is one convex patch.")
      .def_readonly("patches", &sc::PieceStats::patches,
                    "Convex patches (closed) or triangle leaves (soup).")
      .def_readonly("virtual_faces", &sc::PieceStats::virtual_faces,
                    "Hull faces that are not input triangles.")
      .def_readonly("hull_vertices", &sc::PieceStats::hull_vertices,
                    "Vertices summed over patch hulls.")
      .def_readonly("tree_depth", &sc::PieceStats::tree_depth,
                    "Depth of the hull (or triangle) hierarchy.")
      .def_readonly("from_cache", &sc::PieceStats::from_cache, "Loaded from the cache file.")
      .def_readonly("seconds", &sc::PieceStats::seconds, "Wall time of preprocessing.")
      .def("__repr__", [](const sc::PieceStats& s) {
        return "PieceStats(triangles=" + std::to_string(s.triangles) +
               ", patches=" + std::to_string(s.patches) +
               ", convex=" + (s.convex ? "True" : "False") +
               ", from_cache=" + (s.from_cache ? "True" : "False") + ")";
      });
}

}  // namespace

void bindModel(py::module_& m) {
  bindStats(m);
  py::class_<PyModel>(m, "Model",
                      R"(A rigid shape: one or more preprocessed triangle meshes ("pieces").

Immutable once built; one model may be used by any number of trackers and
scenes, on any thread. Preprocessing runs without the GIL.)")
      .def(py::init([](const ArrayArg& vertices, const ArrayArg& triangles, sc::ModelKind kind,
                       const py::object& cache_file, int threads) {
             const std::string cache = pathOf(cache_file);
             std::vector<sc::PiecePtr> pieces{
                 build(kind, meshFrom(vertices, triangles), cache, threads)};
             return PyModel{std::make_shared<const sc::Model>(kind, std::move(pieces))};
           }),
           py::arg("vertices"), py::arg("triangles"),
           py::arg("kind") = sc::ModelKind::ClosedPolyhedron, py::arg("cache_file") = py::none(),
           py::arg("threads") = 0,
           R"(Builds a one-piece model.

vertices: float array (n, 3). triangles: integer array (m, 3) of vertex indices,
counter-clockwise seen from outside. A CLOSED_POLYHEDRON must be closed, oriented
and one shell (inside out is flipped); a TRIANGLE_SOUP takes any finite triangles.
cache_file: path of a preprocessing cache, loaded when valid, else written.
threads: threads of the preprocessing, 0 = one per hardware thread; the model
(and its cache file) is the same for every count.
Raises InvalidArgumentError (shape, non-finite, bad index, threads outside
[0, 256]), InvalidGeometryError
(closed rules); warns CacheFileWarning when the cache could not be written.)")
      .def_static("from_pieces", &fromPieces, py::arg("pieces"),
                  py::arg("kind") = sc::ModelKind::ClosedPolyhedron,
                  py::arg("cache_files") = py::none(), py::arg("threads") = 0,
                  "Builds a model of several pieces, each a (vertices, triangles) pair;\n"
                  "cache_files, if given, holds one path per piece; threads as for Model().")
      .def_property_readonly(
          "kind", [](const PyModel& s) { return s.model->kind(); },
          "CLOSED_POLYHEDRON or TRIANGLE_SOUP.")
      .def_property_readonly(
          "piece_count", [](const PyModel& s) { return s.model->pieces().size(); },
          "Number of pieces.")
      .def_property_readonly(
          "bounds",
          [](const PyModel& s) {
            py::array_t<double> b({2, 3});
            Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> out(b.mutable_data());
            out.row(0) = s.model->bounds().min.transpose();
            out.row(1) = s.model->bounds().max.transpose();
            return b;
          },
          "Axis-aligned box in the model frame: [[xmin, ymin, zmin], [xmax, ymax, zmax]].")
      .def(
          "stats", [](const PyModel& s, int piece) { return pieceOf(s, piece).stats(); },
          py::arg("piece") = 0, "Preprocessing statistics of one piece.")
      .def(
          "vertices",
          [](const py::object& self, int piece) {
            return meshView(self, piece, &sc::MeshData::vertices);
          },
          py::arg("piece") = 0, "Read-only (n, 3) float64 view of a piece's stored vertices.")
      .def(
          "triangles",
          [](const py::object& self, int piece) {
            return meshView(self, piece, &sc::MeshData::triangles);
          },
          py::arg("piece") = 0,
          "Read-only (m, 3) int32 view of a piece's stored triangles (flipped if given inside "
          "out).")
      .def("__repr__", [](const PyModel& s) {
        int triangles = 0;
        for (const auto& p : s.model->pieces()) triangles += p->stats().triangles;
        return "Model(" + py::str(py::cast(s.model->kind())).cast<std::string>() +
               ", pieces=" + std::to_string(s.model->pieces().size()) +
               ", triangles=" + std::to_string(triangles) + ")";
      });
}

}  // namespace scpy
