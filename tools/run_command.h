#pragma once
// `dnurbs run`: runs a scene file (or the built-in default demo) with a progress bar, writing
// meshes, the CSV log, checkpoints and the final state; `--resume` continues a run.

#include <ostream>
#include <string>
#include <vector>

namespace dnurbs::tools {

extern const char* const kRunHelp;
/// The default demo scene (the same as examples/scenes/hat_demo.json).
extern const char* const kDefaultSceneJson;

/// Takes the arguments after "run". Progress goes to `out` (a bar when stdout is a terminal,
/// plain lines otherwise), results to `out`. Returns the exit code: 0 done, 1 diverged (the last
/// good state written). Throws UsageError for a bad command line and Error for a bad scene.
int run_command(const std::vector<std::string>& arguments, const std::string& program,
                std::ostream& out, std::ostream& err);

}  // namespace dnurbs::tools
