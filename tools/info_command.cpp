#include "tools/info_command.h"

#include <iomanip>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <variant>

#include "dnurbs/dynamics/integrators/integrator.h"
#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_simulation.h"
#include "tools/command_line.h"
#include "tools/run_command.h"

namespace dnurbs::tools {

const char* const kInfoHelp = R"(usage: dnurbs info [SCENE.json]

Describes a scene file (default: the built-in demo of dnurbs run) without running it: its
models with their coordinates, velocities, fixed and active coordinates, which matrices are
constant (assembled and factored once) and which are re-assembled every step, the non-zeros of
M + D + K and of its LDL^T factor over the active coordinates, the work of one solve (factor
entries touched: 2 nnz(L) per right-hand side, plus the factorization when the matrices change),
what each automatic choice (fixed weights, rigid or global superquadric parts, deformation
regions) saves against the naive path, the forces, constraints, integrator and run length, and
the scene's state hash (checkpoints carry it).

exit codes: 0 ok, 1 bad scene, 2 bad command line
)";

namespace {

// A cost ratio with three significant digits
std::string ratio(double value) {
  std::ostringstream text;
  text << std::setprecision(3) << value;
  return text.str();
}

}  // namespace

int info_command(const std::vector<std::string>& arguments, std::ostream& out) {
  std::optional<std::string> scene_file;  // absent: the built-in default scene
  CLI::App app("dnurbs info");
  app.add_option("SCENE", scene_file);
  if (!parse_command_line(app, arguments, kInfoHelp, out)) {
    return kExitOk;
  }
  const Scene scene = scene_file ? read_scene_file(*scene_file)
                                 : parse_scene_json(kDefaultSceneJson, "<default demo>");
  const SceneSimulation simulation(scene);
  const System& system = simulation.system();
  out << "scene: " << scene.source << "\n";
  out << "state hash: " << scene_state_hash(scene) << "\n";
  if (!scene.description.empty()) {
    out << "description: " << scene.description << "\n";
  }
  out << "models: " << system.model_count() << "\n";
  double solve_total = 0.0;
  double naive_solve_total = 0.0;
  bool all_constant = true;
  for (const SceneModelCost& c : simulation.cost()) {
    all_constant = all_constant && c.constant_matrices;
    solve_total += c.solve_work;
    naive_solve_total += c.automatic_choice.empty() ? c.solve_work : c.naive_solve_work;
    out << "  " << c.name << " (" << c.type << "): " << c.coordinates << " coordinates, "
        << c.velocities << " velocities, " << c.fixed << " fixed, " << c.velocities - c.fixed
        << " active\n";
    out << "    matrices: "
        << (c.constant_matrices ? "constant (assembled and factored once)"
                                : "state-dependent (assembled and factored every step)");
    if (c.kronecker_block > 0) {
      out << "; x, y, z share one scalar matrix (S (x) I_" << c.kronecker_block << ")";
    }
    out << "\n    non-zeros: M + D + K " << c.matrix_non_zeros
        << ", LDL^T factor (L below the diagonal) " << c.factor_non_zeros
        << (c.kronecker_block > 0 ? " (scalar matrix)" : "") << "; one solve touches "
        << c.solve_work << " factor entries\n";
    if (!c.automatic_choice.empty()) {
      out << "    saved: " << c.automatic_choice << ": " << c.velocities - c.fixed << " instead of "
          << c.naive_active << " active coordinates";
      if (c.constant_matrices && !c.naive_constant_matrices) {
        out << ", constant instead of state-dependent matrices";
      } else if (!c.constant_matrices && c.naive_constant_matrices) {
        out << ", state-dependent instead of constant matrices";
      }
      // A choice that saves coordinates may still cost more per solve (a swung surface
      // re-factors its small dense matrix where its tensor-product twin back-substitutes)
      const double saving = c.naive_solve_work / c.solve_work;
      out << ", one solve "
          << (saving >= 1.0 ? ratio(saving) + "x cheaper"
                            : ratio(1.0 / saving) + "x more expensive")
          << " (estimated)\n";
    }
  }
  out << "system: " << system.coordinate_count() << " coordinates, " << system.velocity_count()
      << " velocities, " << system.fixed_coordinates().size() << " fixed; matrices "
      << (system.matrices_are_constant() ? "constant" : "state-dependent") << "\n";
  std::map<std::string, int> forces;
  for (const auto& force : scene.forces) {
    ++forces[force.spec->type()];
  }
  out << "forces: " << scene.forces.size();
  for (const auto& [type, count] : forces) {
    out << (type == forces.begin()->first ? " (" : ", ") << count << " " << type;
  }
  out << (forces.empty() ? "" : ")") << "\n";
  if (!scene.obstacles.empty()) {
    std::map<std::string, int> obstacles;
    for (const Obstacle& obstacle : scene.obstacles) {
      ++obstacles[std::holds_alternative<GroundPlane>(obstacle)   ? "plane"
                  : std::holds_alternative<BoxObstacle>(obstacle) ? "box"
                                                                  : "sphere"];
    }
    out << "obstacles: " << scene.obstacles.size();
    for (const auto& [kind, count] : obstacles) {
      out << (kind == obstacles.begin()->first ? " (" : ", ") << count << " " << kind;
    }
    out << "), " << scene.contact.method << " contact\n";
  }
  std::map<std::string, int> constraints;
  for (const auto& constraint : scene.constraints) {
    ++constraints[constraint.spec->type()];
  }
  out << "constraints: " << scene.constraints.size() << " (" << simulation.constraints().row_count()
      << " rows)";
  for (const auto& [type, count] : constraints) {
    out << (type == constraints.begin()->first ? ": " : ", ") << count << " " << type;
  }
  out << "\n";
  const SceneIntegrator& integrator = scene.integrator;
  // IntegratorSettings::automatic_newton: free-weight models iterate Newton with 0 set
  const bool automatic =
      automatic_newton_applies(simulation.integrator().settings(), simulation.system());
  const int iterations = automatic ? kAutomaticNewtonIterations : integrator.newton_iterations;
  out << "integrator: " << integrator.scheme << ", dt = " << integrator.dt << ", Newton iterations "
      << integrator.newton_iterations;
  if (automatic) {
    out << " (automatic for free weights: up to " << kAutomaticNewtonIterations << ", to "
        << kAutomaticNewtonTolerance << " of |a|)";
  }
  out << "\n";
  out << "run: " << scene.step_count() << " steps (t = " << scene.step_count() * integrator.dt
      << "), " << scene.probes.size() << " probe(s)\n";
  // Each model's block is factored on its own: constant blocks once, the others every solve
  out << "estimated cost per step: " << (all_constant ? 1 : 1 + iterations) << " solve(s) touching "
      << solve_total << " factor entries each"
      << (all_constant ? " (after one factorization at the first step)" : "")
      << "; the naive paths would touch " << naive_solve_total
      << " ("
      // a factor without off-diagonal entries (one free coordinate) touches none either way
      << (solve_total > 0.0 ? ratio(naive_solve_total / solve_total) + "x" : "the same") << ")";
  if (simulation.constraints().row_count() > 0) {
    out << ", plus " << simulation.constraints().row_count()
        << " constraint rows (one back-substitution each when C_q changes)";
  }
  out << "\n";
  return kExitOk;
}

}  // namespace dnurbs::tools
