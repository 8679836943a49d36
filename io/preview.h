#pragma once
// PNG previews of meshes and energy plots of run logs, rendered by tools/preview_mesh.py and
// tools/plot_energy.py (python3 with matplotlib).

#include <filesystem>
#include <string>
#include <vector>

namespace dnurbs {

/// File name of the preview script.
inline constexpr const char* kPreviewScriptName = "preview_mesh.py";
/// File name of the script that plots the energies of a run's log.csv over time.
inline constexpr const char* kEnergyPlotScriptName = "plot_energy.py";

/// The first directory of `directories` that holds the script `name`, as the script's path.
/// Throws Error naming the script and listing the directories searched if none does.
std::filesystem::path find_preview_script(const std::vector<std::filesystem::path>& directories,
                                          const char* name = kPreviewScriptName);

/// The first interpreter of `candidates` (commands or paths) that can import matplotlib.
/// Throws Error naming the candidates tried (and that python3-matplotlib is needed) otherwise.
std::string find_python_with_matplotlib(const std::vector<std::string>& candidates = {
                                            "python3", "/usr/bin/python3"});

/// Runs `python script mesh.obj <temporary>` (or any script and input of the same form: the
/// energy plot of a log.csv) and renames the PNG it writes to `png` (so a
/// failed render leaves no partial file). Throws Error with the script's output if the mesh does
/// not exist, the script fails, or it writes no PNG.
void render_preview(const std::string& python, const std::filesystem::path& script,
                    const std::filesystem::path& mesh, const std::filesystem::path& png);

}  // namespace dnurbs
