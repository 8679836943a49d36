#include "tools/eval_command.h"

#include <string>
#include <utility>
#include <variant>

#include <nlohmann/json.hpp>

#include "dnurbs/core/error.h"
#include "dnurbs/io/shape_file.h"
#include "tools/command_line.h"

namespace dnurbs::tools {

const char* const kEvalHelp = R"(usage: dnurbs eval SHAPE.json --at U [--at U ...] [--derivatives N]
       dnurbs eval SHAPE.json --at U,V [--at U,V ...] [--derivatives N]

Evaluates the curve or surface of a shape file at each --at parameter (a curve takes U, a
surface U,V) and prints JSON, every number the shortest decimal that reads back as the same
double:

  {"file": "SHAPE.json", "type": "nurbs_curve", "derivative_order": N,
   "evaluations": [{"u": U, "point": [x, y, z],
                    "derivatives": [C, C', ..., C^(N)]}, ...]}

  {"file": "SHAPE.json", "type": "nurbs_surface", "derivative_order": N,
   "evaluations": [{"u": U, "v": V, "point": [x, y, z],
                    "derivatives": {"S": [..], "Su": [..], "Sv": [..], "Suu": [..],
                                    "Suv": [..], "Svv": [..], ...}}, ...]}

Each derivative is an [x, y, z] vector; a surface key has one "u" per derivative in u and one
"v" per derivative in v (all k + l <= N, by total order, u first).

options:
  --at U | U,V        parameter to evaluate at (repeatable, at least one)
  --derivatives N     highest derivative order, 0..15 (default 1)
  -h, --help          this help

exit codes: 0 ok, 1 bad shape file or parameter, 2 bad command line
)";

namespace {

// The output is always valid JSON: a non-finite value (the shape's coordinates or weights
// overflow a double at that parameter) is an Error naming the place and the quantity.
nlohmann::ordered_json json_vector(const Eigen::Vector3d& v, const std::string& file,
                                   const std::string& flag, const std::string& quantity) {
  if (!v.allFinite()) {
    throw make_error(file, ": --at ", flag, ": ", quantity, " = (", v.x(), ", ", v.y(), ", ", v.z(),
                     ") is not finite (the shape's coordinates or weights overflow a double "
                     "there)");
  }
  return {v.x(), v.y(), v.z()};
}

nlohmann::ordered_json evaluate(const NurbsCurve& curve, const std::vector<double>& at, int order,
                                const std::string& file, const std::string& flag) {
  if (at.size() != 1) {
    throw make_error(file, ": --at ", flag, ": a curve takes one parameter u, got ", at.size());
  }
  CurveDerivatives derivatives;
  try {
    curve.derivatives(at[0], order, derivatives);
  } catch (const Error& error) {
    throw make_error(file, ": --at ", flag, ": ", error.what());
  }
  nlohmann::ordered_json values = nlohmann::ordered_json::array();
  for (int k = 0; k <= order; ++k) {
    values.push_back(json_vector(derivatives.row(k).transpose(), file, flag,
                                 "the derivative of order " + std::to_string(k)));
  }
  return {{"u", at[0]},
          {"point", json_vector(derivatives.row(0).transpose(), file, flag, "the point")},
          {"derivatives", std::move(values)}};
}

nlohmann::ordered_json evaluate(const NurbsSurface& surface, const std::vector<double>& at,
                                int order, const std::string& file, const std::string& flag) {
  if (at.size() != 2) {
    throw make_error(file, ": --at ", flag, ": a surface takes two parameters u,v, got ",
                     at.size());
  }
  SurfaceDerivatives derivatives;
  try {
    surface.derivatives(at[0], at[1], order, derivatives);
  } catch (const Error& error) {
    throw make_error(file, ": --at ", flag, ": ", error.what());
  }
  // Keys in total order, u first (an ordered_json keeps them as inserted)
  nlohmann::ordered_json values = nlohmann::ordered_json::object();
  for (int total = 0; total <= order; ++total) {
    for (int k = total; k >= 0; --k) {
      const int l = total - k;
      std::string name = "S";
      name.append(static_cast<size_t>(k), 'u');
      name.append(static_cast<size_t>(l), 'v');
      values[name] = json_vector(derivatives(k, l), file, flag, name);
    }
  }
  return {{"u", at[0]},
          {"v", at[1]},
          {"point", json_vector(derivatives(0, 0), file, flag, "the point")},
          {"derivatives", std::move(values)}};
}

}  // namespace

int eval_command(const std::vector<std::string>& arguments, std::ostream& out) {
  std::string file;
  std::vector<std::string> at_flags;
  int order = 1;
  CLI::App app("dnurbs eval");
  app.add_option("SHAPE", file)->required();
  app.add_option("--at", at_flags)->required()->allow_extra_args(false);
  app.add_option("--derivatives", order)->transform(integer_in(0, kMaxDerivativeOrder));
  if (!parse_command_line(app, arguments, kEvalHelp, out)) {
    return kExitOk;
  }
  std::vector<std::vector<double>> parameters;
  parameters.reserve(at_flags.size());
  for (const auto& flag : at_flags) {
    parameters.push_back(parse_doubles(flag, "--at " + flag));
  }

  const Shape shape = read_shape_file(file);
  const bool is_curve = std::holds_alternative<NurbsCurve>(shape);
  // Build the whole output first so that an error prints nothing on stdout
  nlohmann::ordered_json evaluations = nlohmann::ordered_json::array();
  for (size_t i = 0; i < parameters.size(); ++i) {
    evaluations.push_back(std::visit(
        [&](const auto& value) { return evaluate(value, parameters[i], order, file, at_flags[i]); },
        shape));
  }
  print_json(out, {{"file", file},
                   {"type", is_curve ? "nurbs_curve" : "nurbs_surface"},
                   {"derivative_order", order},
                   {"evaluations", std::move(evaluations)}});
  return kExitOk;
}

}  // namespace dnurbs::tools
