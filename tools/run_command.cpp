#include "tools/run_command.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>

#include "dnurbs/core/error.h"
#include "dnurbs/core/progress_report.h"
#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_runner.h"
#include "dnurbs/io/scene_simulation.h"
#include "tools/command_line.h"
#include "tools/mesh_commands.h"

namespace dnurbs::tools {

const char* const kRunHelp =
    R"(usage: dnurbs run [SCENE.json] [--out DIR] [--resume CHECKPOINT] [options]

Runs a scene file (docs/scene-format.md) and writes into DIR (default ./dnurbs-out):
  log.csv                   step, time, kinetic/potential/total energy, constraint violations
                            and probe positions (every output.log_every steps)
  frames/NAME_STEP.FORMAT   meshes of every model every output.mesh_every steps (the first
                            of output.format)
  checkpoint.json           the state every output.checkpoint_every steps and at the end
  NAME.FORMAT               the final meshes, in every output.format (OBJ by default), and
                            with output.preview NAME.png and energy.png (the energies of
                            log.csv over time)
  MODEL.json                final D-NURBS shapes with output.shape_files
Every file is written to a temporary file and renamed, so a killed run leaves no partial file.

Without SCENE.json runs the built-in default demo (examples/scenes/hat_demo.json): a flat
D-NURBS sheet with a clamped border sculpted into a hat by springs pulling its centre up over
time (damping, Newmark), a D-NURBS torus inflated by a pressure pulse, and a superquadric
pendulum (a link held at a pivot, a rounded cube hanging from it by a ball joint) swinging under
gravity; it writes OBJ frames, log.csv (with the joints' max_violation), the final mesh demo.obj,
its preview demo.png, the energy plot energy.png and the final shapes hat.json and
torus.json.

A step that diverges (a non-finite state or an energy above integrator.max_energy) stops the
run: the last good state is written (checkpoint.json and the final mesh) and the exit code is 1.

options:
  --out DIR             output directory (created if missing)
  --resume CHECKPOINT   continue the run from a checkpoint of the same scene (log.csv in DIR is
                        continued from the checkpoint's step)
  --resolution N        mesh segments per direction, 3..1024 (overrides output.resolution)
  --stop-after N        stop after N steps in total without writing the final state (as if
                        killed there; for testing --resume)
  --no-preview          skip the PNG previews (NAME.png and energy.png)
  --quiet               print nothing but errors (no progress, no list of files written)
  -h, --help            this help

Set DNURBS_PYTHON to choose the python interpreter for the preview.
exit codes: 0 ok, 1 bad scene, failed output or diverged run, 2 bad command line
)";

const char* const kDefaultSceneJson = R"json({
  "description": "The default demo of `dnurbs run`: a flat D-NURBS sheet with a clamped border is sculpted into a hat by springs that pull its centre up over time (damping, Newmark), while a D-NURBS torus beside it is inflated by a pressure pulse and, on its other side, a superquadric pendulum (a slim link held at a pivot, a rounded cube hanging from it by a ball joint) swings under gravity.",
  "models": [
    {
      "name": "hat",
      "type": "dnurbs_surface",
      "make": {"kind": "plane", "size": [2.4, 2.4], "domain": [1, 1], "control_points": [7, 7], "origin": [-1.2, -1.2, 0]},
      "material": {
        "mass_density": 1.0,
        "damping_density": 4.0,
        "a10": 1.0,
        "a01": 1.0,
        "b20": 0.2,
        "b11": 0.2,
        "b02": 0.2
      },
      "boundary": {
        "clamp_border": true
      }
    },
    {
      "name": "torus",
      "type": "dnurbs_surface",
      "make": {"kind": "torus", "major_radius": 0.8, "minor_radius": 0.28, "periodic": true, "translate": [2.6, 0, 0.28]},
      "material": {
        "mass_density": 1.0,
        "damping_density": 1.0
      },
      "resolution_scale": [1.0, 0.5]
    },
    {
      "name": "link",
      "type": "superquadric",
      "shape": {"a1": 0.07, "a2": 0.07, "a3": 0.35},
      "centre": [-2.5992482472771337, 0.0, 1.1132967844988528],
      "orientation": [0.9537169507482269, 0, -0.3007057995042731, 0],
      "parts": "rigid",
      "mesh_cells": [4, 8],
      "quadrature_points": 2,
      "material": {
        "mass_density": 1.0,
        "damping_alpha": 0.2
      }
    },
    {
      "name": "bob",
      "type": "superquadric",
      "shape": {"a1": 0.22, "a2": 0.22, "a3": 0.22, "e1": 0.5, "e2": 0.5},
      "centre": [-2.2723096785570376, 0.0, 0.6463801192541274],
      "orientation": [0.9537169507482269, 0, -0.3007057995042731, 0],
      "parts": "rigid",
      "mesh_cells": [4, 8],
      "quadrature_points": 2,
      "material": {
        "mass_density": 1.0,
        "damping_alpha": 0.2
      }
    }
  ],
  "forces": [
    {
      "type": "spring",
      "model": "hat",
      "at": [0.5, 0.5],
      "stiffness": 150.0,
      "target": {
        "times": [0.0, 1.0, 2.0],
        "values": [[0, 0, 0], [0, 0, 0.9], [0, 0, 1.2]]
      }
    },
    {
      "type": "spring",
      "model": "hat",
      "at": [0.38, 0.38],
      "stiffness": 60.0,
      "target": [-0.25, -0.25, 0.9],
      "start": 0.5
    },
    {
      "type": "spring",
      "model": "hat",
      "at": [0.62, 0.38],
      "stiffness": 60.0,
      "target": [0.25, -0.25, 0.9],
      "start": 0.5
    },
    {
      "type": "spring",
      "model": "hat",
      "at": [0.38, 0.62],
      "stiffness": 60.0,
      "target": [-0.25, 0.25, 0.9],
      "start": 0.5
    },
    {
      "type": "spring",
      "model": "hat",
      "at": [0.62, 0.62],
      "stiffness": 60.0,
      "target": [0.25, 0.25, 0.9],
      "start": 0.5
    },
    {
      "type": "pressure",
      "model": "torus",
      "pressure": {
        "times": [0.0, 0.6, 1.2],
        "values": [0.0, 0.015, 0.0]
      }
    }
,
    {
      "type": "gravity",
      "model": "link",
      "acceleration": [0, 0, -9.81]
    },
    {
      "type": "gravity",
      "model": "bob",
      "acceleration": [0, 0, -9.81]
    }
  ],
  "constraints": [
    {
      "type": "point_target",
      "model": "link",
      "at": [1.5707963267948966, 0],
      "target": [-2.8, 0.0, 1.4]
    },
    {
      "type": "point_to_point",
      "model_a": "link",
      "at_a": [-1.5707963267948966, 0],
      "model_b": "bob",
      "at_b": [1.5707963267948966, 0]
    }
  ],
  "integrator": {
    "scheme": "newmark",
    "dt": 0.01
  },
  "run": {
    "steps": 200
  },
  "probes": [
    {
      "name": "crown",
      "model": "hat",
      "at": [0.5, 0.5]
    },
    {
      "name": "brim",
      "model": "hat",
      "at": [0.2, 0.5]
    }
  ],
  "output": {
    "name": "demo",
    "mesh_every": 20,
    "resolution": 48,
    "preview": true,
    "shape_files": true,
    "checkpoint_every": 50
  }
}
)json";

int run_command(const std::vector<std::string>& arguments, const std::string& program,
                std::ostream& out, std::ostream& err) {
  SceneRunOptions options;
  std::optional<std::string> scene_file;  // absent: the built-in default scene
  std::string output_directory = options.output_directory.string();
  std::optional<std::string> resume;
  bool no_preview = false;
  bool quiet = false;
  CLI::App app("dnurbs run");
  app.add_option("SCENE", scene_file);
  app.add_option("--out", output_directory);
  app.add_option("--resume", resume);
  app.add_option("--resolution", options.resolution)->transform(integer_in(3, 1024));
  app.add_option("--stop-after", options.stop_after)->transform(integer_in(0, 100000000));
  app.add_flag("--no-preview", no_preview);
  app.add_flag("--quiet", quiet);
  if (!parse_command_line(app, arguments, kRunHelp, out)) {
    return kExitOk;
  }
  options.output_directory = output_directory;
  if (resume) {
    options.resume = *resume;
  }
  const bool preview = !no_preview;

  std::ostream silent(nullptr);  // no buffer: what is written to it goes nowhere
  std::ostream& shown = quiet ? silent : out;
  const Scene scene = scene_file ? read_scene_file(*scene_file)
                                 : parse_scene_json(kDefaultSceneJson, "<default demo>");
  SceneSimulation simulation(scene);
  const System& system = simulation.system();
  shown << "scene " << scene.source << ": " << system.model_count() << " model(s), "
        << system.velocity_count() << " velocities (" << system.fixed_coordinates().size()
        << " fixed), " << scene.forces.size() << " force(s), "
        << simulation.constraints().constraint_count() << " constraint(s); " << scene.step_count()
        << " steps of dt = " << scene.integrator.dt << " (" << scene.integrator.scheme << ")\n";
  if (options.resume) {
    shown << "resuming from " << options.resume->string() << "\n";
  }

  // Steps done, the rate, the time left, the simulated time and the energy (core/progress_report.h)
  ProgressReport progress(shown, "step", ::isatty(STDOUT_FILENO) == 1);
  const SceneRunResult result = run_scene(simulation, options, [&](const SceneRunProgress& p) {
    if (!quiet) {
      std::ostringstream detail;
      detail << "t = " << p.time << ", energy " << p.energy;
      progress.update(p.step, p.total, detail.str());
    }
  });
  progress.finish();
  const double seconds = progress.elapsed_seconds();

  if (result.stopped) {
    shown << "stopped after step " << result.steps_done << " of " << result.total_steps
          << " (--stop-after); continue with --resume "
          << (options.output_directory / "checkpoint.json").string() << "\n";
    return kExitOk;
  }
  shown << "ran " << result.steps_done << " of " << result.total_steps << " steps in " << seconds
        << " s (t = " << system.time() << ")\n";
  shown << "wrote " << result.log.string() << "\n";
  if (result.frames_written > 0) {
    shown << "wrote " << result.frames_written << " mesh frame(s) to "
          << (options.output_directory / "frames").string() << "\n";
  }
  for (const auto& mesh : result.final_meshes) {
    shown << "wrote " << mesh.string() << " (final state)\n";
  }
  for (const auto& shape : result.shape_files) {
    shown << "wrote " << shape.string() << " (final shape)\n";
  }
  shown << "wrote " << result.checkpoint.string() << " (step " << result.steps_done << ")\n";
  if (result.diverged) {
    err << "dnurbs run: error: " << result.message << "\n"
        << "dnurbs run: the run stopped; the last good state (step " << result.steps_done
        << ", t = " << system.time() << ") is in " << result.checkpoint.string()
        << (result.final_mesh.empty() ? std::string() : " and " + result.final_mesh.string())
        << "\n";
    return kExitError;
  }
  const ConstraintReport& report = simulation.constraints().last_report();
  if (!report.message.empty()) {
    shown << "constraints: " << report.message << "\n";
  }
  if (scene.output.preview && preview && !result.final_mesh.empty()) {
    std::filesystem::path png = result.final_mesh;
    png.replace_extension(".png");
    render_preview_png(program, result.final_mesh, png);
    shown << "wrote " << png.string() << " (shaded preview of the final frame)\n";
    const std::filesystem::path energy = result.log.parent_path() / "energy.png";
    render_energy_png(program, result.log, energy);
    shown << "wrote " << energy.string() << " (energies over time)\n";
  }
  return kExitOk;
}

}  // namespace dnurbs::tools
