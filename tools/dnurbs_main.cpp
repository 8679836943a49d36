// The dnurbs command: evaluate, tessellate, export and preview shapes; run and inspect scenes.

#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "dnurbs/core/error.h"
#include "dnurbs/core/version.h"
#include "tools/command_line.h"
#include "tools/design_command.h"
#include "tools/eval_command.h"
#include "tools/fit_command.h"
#include "tools/import_command.h"
#include "tools/info_command.h"
#include "tools/make_command.h"
#include "tools/mesh_commands.h"
#include "tools/run_command.h"
#include "tools/serve_command.h"

namespace {

constexpr const char* kHelp = R"(usage: dnurbs COMMAND [ARGS...]

commands:
  eval SHAPE.json --at U[,V] ...   points and derivatives of a curve or surface, as JSON
  run [SCENE.json] [--out DIR]     run a scene (default: the built-in demo): meshes, CSV log,
                                   checkpoints, PNG preview; --resume CHECKPOINT continues
  info [SCENE.json]                models, coordinates, constant matrices, cost per step
  make KIND OUT.json [--KEY V...]  a shape file: line, plane, box, cylinder, cone, sphere, torus,
                                   revolve, extrude or loft
  export SHAPE.json MESH           tessellate a shape into .obj/.stl/.ply/.gltf/.glb, or write
                                   shapes as NURBS to .step/.stp/.iges/.igs
  import PART OUT.json             the curves and surfaces of a STEP or IGES file as shape files
  preview MESH.obj OUT.png         shaded PNG of an OBJ mesh (python3 + matplotlib)
  fit superquadric|surface POINTS  fit a superquadric or a D-NURBS surface to points, as JSON
  design SCENE.json [--out DIR]    energy-minimizing static shape under forces and constraints
  serve [SCENE.json] [--port N]    sculpt a scene in the browser (http://127.0.0.1:N/)

Run `dnurbs COMMAND --help` for a command's options; `dnurbs --version` prints the version.
exit codes: 0 ok, 1 bad input or failed processing, 2 bad command line
)";

}  // namespace

int main(int argc, char** argv) {
  using namespace dnurbs::tools;
  const std::vector<std::string> arguments(argv + 1, argv + argc);
  if (arguments.empty()) {
    std::cerr << kHelp;
    return kExitUsage;
  }
  const std::string& command = arguments.front();
  if (command == "-h" || command == "--help" || command == "help") {
    std::cout << kHelp;
    return kExitOk;
  }
  if (command == "--version" || command == "version") {
    std::cout << "dnurbs " << dnurbs::kVersion << "\n";
    return kExitOk;
  }
  const std::vector<std::string> rest(arguments.begin() + 1, arguments.end());
  const std::string program = argc > 0 ? argv[0] : "dnurbs";
  try {
    if (command == "eval") {
      return eval_command(rest, std::cout);
    }
    if (command == "run") {
      return run_command(rest, program, std::cout, std::cerr);
    }
    if (command == "info") {
      return info_command(rest, std::cout);
    }
    if (command == "make") {
      return make_command(rest, std::cout);
    }
    if (command == "import") {
      return import_command(rest, std::cout);
    }
    if (command == "export") {
      return export_command(rest, std::cout);
    }
    if (command == "fit") {
      return fit_command(rest, std::cout, std::cerr);
    }
    if (command == "design") {
      return design_command(rest, std::cout, std::cerr);
    }
    if (command == "serve") {
      return serve_command(rest, std::cout);
    }
    if (command == "preview") {
      return preview_command(rest, program, std::cout);
    }
    std::cerr << "dnurbs: unknown command \"" << command << "\"\n\n" << kHelp;
    return kExitUsage;
  } catch (const UsageError& error) {
    std::cerr << "dnurbs " << command << ": " << error.what() << "\n"
              << "run `dnurbs " << command << " --help` for usage\n";
    return kExitUsage;
  } catch (const dnurbs::Error& error) {
    std::cerr << "dnurbs " << command << ": error: " << error.what() << "\n";
    return kExitError;
  } catch (const std::exception& error) {
    std::cerr << "dnurbs " << command << ": unexpected error: " << error.what() << "\n";
    return kExitError;
  }
}
