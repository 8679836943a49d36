#pragma once
// `dnurbs run` (the default demo), `dnurbs export` and `dnurbs preview`.

#include <ostream>
#include <string>
#include <vector>

namespace dnurbs::tools {

extern const char* const kRunHelp;
extern const char* const kExportHelp;
extern const char* const kPreviewHelp;

/// Each takes the arguments after its subcommand's name and reports what it wrote to `out`.
/// They throw UsageError for a bad command line and Error for failed processing.
/// `program` is argv[0] (to find the preview script of an installed dnurbs).
int run_command(const std::vector<std::string>& arguments, const std::string& program,
                std::ostream& out);
int export_command(const std::vector<std::string>& arguments, std::ostream& out);
int preview_command(const std::vector<std::string>& arguments, const std::string& program,
                    std::ostream& out);

}  // namespace dnurbs::tools
