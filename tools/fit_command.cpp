#include "tools/fit_command.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "dnurbs/core/error.h"
#include "dnurbs/core/progress_report.h"
#include "dnurbs/design/dnurbs_fitting.h"
#include "dnurbs/design/point_set.h"
#include "dnurbs/design/superquadric_fitting.h"
#include "dnurbs/io/atomic_write.h"
#include "dnurbs/io/mesh_export.h"
#include "dnurbs/io/output_path.h"
#include "dnurbs/io/scene_fit.h"
#include "dnurbs/io/shape_file.h"
#include "dnurbs/surface/parametric_fe_mesh.h"
#include "dnurbs/surface/parametric_surface.h"
#include "dnurbs/surface/parametric_surface_tessellation.h"
#include "dnurbs/surface/tessellation.h"
#include "tools/command_line.h"

namespace dnurbs::tools {

const char* const kFitHelp = R"(usage: dnurbs fit superquadric|surface POINTS [options]

Fits a shape to points and prints it with its RMS and max error as JSON. POINTS is a text file
of "x y z" lines (.xyz, .txt, .csv) or any mesh assimp reads (its vertices are the points).
With --out DIR it also writes DIR/surface.json (a shape file, as `dnurbs eval` reads) or
DIR/superquadric.json (the printed JSON), and DIR/<shape>.obj, the fitted shape tessellated.

  superquadric        rigid pose, sizes, squareness, taper, bend, twist and shear (radial
                      distance, LBFGS with the analytic gradient, then Levenberg-Marquardt);
                      with --local also the local displacements d on the model's (u, v) mesh
  surface             a D-NURBS surface over the points' principal plane, by least squares
                      plus smoothness with closest-point re-projection
options:
  --out DIR           write the fitted shape and its OBJ mesh into DIR
  --resolution N      mesh segments per direction (default 32)
  --quiet             no progress lines (on stderr, at most one a second: the iterations of
                      the surface fit, the objective evaluations of the superquadric fit)
options (superquadric):
  --no-twist          hold the twist tau at 0
  --no-shear          hold the shears sx, sy at 0
  --bend-shape        fit the bend's offset b2 and frequency b3 too (held at 0 and 0.5)
  --local             then fit the local displacements d = S q_d: the equilibrium of the
                      membrane energy (the model's) and springs to the points; adds "local"
                      to the JSON and d to the mesh
  --local-cells NU NV cells of the displacement mesh in u and v (default 8 16)
  --local-smoothness L  weight of the membrane energy against the mean squared distance
                      (default 1e-4; larger is smoother)
options (surface):
  --degree P          degree in u and v (default 3)
  --spans N           knot spans in u and v (default 4)
  --smoothness S      weight of the thin-plate energy (default 1e-6)
  --iterations N      projection-and-solve iterations (default 30)

exit codes: 0 ok, 1 bad data, 2 bad command line
)";

namespace {

nlohmann::ordered_json json_array(const Eigen::VectorXd& values) {
  return std::vector<double>(values.data(), values.data() + values.size());
}

// Where --out writes, and the mesh resolution.
struct FitOutput {
  std::optional<std::filesystem::path> directory;
  int resolution = 32;
};

// The body-frame surface p = s + d of a fit (d = 0 without a local stage).
ParametricSurface fitted_body_surface(const SuperquadricFitResult& fit) {
  const DeformableSuperquadricShape shape(fit.shape);
  if (!fit.local) {
    return parametric_surface(shape);
  }
  const ParametricFeMesh mesh(fit.local->mesh_cells_u, fit.local->mesh_cells_v);
  const Eigen::VectorXd displacements = fit.local->displacements;
  return ParametricSurface(
      superquadric_parameter_domain(),
      [shape, mesh, displacements](double u, double v) {
        return Eigen::Vector3d(shape.point(u, v) +
                               mesh.displacement(displacements, mesh.shape_values(u, v)).value);
      },
      {}, NormalOrientation::kSvCrossSu);
}

int fit_superquadric_command(const Eigen::MatrixX3d& points, SuperquadricFitSettings settings,
                             const FitOutput& output, std::ostream& out,
                             const std::function<void(int, double)>& on_evaluation) {
  settings.on_evaluation = on_evaluation;
  const SuperquadricFitResult fit = fit_superquadric(points, settings);
  nlohmann::ordered_json json = {
      {"shape", "superquadric"},
      {"q_s", json_array(fit.shape)},
      {"centre", json_array(fit.centre)},
      {"rotation", json_array(Eigen::Map<const Eigen::VectorXd>(fit.rotation.data(), 9))},
      {"rms_error", fit.rms_error},
      {"max_error", fit.max_error}};
  if (fit.local) {
    json["local"] = {{"mesh_cells", {fit.local->mesh_cells_u, fit.local->mesh_cells_v}},
                     {"q_d", json_array(fit.local->displacements)},
                     {"rms_error", fit.local->rms_error},
                     {"max_error", fit.local->max_error},
                     {"global_rms_error", fit.local->global_rms_error},
                     {"global_max_error", fit.local->global_max_error}};
  }
  std::ostringstream text;
  print_json(text, json);
  if (output.directory) {
    std::filesystem::create_directories(*output.directory);
    write_file_atomically(output_file_path(*output.directory, "superquadric.json"), text.str());
    // The body-frame surface moved to the fitted pose x = c + R (s + d).
    TriangleMesh mesh = tessellate_surface(fitted_body_surface(fit), output.resolution,
                                           2 * output.resolution, "superquadric");
    mesh.vertices = (mesh.vertices * fit.rotation.transpose()).rowwise() + fit.centre.transpose();
    mesh.normals = mesh.normals * fit.rotation.transpose();
    export_mesh(mesh, output_file_path(*output.directory, "superquadric.obj"));
  }
  out << text.str();
  return kExitOk;
}

int fit_surface_command(const Eigen::MatrixX3d& points, int degree, int spans, double smoothness,
                        int iterations, const FitOutput& output, std::ostream& out,
                        const std::function<void(int, double)>& on_iteration) {
  // A flat start over the principal plane of the points, covering their extent.
  const NurbsSurface start = principal_plane_surface(points, degree, spans);
  const KnotVector& knots = start.knots_u();
  DNurbsSurfaceMaterial material;
  material.b20 = 1.0;
  material.b11 = 1.0;
  material.b02 = 1.0;
  const DNurbsSurface model(start, material);
  DNurbsFitSettings settings;
  settings.smoothness = smoothness;
  settings.max_iterations = iterations;
  settings.on_iteration = on_iteration;
  const DNurbsFitResult fit = fit_dnurbs_surface(model, points, settings);
  if (output.directory) {
    const NurbsSurface surface = model.surface(fit.coordinates);
    std::filesystem::create_directories(*output.directory);
    write_shape_file(output_file_path(*output.directory, "surface.json"), Shape(surface));
    export_mesh(tessellate_surface(surface, output.resolution, output.resolution),
                output_file_path(*output.directory, "surface.obj"));
  }
  print_json(out, {{"shape", "nurbs_surface"},
                   {"degree", degree},
                   {"knots", knots.knots()},
                   {"control_points", json_array(fit.coordinates)},
                   {"iterations", fit.iterations},
                   {"rms_error", fit.rms_error},
                   {"max_error", fit.max_error}});
  return kExitOk;
}

}  // namespace

int fit_command(const std::vector<std::string>& arguments, std::ostream& out, std::ostream& err) {
  std::string shape;
  std::string path;
  int degree = 3;
  int spans = 4;
  double smoothness = 1e-6;
  int iterations = 30;
  std::string directory;
  FitOutput output;
  bool quiet = false;
  SuperquadricFitSettings superquadric_settings;
  bool no_twist = false;
  bool no_shear = false;
  bool local = false;
  SuperquadricLocalFitSettings local_settings;
  std::vector<int> local_cells;
  CLI::App app("dnurbs fit");
  app.add_option("SHAPE", shape)->required()->check(CLI::IsMember({"superquadric", "surface"}));
  app.add_option("POINTS", path)->required();
  app.add_option("--degree", degree)->transform(integer_in(1, 9));
  app.add_option("--spans", spans)->transform(integer_in(1, 1000));
  app.add_option("--smoothness", smoothness)->check(finite_number());
  const CLI::Option* directory_option = app.add_option("--out", directory);
  app.add_option("--resolution", output.resolution)->transform(integer_in(3, 1024));
  app.add_option("--iterations", iterations)->transform(integer_in(1, 100000));
  app.add_flag("--quiet", quiet);
  app.add_flag("--no-twist", no_twist);
  app.add_flag("--no-shear", no_shear);
  app.add_flag("--bend-shape", superquadric_settings.fit_bend_shape);
  app.add_flag("--local", local);
  app.add_option("--local-cells", local_cells)->expected(2)->transform(integer_in(2, 1000));
  app.add_option("--local-smoothness", local_settings.smoothness)->check(positive_number());
  if (!parse_command_line(app, arguments, kFitHelp, out)) {
    return kExitOk;
  }
  superquadric_settings.fit_twist = !no_twist;
  superquadric_settings.fit_shear = !no_shear;
  if (!local_cells.empty()) {
    local_settings.mesh_cells_u = local_cells[0];
    local_settings.mesh_cells_v = local_cells[1];
  }
  if (local) {
    superquadric_settings.local = local_settings;
  }
  if (*directory_option) {
    output.directory = directory;
  }
  const Eigen::MatrixX3d points = read_fit_points(path);
  // Progress on stderr (stdout is the JSON result), at most once a second: iterations of the
  // surface fit, objective evaluations of the superquadric fit (24 starts, then a polish)
  const bool superquadric = shape == "superquadric";
  ProgressReport progress(err, superquadric ? "evaluation" : "iteration",
                          ::isatty(STDERR_FILENO) == 1);
  std::function<void(int, double)> on_progress;
  if (!quiet) {
    on_progress = [&progress, superquadric](int count, double rms_error) {
      std::ostringstream detail;
      detail << (superquadric ? "best rms distance " : "rms distance ") << rms_error;
      progress.update(count, 0, detail.str());
    };
  }
  const int status = superquadric ? fit_superquadric_command(points, superquadric_settings, output,
                                                             out, on_progress)
                                  : fit_surface_command(points, degree, spans, smoothness,
                                                        iterations, output, out, on_progress);
  progress.finish();
  return status;
}

}  // namespace dnurbs::tools
