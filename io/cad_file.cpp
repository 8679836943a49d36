#include "dnurbs/io/cad_file.h"

#include <string>

#include "dnurbs/core/error.h"
#include "dnurbs/core/input_file.h"
#include "dnurbs/io/atomic_write.h"
#if DNURBS_WITH_CAD
#include "dnurbs/cad/iges_file.h"
#include "dnurbs/cad/step_file.h"
#endif

namespace dnurbs {
namespace {

CadFormat checked_format(const std::filesystem::path& path) {
  const std::optional<CadFormat> format = cad_format_of(path);
  if (!format) {
    throw make_error(path.string(),
                     ": not a CAD file name (the extension must be .step, .stp, "
                     ".iges or .igs, not \"",
                     printable_excerpt(lowercase_extension(path)), "\")");
  }
  if (!cad_exchange_available()) {
    throw make_error(path.string(),
                     ": this dnurbs was built without STEP and IGES exchange; install Open "
                     "CASCADE (libocct-data-exchange-dev, scripts/install_dependencies.sh) and "
                     "build again");
  }
  return *format;
}

}  // namespace

std::optional<CadFormat> cad_format_of(const std::filesystem::path& path) {
  const std::string extension = lowercase_extension(path);
  if (extension == ".step" || extension == ".stp") {
    return CadFormat::step;
  }
  if (extension == ".iges" || extension == ".igs") {
    return CadFormat::iges;
  }
  return std::nullopt;
}

bool cad_exchange_available() {
  return DNURBS_WITH_CAD != 0;
}

std::vector<Shape> read_cad_file(const std::filesystem::path& path) {
  const CadFormat format = checked_format(path);
  check_input_file(path, format == CadFormat::step ? "STEP file" : "IGES file");
  std::vector<Shape> shapes;
#if DNURBS_WITH_CAD
  shapes = format == CadFormat::step ? read_step_file(path) : read_iges_file(path);
#endif
  if (shapes.empty()) {
    throw make_error(path.string(), ": the file holds no curve or surface");
  }
  return shapes;
}

void write_cad_file(const std::filesystem::path& path, const std::vector<Shape>& shapes) {
  const CadFormat format = checked_format(path);
  if (shapes.empty()) {
    throw make_error(path.string(), ": nothing to write (no shapes)");
  }
  std::string text;
#if DNURBS_WITH_CAD
  text = format == CadFormat::step ? step_text(shapes) : iges_text(shapes);
#endif
  write_file_atomically(path, text);
}

}  // namespace dnurbs
