// dnurbs.TriangleMesh (surface/triangle_mesh.h) and mesh export and import through assimp
// (io/mesh_export.h, io/mesh_import.h).

#include <type_traits>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "dnurbs/core/error.h"
#include "dnurbs/io/mesh_export.h"
#include "dnurbs/io/mesh_import.h"
#include "dnurbs/surface/triangle_mesh.h"
#include "python/src/bindings.h"
#include "python/src/numpy_arrays.h"

namespace dnurbs::python {

namespace {

// A (rows, columns) matrix member of the mesh as a read-only view with a checked setter.
template <typename Matrix>
void add_matrix_property(py::class_<TriangleMesh>& mesh, const char* name,
                         Matrix TriangleMesh::*member, const char* doc) {
  mesh.def_property(
      name,
      [member](const py::object& self) {
        const Matrix& matrix = self.cast<const TriangleMesh&>().*member;
        return read_only_view(matrix.data(), matrix.rows(), matrix.cols(), self);
      },
      [member, name](TriangleMesh& self, const py::object& value) {
        if constexpr (std::is_same_v<typename Matrix::Scalar, int>) {
          self.*member = index_matrix_from_array(value, name, Matrix::ColsAtCompileTime);
        } else {
          self.*member = matrix_from_array(value, name, -1, Matrix::ColsAtCompileTime);
        }
      },
      doc);
}

TriangleMesh make_mesh(const py::object& vertices, const py::object& triangles,
                       const py::object& normals, const py::object& uv, const std::string& name) {
  TriangleMesh mesh;
  mesh.name = name;
  mesh.vertices = matrix_from_array(vertices, "vertices", -1, 3);
  mesh.triangles = index_matrix_from_array(triangles, "triangles", 3);
  if (!normals.is_none()) {
    mesh.normals = matrix_from_array(normals, "normals", mesh.vertices.rows(), 3);
  }
  if (!uv.is_none()) {
    mesh.uv = matrix_from_array(uv, "uv", mesh.vertices.rows(), 2);
  }
  return mesh;
}

}  // namespace

void bind_triangle_mesh(py::module_& module) {
  py::class_<TriangleMesh> mesh(
      module, "TriangleMesh",
      "An indexed triangle mesh: vertices (V, 3), normals (V, 3) or (0, 3), uv (V, 2) or "
      "(0, 2) (the surface parameters), triangles (F, 3) int32 vertex indices, counter-clockwise "
      "seen from the side the normals point to, and a name. The arrays read as read-only views "
      "of the mesh (no copy); assign new arrays to change them.");
  mesh.def(py::init(&make_mesh), py::arg("vertices"), py::arg("triangles"),
           py::arg("normals") = py::none(), py::arg("uv") = py::none(), py::arg("name") = "mesh",
           "vertices (V, 3), triangles (F, 3) integer indices, normals (V, 3) or None, uv (V, 2) "
           "or None; copied.")
      .def_readwrite("name", &TriangleMesh::name, "Names the mesh in exported files.")
      .def_property_readonly("vertex_count", &TriangleMesh::vertex_count, "V.")
      .def_property_readonly("triangle_count", &TriangleMesh::triangle_count, "F.")
      .def("__repr__", [](const TriangleMesh& self) {
        return "TriangleMesh('" + self.name + "', " + std::to_string(self.vertex_count()) +
               " vertices, " + std::to_string(self.triangle_count()) + " triangles)";
      });
  add_matrix_property(mesh, "vertices", &TriangleMesh::vertices, "Positions, (V, 3).");
  add_matrix_property(mesh, "normals", &TriangleMesh::normals, "Unit normals, (V, 3) or (0, 3).");
  add_matrix_property(mesh, "uv", &TriangleMesh::uv, "Surface parameters, (V, 2) or (0, 2).");
  add_matrix_property(mesh, "triangles", &TriangleMesh::triangles, "Vertex indices, (F, 3) int32.");

  module.def(
      "export_meshes",
      [](const std::vector<TriangleMesh>& meshes, const std::filesystem::path& path,
         const std::string& up_axis) {
        if (up_axis != "z" && up_axis != "y") {
          throw make_error("up_axis must be \"z\" or \"y\", got \"", up_axis, "\"");
        }
        export_meshes(meshes, path, up_axis == "y" ? UpAxis::kY : UpAxis::kZ);
      },
      py::arg("meshes"), py::arg("path"), py::arg("up_axis") = "z",
      "Writes a list of TriangleMesh into one file through assimp, the format chosen by the "
      "extension (.obj, .stl, .ply, .gltf, .glb); atomic (temporary files renamed). glTF is "
      "written Y-up; `up_axis` 'y' turns OBJ, STL and PLY Y-up too ((x, y, z) -> (x, z, -y)). "
      "Raises dnurbs.Error for an unknown extension, an empty list, an index out of range or an "
      "assimp failure.");
  module.def("import_meshes", &import_meshes, py::arg("path"), py::arg("cpu_seconds") = 0,
             "Reads the meshes of a file through assimp: a list of TriangleMesh. assimp runs in "
             "a child process with at most cpu_seconds of CPU time (0: 10 s plus 1 s per MB), so "
             "that a malformed file that crashes it or makes it loop raises dnurbs.Error.");
}

}  // namespace dnurbs::python
