#include "tools/serve_command.h"

#include <filesystem>
#include <optional>
#include <utility>

#include "dnurbs/core/error.h"
#include "dnurbs/io/scene.h"
#include "dnurbs/sculpt/sculpt_server.h"
#include "dnurbs/sculpt/sculpt_session.h"
#include "tools/command_line.h"
#include "tools/run_command.h"

namespace dnurbs::tools {

const char* const kServeHelp =
    R"(usage: dnurbs serve [SCENE.json] [--port N] [--host ADDR] [--out DIR] [options]

Runs a scene (default: the sculpting demo, the default demo of `dnurbs run` without its
scripted springs and pressure) and serves the sculpting page at http://HOST:PORT/: drag a
shape to pull it with a mouse spring, shift-drag to push it, ctrl-click to pin a point; sliders
for the spring stiffness, the material and the time step; play, pause, step, reset, undo, save.
The first line printed gives the address. SIGINT or SIGTERM stops the server (exit code 0).

options:
  --port N          TCP port, 0..65535 (default 8080; 0: a free port, printed)
  --host ADDR       IP address to bind (default 127.0.0.1, this machine only; another address
                    lets other machines sculpt and save here)
  --out DIR         where `save` writes shape files and OBJ meshes (default ./dnurbs-out)
  --rate HZ         simulation steps a second of wall time, 1..1000 (default 60)
  --resolution N    mesh segments per direction of the page's meshes, 3..256 (default 24)
  --web DIR         the page's files (default: the source tree's or the installed web/)
  -h, --help        this help

exit codes: 0 stopped by a signal, 1 bad scene or address, 2 bad command line
)";

namespace {

// The sculpting demo: the default demo of `dnurbs run` without the forces that sculpt it by
// script (its springs and the torus's pressure pulse); gravity on the pendulum stays.
Scene sculpting_demo_scene() {
  Scene scene = parse_scene_json(kDefaultSceneJson, "<sculpting demo>");
  std::erase_if(scene.forces, [](const SceneForce& force) {
    return force.spec->type() == "spring" || force.spec->type() == "pressure";
  });
  scene.description =
      "The sculpting demo of `dnurbs serve`: a flat clamped D-NURBS sheet (hat), "
      "a D-NURBS torus and a superquadric pendulum, waiting to be sculpted.";
  return scene;
}

std::filesystem::path default_web_root() {
  for (const char* directory : {DNURBS_SOURCE_WEB_DIR, DNURBS_INSTALLED_WEB_DIR}) {
    if (std::filesystem::is_regular_file(std::filesystem::path(directory) / "index.html")) {
      return directory;
    }
  }
  return DNURBS_INSTALLED_WEB_DIR;
}

}  // namespace

int serve_command(const std::vector<std::string>& arguments, std::ostream& out) {
  std::optional<std::string> scene_file;  // absent: the built-in default scene
  SculptServerOptions server;
  std::string web_root = default_web_root().string();
  SculptSessionOptions session_options;
  std::string output_directory = session_options.output_directory.string();
  int port = server.port;
  CLI::App app("dnurbs serve");
  app.add_option("SCENE", scene_file);
  app.add_option("--port", port)->transform(integer_in(0, 65535));
  app.add_option("--host", server.host);
  app.add_option("--out", output_directory);
  app.add_option("--rate", server.steps_per_second)->transform(integer_in(1, 1000));
  app.add_option("--resolution", session_options.resolution)->transform(integer_in(3, 256));
  app.add_option("--web", web_root);
  if (!parse_command_line(app, arguments, kServeHelp, out)) {
    return kExitOk;
  }
  server.port = static_cast<unsigned short>(port);
  server.web_root = web_root;
  session_options.output_directory = output_directory;
  Scene scene = scene_file ? read_scene_file(*scene_file) : sculpting_demo_scene();
  SculptSession session(std::move(scene), session_options);
  SculptServer listener(session, server);
  out << "dnurbs serve: listening on http://" << server.host << ":" << listener.port() << "/ ("
      << (server.host == "127.0.0.1" ? "this machine only; --host ADDR to change"
                                     : "reachable from other machines")
      << ")" << std::endl;
  listener.run();
  out << "dnurbs serve: stopped" << std::endl;
  return kExitOk;
}

}  // namespace dnurbs::tools
