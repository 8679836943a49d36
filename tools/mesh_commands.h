#pragma once
// `dnurbs export` and `dnurbs preview`, and the PNG preview rendering `dnurbs run` shares.

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace dnurbs::tools {

extern const char* const kExportHelp;
extern const char* const kPreviewHelp;

/// Each takes the arguments after its subcommand's name and reports what it wrote to `out`.
/// They throw UsageError for a bad command line and Error for failed processing.
/// `program` is argv[0] (to find the preview script of an installed dnurbs).
int export_command(const std::vector<std::string>& arguments, std::ostream& out);
/// Renders a shaded PNG of an OBJ mesh with preview_mesh.py (found beside `program`, in the
/// source tree or the install prefix; python from DNURBS_PYTHON or python3). Throws Error.
void render_preview_png(const std::string& program, const std::filesystem::path& mesh,
                        const std::filesystem::path& png);

/// Plots the kinetic, elastic and total energies of a run's log.csv over time into a PNG with
/// plot_energy.py (found like preview_mesh.py). Throws Error.
void render_energy_png(const std::string& program, const std::filesystem::path& log,
                       const std::filesystem::path& png);

int preview_command(const std::vector<std::string>& arguments, const std::string& program,
                    std::ostream& out);

}  // namespace dnurbs::tools
