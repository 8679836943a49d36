#include "tools/make_command.h"

#include <filesystem>
#include <variant>

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

Lines and planes have their control points at the Greville abscissae: they are linear in their
parameters and at rest under the D-NURBS energy with a clamped border. A VALUE is JSON (a number,
an array, an object, a quoted string), or comma-separated numbers, or else a file name.

exit codes: 0 ok, 1 a value a generator rejects or an unwritable file, 2 bad command line
)";

namespace {

// "--control-points" -> "control_points"
std::string recipe_key(const std::string& flag) {
  std::string key = flag.substr(2);
  for (char& c : key) {
    if (c == '-') {
      c = '_';
    }
  }
  return key;
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
  if (wants_help(arguments)) {
    out << kMakeHelp;
    return kExitOk;
  }
  nlohmann::json recipe = nlohmann::json::object();
  std::string output;
  for (size_t i = 0; i < arguments.size(); ++i) {
    const std::string& argument = arguments[i];
    if (argument.starts_with("--") && argument.size() > 2) {
      const std::string key = recipe_key(argument);
      if (key == "kind" || recipe.contains(key)) {
        throw UsageError("option " + argument +
                         (key == "kind" ? " is the first argument" : " given twice"));
      }
      recipe[key] = recipe_value(flag_value(arguments, i));
    } else if (argument.starts_with("-") && argument.size() > 1) {
      throw UsageError("unknown option " + argument);
    } else if (!recipe.contains("kind")) {
      recipe["kind"] = argument;
    } else if (output.empty()) {
      output = argument;
    } else {
      throw UsageError("unexpected argument " + argument + " (KIND and one output file)");
    }
  }
  if (!recipe.contains("kind")) {
    throw UsageError("missing the KIND of shape");
  }
  if (output.empty()) {
    throw UsageError("missing the output file OUT.json");
  }
  const SceneReader reader("command line", std::filesystem::current_path());
  const Shape shape = make_shape(reader, recipe, "");
  write_shape_file(output, shape);
  out << output << ": " << shape_summary(shape) << "\n";
  return kExitOk;
}

}  // namespace dnurbs::tools
