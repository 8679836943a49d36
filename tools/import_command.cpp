#include "tools/import_command.h"

#include <filesystem>

#include "dnurbs/io/shape_file.h"
#include "tools/command_line.h"

namespace dnurbs::tools {

const char* const kImportHelp = R"(usage: dnurbs import PART OUT.json [--index K]

Reads the NURBS curves and surfaces of a STEP (.step, .stp), IGES (.iges, .igs) or OBJ (.obj,
its free-form curv and surf statements) file and writes each as a shape file: OUT.json for a file of one shape, else OUT-0.json, OUT-1.json, ... in the
file's order (STEP: faces, then free edges). --index K writes only shape K, to OUT.json.

Faces are read over their whole parameter rectangle: B-spline surfaces as they are, planes,
cylinders, cones, spheres, tori and swept surfaces in their exact NURBS form. A trimmed face
(bounded by anything but the border of its rectangle) is refused, naming its entity. Periodic
curves and surfaces written by dnurbs (`dnurbs export`) come back periodic.

options:
  --index K   only shape K (0-based)
)";

int import_command(const std::vector<std::string>& arguments, std::ostream& out) {
  std::vector<std::string> files(2);
  int index = -1;
  CLI::App app("dnurbs import");
  app.add_option("PART", files[0])->required();
  app.add_option("OUT", files[1])->required();
  app.add_option("--index", index)->transform(integer_in(0, 1 << 30));
  if (!parse_command_line(app, arguments, kImportHelp, out)) {
    return kExitOk;
  }
  const std::filesystem::path output = files[1];
  const std::vector<Shape> shapes = read_exchange_shapes(files[0]);
  if (index >= static_cast<int>(shapes.size())) {
    throw UsageError("--index " + std::to_string(index) + ": " + files[0] + " holds " +
                     std::to_string(shapes.size()) + " shapes (0.." +
                     std::to_string(shapes.size() - 1) + ")");
  }
  const auto write = [&](const std::filesystem::path& path, const Shape& shape) {
    write_shape_file(path, shape);
    out << path.string() << ": " << shape_summary(shape) << "\n";
  };
  if (index >= 0) {
    write(output, shapes[static_cast<size_t>(index)]);
  } else if (shapes.size() == 1) {
    write(output, shapes.front());
  } else {
    for (size_t k = 0; k < shapes.size(); ++k) {
      std::filesystem::path path = output;
      path.replace_filename(output.stem().string() + "-" + std::to_string(k) +
                            output.extension().string());
      write(path, shapes[k]);
    }
  }
  return kExitOk;
}

}  // namespace dnurbs::tools
