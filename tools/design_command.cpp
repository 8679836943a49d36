#include "tools/design_command.h"

#include <unistd.h>

#include <filesystem>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "dnurbs/core/progress_report.h"
#include "dnurbs/design/energy_minimization.h"
#include "dnurbs/io/mesh_export.h"
#include "dnurbs/io/output_path.h"
#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_simulation.h"
#include "dnurbs/io/shape_file.h"
#include "tools/command_line.h"

namespace dnurbs::tools {

const char* const kDesignHelp = R"(usage: dnurbs design SCENE.json [--out DIR] [options]

Minimizes the elastic energy of the scene's models minus the work of its forces (evaluated at
time 0) subject to its constraints as equalities, with free weights bounded below by the
minimum weight (NLopt). The scene file is the format of `dnurbs run` (docs/scene-format.md);
its optional "design" section sets the algorithm and tolerances, the dynamics keys are ignored.
Writes DIR/<model name>.json for every D-NURBS model (the shape file format of `dnurbs eval`)
and DIR/<output.name>.obj (every model, output.resolution segments), and prints the
iterations, final energy, constraint violation and NLopt status as JSON.

options:
  --out DIR               output directory (default: design_out)
  --algorithm A           slsqp or auglag_lbfgs (overrides design.algorithm)
  --max-evaluations N     overrides design.max_evaluations
  --quiet                 no progress lines (on stderr, at most one a second)

exit codes: 0 ok, 1 bad scene or NLopt failure, 2 bad command line
)";

namespace {

DesignSettings design_settings(const SceneDesign& design) {
  DesignSettings settings;
  settings.algorithm = design.algorithm == "auglag_lbfgs"
                           ? DesignAlgorithm::kAugmentedLagrangianLbfgs
                           : DesignAlgorithm::kSlsqp;
  settings.variable_tolerance = design.variable_tolerance;
  settings.energy_tolerance = design.energy_tolerance;
  settings.constraint_tolerance = design.constraint_tolerance;
  settings.max_evaluations = design.max_evaluations;
  settings.max_seconds = design.max_seconds;
  return settings;
}

}  // namespace

int design_command(const std::vector<std::string>& arguments, std::ostream& out,
                   std::ostream& err) {
  std::string scene_path;
  std::string directory = "design_out";
  std::string algorithm;
  int max_evaluations = 0;
  bool quiet = false;
  CLI::App app("dnurbs design");
  app.add_option("SCENE", scene_path)->required();
  app.add_option("--out", directory);
  const CLI::Option* algorithm_option =
      app.add_option("--algorithm", algorithm)->check(CLI::IsMember({"slsqp", "auglag_lbfgs"}));
  const CLI::Option* evaluations_option =
      app.add_option("--max-evaluations", max_evaluations)->transform(integer_in(1, 100000000));
  app.add_flag("--quiet", quiet);
  if (!parse_command_line(app, arguments, kDesignHelp, out)) {
    return kExitOk;
  }
  Scene scene = read_scene_file(scene_path);
  SceneDesign design = scene.design.value_or(SceneDesign{});
  if (*algorithm_option) {
    design.algorithm = algorithm;
  }
  if (*evaluations_option) {
    design.max_evaluations = max_evaluations;
  }
  const int resolution = scene.output.resolution;
  const std::string mesh_name = scene.output.name + ".obj";
  SceneSimulation simulation(std::move(scene));
  DesignSettings settings = design_settings(design);
  // Progress on stderr (stdout is the JSON result): evaluations of Pi of at most
  // max_evaluations (NLopt usually stops earlier, so no time left is shown), at most once a second
  ProgressReport progress(err, "evaluation", ::isatty(STDERR_FILENO) == 1);
  if (!quiet) {
    settings.on_evaluation = [&progress](int evaluations, double energy) {
      std::ostringstream detail;
      detail << "energy " << energy;
      progress.update(evaluations, 0, detail.str());
    };
  }
  const DesignResult result =
      minimize_energy(simulation.system(), &simulation.constraints(), settings);
  progress.finish();
  simulation.set_coordinates(result.coordinates);

  std::filesystem::create_directories(directory);
  std::vector<std::filesystem::path> written;
  for (int i = 0; i < simulation.system().model_count(); ++i) {
    if (const std::optional<Shape> shape = simulation.shape(i)) {
      const auto path = output_file_path(
          directory, output_file_stem(simulation.scene().models[static_cast<size_t>(i)].name,
                                      "model" + std::to_string(i)) +
                         ".json");
      write_shape_file(path, *shape);
      written.push_back(path);
    }
  }
  const auto mesh_path = output_file_path(directory, mesh_name);
  export_meshes(simulation.meshes(resolution), mesh_path,
                simulation.scene().output.up_axis == "y" ? UpAxis::kY : UpAxis::kZ);
  written.push_back(mesh_path);

  nlohmann::ordered_json files = nlohmann::ordered_json::array();
  for (const auto& file : written) {
    files.push_back(file.string());
  }
  print_json(out, {{"algorithm", design.algorithm},
                   {"iterations", result.iterations},
                   {"energy", result.energy},
                   {"constraint_violation", result.constraint_violation},
                   {"status", result.status},
                   {"status_name", result.status_name},
                   {"files", std::move(files)}});
  return result.converged() ? kExitOk : kExitError;
}

}  // namespace dnurbs::tools
