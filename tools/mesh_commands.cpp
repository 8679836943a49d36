#include "tools/mesh_commands.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <numbers>
#include <system_error>
#include <variant>

#include "dnurbs/core/error.h"
#include "dnurbs/core/input_file.h"
#include "dnurbs/dynamics/triangular/triangular_tessellation.h"
#include "dnurbs/io/cad_file.h"
#include "dnurbs/io/mesh_export.h"
#include "dnurbs/io/mesh_import.h"
#include "dnurbs/io/obj_freeform.h"
#include "dnurbs/io/preview.h"
#include "dnurbs/io/shape_file.h"
#include "dnurbs/io/triangular_shape_file.h"
#include "dnurbs/surface/adaptive_tessellation.h"
#include "dnurbs/surface/tessellation.h"
#include "tools/command_line.h"

namespace dnurbs::tools {

const char* const kExportHelp =
    R"(usage: dnurbs export SHAPE.json MESH [--resolution N | --max-error E | --max-angle DEG]
                     [--compare] [--radius R] [--up-axis z|y]
       dnurbs export SHAPE.json [SHAPE.json ...] PART.step|.stp|.iges|.igs
       dnurbs export SHAPE.json [SHAPE.json ...] PART.obj --nurbs

Tessellates the curve or surface of a shape file and writes a triangle mesh. The format follows
MESH's extension: .obj (default choice; with a .mtl), .stl, .ply, .gltf (with a .bin) or .glb.
A surface gets N x N cells, or an adaptive mesh (Goldenstein et al. 2005, section 5: a restricted binary
multi-triangulation, crack-free) refined until every triangle is within E of the surface
(sampled distance) or its vertex normals within DEG degrees; a curve becomes a tube of radius R
around N segments. A triangular_nurbs surface gets every domain triangle split into N x N
triangles (default 4), or with --max-error E longest-edge bisection until its chord error is
within E.

To a STEP or IGES file, the shapes are written as they are, NURBS curves and surfaces with their
knots, weights and control points to 17 digits (periodic ones closed and unclamped), for a CAD
tool to read; `dnurbs import` reads them back exactly. --nurbs writes them to an OBJ file the
same way, as free-form curv and surf statements. The mesh options do not apply.

options:
  --resolution N      segments per direction, 3..4096 (default 32 for surfaces, 128 for curves;
                      triangular_nurbs: N x N per domain triangle, default 4)
  --max-error E       surfaces: adaptive mesh by the surface-error criterion, E > 0 (absolute,
                      in the shape's units), from the base grid that needs the fewest vertices
  --max-angle DEG     surfaces: adaptive mesh by the normals criterion, 0 < DEG <= 180
  --compare           with --max-error: also report the coarsest uniform grid meeting E
  --nurbs             with a .obj file: NURBS (free-form geometry) instead of a mesh
  --radius R          tube radius for curves (default 1% of the control polygon's diagonal)
  --up-axis z|y       the up axis of .obj/.stl/.ply (default z, as dnurbs; y turns (x, y, z)
                      into (x, z, -y)); .gltf/.glb are always Y-up, as glTF 2.0 requires
  -h, --help          this help

Adaptive meshes stop at 16 bisections below a 4 x 4 base grid; a bound not met there is reported
on stderr (the mesh is still written).

exit codes: 0 ok, 1 bad shape file or failed export, 2 bad command line
)";

const char* const kPreviewHelp = R"(usage: dnurbs preview MESH OUT.png

Renders a shaded PNG of a mesh with preview_mesh.py (python3 + matplotlib; set DNURBS_PYTHON to
choose the interpreter). MESH is OBJ, or any format the mesh import reads (STL, PLY, glTF, ...),
converted to a temporary OBJ first.

exit codes: 0 ok, 1 failure (missing mesh, no python with matplotlib), 2 bad command line
)";

namespace {

// A fresh directory under the system's temporary directory, removed with everything in it when
// the object goes.
class ScratchDirectory {
 public:
  explicit ScratchDirectory(const std::string& prefix) {
    std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      throw make_error(pattern, ": cannot create a temporary directory: ", std::strerror(errno));
    }
    path_ = pattern;
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;
  ScratchDirectory(ScratchDirectory&&) = delete;
  ScratchDirectory& operator=(ScratchDirectory&&) = delete;
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// Where preview_mesh.py may be: the source tree, beside an installed dnurbs, the install prefix
std::vector<std::filesystem::path> preview_script_directories(const std::string& program) {
  std::vector<std::filesystem::path> directories = {DNURBS_SOURCE_TOOLS_DIR};
  std::error_code error;
  const std::filesystem::path executable = std::filesystem::read_symlink("/proc/self/exe", error);
  const std::filesystem::path binary = error ? std::filesystem::path(program) : executable;
  if (!binary.empty()) {
    directories.push_back(binary.parent_path().parent_path() / "share" / "dnurbs");
  }
  directories.emplace_back(DNURBS_INSTALLED_TOOLS_DIR);
  return directories;
}

std::vector<std::string> python_candidates() {
  std::vector<std::string> candidates;
  if (const char* chosen = std::getenv("DNURBS_PYTHON"); chosen != nullptr && *chosen != '\0') {
    candidates.emplace_back(chosen);
  }
  candidates.emplace_back("python3");
  candidates.emplace_back("/usr/bin/python3");
  return candidates;
}

// The adaptive mesh of `export`, reporting its vertices and measured error (and the uniform
// grid for the same bound with `compare`)
TriangleMesh export_adaptive_mesh(const NurbsSurface& shape, double max_error,
                                  double max_angle_degrees, bool compare, const std::string& name,
                                  std::ostream& out) {
  constexpr int kBaseCells = 4;
  constexpr int kMaxLevel = 16;
  const ParametricSurface surface = parametric_surface(shape);
  auto refined = [&] {
    if (max_error > 0.0) {
      return refine_to_surface_error_from_best_base(surface, max_error, kBaseCells, kBaseCells,
                                                    kMaxLevel);
    }
    RestrictedMesh mesh(surface, kBaseCells, kBaseCells);
    mesh.refine(normal_angle_criterion(max_angle_degrees * std::numbers::pi / 180.0), kMaxLevel);
    return mesh;
  };
  const RestrictedMesh adaptive = refined();
  const SurfaceError error = mesh_surface_error(adaptive, kDefaultErrorSampleOrder);
  TriangleMesh mesh = adaptive.to_triangle_mesh(name);
  out << "adaptive (" << (max_error > 0.0 ? "surface error" : "normals")
      << " criterion): " << mesh.vertex_count() << " vertices from a " << adaptive.base_cells_u()
      << " x " << adaptive.base_cells_v() << " base, levels 0.." << adaptive.max_level()
      << ", sampled max error " << error.max << ", mean " << error.mean << "\n";
  if (max_error > 0.0 && error.max > max_error) {
    std::cerr << "warning: the bound " << max_error << " is not met at " << kMaxLevel
              << " levels (max error " << error.max << ")\n";
  }
  if (compare) {
    const UniformTessellationChoice uniform =
        coarsest_uniform_tessellation(surface, kBaseCells, kBaseCells, max_error);
    out << "uniform: " << uniform.cells_u << " x " << uniform.cells_v << " cells, "
        << uniform.vertices << " vertices, sampled max error " << uniform.error.max << "\n";
  }
  return mesh;
}

// The mesh of a NURBS curve or surface shape (export_command's options).
TriangleMesh export_shape_mesh(const Shape& shape, int resolution, double radius, double max_error,
                               double max_angle_degrees, bool compare, const std::string& file,
                               std::ostream& out) {
  const std::string name = std::filesystem::path(file).stem().string();
  TriangleMesh mesh;
  if (const auto* surface = std::get_if<NurbsSurface>(&shape)) {
    if (max_error > 0.0 || max_angle_degrees > 0.0) {
      mesh = export_adaptive_mesh(*surface, max_error, max_angle_degrees, compare, name, out);
    } else {
      const int segments = resolution > 0 ? resolution : 32;
      mesh = tessellate_surface(*surface, segments, segments, name);
    }
  } else {
    if (max_error > 0.0 || max_angle_degrees > 0.0) {
      throw UsageError("--max-error and --max-angle apply to surfaces; " + file + " is a curve");
    }
    const auto& curve = std::get<NurbsCurve>(shape);
    const Eigen::MatrixX3d& points = curve.control_points();
    const double diagonal = (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
    const double tube = radius > 0.0 ? radius : (diagonal > 0.0 ? 0.01 * diagonal : 0.01);
    mesh = tessellate_curve_tube(curve, resolution > 0 ? resolution : 128, tube, 12, name);
  }
  return mesh;
}

}  // namespace

void render_preview_png(const std::string& program, const std::filesystem::path& mesh,
                        const std::filesystem::path& png) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(mesh, error)) {
    throw make_error(mesh.string(), ": the mesh file does not exist");
  }
  const std::filesystem::path script = find_preview_script(preview_script_directories(program));
  const std::string python = find_python_with_matplotlib(python_candidates());
  if (lowercase_extension(mesh) == ".obj") {
    render_preview(python, script, mesh, png);
    return;
  }
  // The script reads OBJ: any other format assimp reads goes through a temporary OBJ copy
  const std::vector<TriangleMesh> meshes = import_meshes(mesh);
  const ScratchDirectory scratch("dnurbs-preview");
  const std::filesystem::path obj = scratch.path() / "preview.obj";
  export_meshes(meshes, obj);
  render_preview(python, script, obj, png);
}

void render_energy_png(const std::string& program, const std::filesystem::path& log,
                       const std::filesystem::path& png) {
  const std::filesystem::path script =
      find_preview_script(preview_script_directories(program), kEnergyPlotScriptName);
  render_preview(find_python_with_matplotlib(python_candidates()), script, log, png);
}

int export_command(const std::vector<std::string>& arguments, std::ostream& out) {
  std::vector<std::string> files;
  int resolution = 0;
  double radius = 0.0;
  double max_error = 0.0;
  double max_angle_degrees = 0.0;
  bool compare = false;
  bool nurbs = false;
  std::string axis = "z";
  CLI::App app("dnurbs export");
  app.add_option("FILES", files)->required();
  const std::vector<CLI::Option*> mesh_options = {
      app.add_option("--resolution", resolution)->transform(integer_in(3, 4096)),
      app.add_option("--up-axis", axis)->check(CLI::IsMember({"z", "y"})),
      app.add_option("--radius", radius)->check(positive_number()),
      app.add_option("--max-error", max_error)->check(positive_number()),
      app.add_option("--max-angle", max_angle_degrees)->check(positive_number(180.0)),
      app.add_flag("--compare", compare)};
  app.add_flag("--nurbs", nurbs);
  if (!parse_command_line(app, arguments, kExportHelp, out)) {
    return kExitOk;
  }
  const UpAxis up = axis == "y" ? UpAxis::kY : UpAxis::kZ;
  if ((resolution > 0) + (max_error > 0.0) + (max_angle_degrees > 0.0) > 1) {
    throw UsageError("--resolution, --max-error and --max-angle exclude each other");
  }
  if (compare && !(max_error > 0.0)) {
    throw UsageError("--compare needs --max-error");
  }
  if (nurbs && (files.empty() || lowercase_extension(files.back()) != ".obj")) {
    throw UsageError("--nurbs applies to a .obj file (STEP and IGES files are always NURBS)");
  }
  if (files.size() >= 2 && (nurbs || cad_format_of(files.back()))) {
    if (std::any_of(mesh_options.begin(), mesh_options.end(),
                    [](const CLI::Option* option) { return option->count() > 0; })) {
      throw UsageError("the mesh options do not apply to NURBS in a STEP, IGES or OBJ file");
    }
    std::vector<Shape> shapes;
    for (size_t k = 0; k + 1 < files.size(); ++k) {
      shapes.push_back(read_shape_file(files[k]));
    }
    if (nurbs) {
      write_obj_freeform_file(files.back(), shapes);
    } else {
      write_cad_file(files.back(), shapes);
    }
    for (size_t k = 0; k < shapes.size(); ++k) {
      out << "wrote " << files[k] << " to " << files.back() << " (" << shape_summary(shapes[k])
          << ")\n";
    }
    return kExitOk;
  }
  if (files.size() != 2) {
    throw UsageError("expected SHAPE.json and MESH, got " + std::to_string(files.size()) +
                     " file arguments");
  }
  const std::filesystem::path mesh_path = files[1];
  mesh_format_from_path(mesh_path);  // an unknown extension fails before any work
  const std::string name = std::filesystem::path(files[0]).stem().string();
  TriangleMesh mesh;
  if (is_triangular_shape_file(files[0])) {
    if (max_angle_degrees > 0.0 || compare) {
      throw UsageError("--max-angle and --compare do not apply to triangular_nurbs surfaces");
    }
    const TriangularNurbsSurface surface = read_triangular_shape_file(files[0]);
    mesh = max_error > 0.0
               ? tessellate_triangular_surface_adaptive(surface, max_error, 20, name)
               : tessellate_triangular_surface(surface, resolution > 0 ? resolution : 4, name);
  } else {
    mesh = export_shape_mesh(read_shape_file(files[0]), resolution, radius, max_error,
                             max_angle_degrees, compare, files[0], out);
  }
  export_meshes({mesh}, mesh_path, up);
  out << "wrote " << mesh_path.string() << " (" << mesh.vertex_count() << " vertices, "
      << mesh.triangle_count() << " triangles)\n";
  return kExitOk;
}

int preview_command(const std::vector<std::string>& arguments, const std::string& program,
                    std::ostream& out) {
  std::vector<std::string> files(2);
  CLI::App app("dnurbs preview");
  app.add_option("MESH", files[0])->required();
  app.add_option("PNG", files[1])->required();
  if (!parse_command_line(app, arguments, kPreviewHelp, out)) {
    return kExitOk;
  }
  render_preview_png(program, files[0], files[1]);
  out << "wrote " << files[1] << " (shaded preview of " << files[0] << ")\n";
  return kExitOk;
}

}  // namespace dnurbs::tools
