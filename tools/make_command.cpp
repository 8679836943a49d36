#include "tools/make_command.h"

#include <algorithm>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "dnurbs/core/error.h"
#include "dnurbs/io/scene_reader.h"
#include "dnurbs/io/shape_file.h"
#include "dnurbs/io/shape_recipe.h"
#include "tools/command_line.h"

namespace dnurbs::tools {

const char* const kMakeHelp =
    R"(usage: dnurbs make KIND OUT.json [--KEY VALUE ...]

Writes the shape file of a generated shape. KIND and its keys (defaults in brackets; docs/
scene-format.md, "Generated shapes", has the details; a scene model's "make" key takes the same
recipe as JSON):
  line      --start X,Y,Z [0,0,0] --end X,Y,Z [1,0,0] --control-points N [4] --degree P [3]
  plane     --size X,Y [1,1] --control-points NU,NV [4,4] --degree PU,PV [3,3]
            --origin X,Y,Z [0,0,0]
  box       --size X,Y,Z [1,1,1]
  cylinder  --radius R [1] --height H [1] --profile-control-points N [4]
  cone      --radius R [1] --height H [1] --profile-control-points N [4]
  sphere    --radius R [1]
  torus     --major-radius R [1] --minor-radius r [0.25]
  revolve   --profile CURVE.json --angle-degrees A [360]
  extrude   --curve CURVE.json --direction X,Y,Z [0,0,1]
  loft      --sections '["a.json", "b.json", ...]' --degree Q [3]
every kind: --split PU,PV (surfaces) or P (curves): split every knot span into equal parts;
            --translate X,Y,Z: move the shape.

Every shape is at rest as made in a scene model with "rest_shape": "initial" (the energy of the
change from it). Lines and planes have their control points at the Greville abscissae: they are
linear in their parameters and at rest under the D-NURBS energy measured from zero too when
their border is clamped. A VALUE is JSON (a number, an array, an object, a quoted string), or
comma-separated numbers, or else a file name.

exit codes: 0 ok, 1 a value a generator rejects or an unwritable file, 2 bad command line
)";

namespace {

// "control_points" -> "--control-points"
std::string recipe_flag(const std::string& key) {
  std::string flag = "--" + key;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

// A flag's value as JSON: JSON itself, comma-separated numbers as an array, otherwise a string.
nlohmann::json recipe_value(const std::string& text) {
  nlohmann::json value = nlohmann::json::parse(text, nullptr, false);
  if (!value.is_discarded()) {
    return value;
  }
  if (text.find(',') != std::string::npos) {
    value = nlohmann::json::parse("[" + text + "]", nullptr, false);
    if (!value.is_discarded()) {
      return value;
    }
  }
  return text;
}

}  // namespace

int make_command(const std::vector<std::string>& arguments, std::ostream& out) {
  std::string kind;
  std::string output;
  CLI::App app("dnurbs make");
  app.add_option("KIND", kind)->required();
  app.add_option("OUT", output)->required();
  // Every key of the recipe kinds (io/shape_recipe.h) is an option: "--control-points" is the
  // key "control_points". A key that does not apply to the kind is refused by the recipe
  // reader, naming the kind.
  const std::vector<const char*>& keys = shape_recipe_keys();
  std::vector<std::string> values(keys.size());
  std::vector<const CLI::Option*> options(keys.size());
  for (size_t k = 0; k < keys.size(); ++k) {
    options[k] = app.add_option(recipe_flag(keys[k]), values[k]);
  }
  if (!parse_command_line(app, arguments, kMakeHelp, out)) {
    return kExitOk;
  }
  nlohmann::json recipe = {{"kind", kind}};
  for (size_t k = 0; k < keys.size(); ++k) {
    if (options[k]->count() > 0) {
      recipe[keys[k]] = recipe_value(values[k]);
    }
  }
  const SceneReader reader("command line", std::filesystem::current_path());
  const Shape shape = make_shape(reader, recipe, "");
  write_shape_file(output, shape);
  out << output << ": " << shape_summary(shape) << "\n";
  return kExitOk;
}

}  // namespace dnurbs::tools
