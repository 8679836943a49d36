#include "dnurbs/io/shape_file.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "dnurbs/core/error.h"
#include "dnurbs/core/input_file.h"
#include "dnurbs/io/atomic_write.h"
#include "dnurbs/io/cad_file.h"
#include "dnurbs/io/json_messages.h"
#include "dnurbs/io/obj_freeform.h"

namespace dnurbs {
namespace {

using Json = nlohmann::json;

// Reads typed values out of a parsed document; every failure names the source and JSON path.
class ShapeReader {
 public:
  explicit ShapeReader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& message) const {
    throw Error(source_ + ": " + path + ": " + message);
  }

  void check_keys(const Json& object, std::initializer_list<const char*> allowed) const {
    for (const auto& [key, value] : object.items()) {
      bool known = false;
      std::string list;
      for (const char* name : allowed) {
        known = known || key == name;
        list += list.empty() ? name : std::string(", ") + name;
      }
      if (!known) {
        fail(key, "unknown key (expected only " + list + ")");
      }
    }
  }

  const Json& require(const Json& object, const char* key, const char* expected) const {
    const auto found = object.find(key);
    if (found == object.end()) {
      fail(key, std::string("missing key (expected ") + expected + ")");
    }
    return *found;
  }

  int integer(const Json& value, const std::string& path, int minimum, int maximum) const {
    const std::string expected =
        "an integer in " + std::to_string(minimum) + ".." + std::to_string(maximum);
    if (!value.is_number_integer()) {
      fail(path, "expected " + expected + ", got " + describe_json_value(value));
    }
    const auto number = value.get<long long>();
    if (number < minimum || number > maximum) {
      fail(path, "expected " + expected + ", got " + describe_json_value(value));
    }
    return static_cast<int>(number);
  }

  bool boolean(const Json& object, const char* key) const {
    const auto found = object.find(key);
    if (found == object.end()) {
      return false;
    }
    if (!found->is_boolean()) {
      fail(key, "expected true or false, got " + describe_json_value(*found));
    }
    return found->get<bool>();
  }

  double finite_number(const Json& value, const std::string& path) const {
    if (!value.is_number()) {
      fail(path, "expected a finite number, got " + describe_json_value(value));
    }
    const double number = value.get<double>();
    if (!std::isfinite(number)) {
      fail(path, "expected a finite number, got " + format_json_number(number));
    }
    return number;
  }

  const Json& array(const Json& value, const std::string& path, const std::string& of) const {
    if (!value.is_array()) {
      fail(path, "expected an array of " + of + ", got " + describe_json_value(value));
    }
    return value;
  }

  std::vector<double> numbers(const Json& value, const std::string& path) const {
    array(value, path, "numbers");
    std::vector<double> result;
    result.reserve(value.size());
    for (size_t i = 0; i < value.size(); ++i) {
      result.push_back(finite_number(value[i], json_index_path(path, i)));
    }
    return result;
  }

  Eigen::Vector3d point(const Json& value, const std::string& path) const {
    if (!value.is_array() || value.size() != 3) {
      fail(path, "expected a point [x, y, z], got " + describe_json_value(value));
    }
    return {finite_number(value[0], json_index_path(path, 0)),
            finite_number(value[1], json_index_path(path, 1)),
            finite_number(value[2], json_index_path(path, 2))};
  }

  double weight(const Json& value, const std::string& path) const {
    const double w = finite_number(value, path);
    if (!(w > 0.0)) {
      fail(path, "expected a weight > 0, got " + format_json_number(w));
    }
    return w;
  }

  KnotVector knot_vector(const Json& object, const char* degree_key, const char* knots_key,
                         const char* periodic_key) const {
    const int degree =
        integer(require(object, degree_key, "an integer degree"), degree_key, 1, kMaxDegree);
    const std::vector<double> knots =
        numbers(require(object, knots_key, "an array of knots"), knots_key);
    const bool periodic = boolean(object, periodic_key);
    try {
      return periodic ? KnotVector::periodic(degree, knots) : KnotVector(degree, knots);
    } catch (const Error& error) {
      fail(knots_key, std::string(periodic ? "invalid periodic knots (one period, n + 1 values "
                                             "for n control points): "
                                           : "invalid knots: ") +
                          error.what());
    }
  }

  std::string count_reason(const KnotVector& knots, const char* degree_key,
                           const char* knots_key) const {
    const auto size = knots.is_periodic() ? knots.period_knots().size() : knots.knots().size();
    if (knots.is_periodic()) {
      return std::string("for ") + std::to_string(size) + " periodic " + knots_key +
             " (one per knot span)";
    }
    return std::string("for ") + degree_key + " " + std::to_string(knots.degree()) + " and " +
           std::to_string(size) + " " + knots_key + " (knots - degree - 1)";
  }

  Shape curve(const Json& root) const {
    check_keys(root, {"type", "degree", "knots", "control_points", "weights", "periodic"});
    const KnotVector knots = knot_vector(root, "degree", "knots", "periodic");
    const int n = knots.control_point_count();
    const Json& points = array(require(root, "control_points", "an array of [x, y, z] points"),
                               "control_points", "[x, y, z] points");
    if (static_cast<int>(points.size()) != n) {
      fail("control_points", "expected " + std::to_string(n) + " control points " +
                                 count_reason(knots, "degree", "knots") + ", got " +
                                 std::to_string(points.size()));
    }
    Eigen::MatrixX3d control_points(n, 3);
    for (int i = 0; i < n; ++i) {
      control_points.row(i) = point(points[static_cast<size_t>(i)],
                                    json_index_path("control_points", static_cast<size_t>(i)))
                                  .transpose();
    }
    Eigen::VectorXd weights = Eigen::VectorXd::Ones(n);
    if (const auto found = root.find("weights"); found != root.end()) {
      array(*found, "weights", "positive numbers");
      if (static_cast<int>(found->size()) != n) {
        fail("weights", "expected " + std::to_string(n) + " weights (one per control point), got " +
                            std::to_string(found->size()));
      }
      for (int i = 0; i < n; ++i) {
        weights(i) = weight((*found)[static_cast<size_t>(i)],
                            json_index_path("weights", static_cast<size_t>(i)));
      }
    }
    try {
      return NurbsCurve(knots, std::move(control_points), std::move(weights));
    } catch (const Error& error) {
      throw Error(source_ + ": invalid curve: " + error.what());
    }
  }

  Shape surface(const Json& root) const {
    check_keys(root, {"type", "degree_u", "degree_v", "knots_u", "knots_v", "control_points",
                      "weights", "periodic_u", "periodic_v"});
    const KnotVector knots_u = knot_vector(root, "degree_u", "knots_u", "periodic_u");
    const KnotVector knots_v = knot_vector(root, "degree_v", "knots_v", "periodic_v");
    const int m = knots_u.control_point_count();
    const int n = knots_v.control_point_count();
    const Json& rows = array(require(root, "control_points", "rows (along u) of [x, y, z] points"),
                             "control_points", "rows (along u) of [x, y, z] points");
    if (static_cast<int>(rows.size()) != m) {
      fail("control_points", "expected " + std::to_string(m) + " rows along u " +
                                 count_reason(knots_u, "degree_u", "knots_u") + ", got " +
                                 std::to_string(rows.size()));
    }
    Eigen::MatrixX3d control_points(m * n, 3);
    for (int i = 0; i < m; ++i) {
      const std::string row_path = json_index_path("control_points", static_cast<size_t>(i));
      const Json& row = array(rows[static_cast<size_t>(i)], row_path, "[x, y, z] points");
      if (static_cast<int>(row.size()) != n) {
        fail(row_path, "expected " + std::to_string(n) + " points along v " +
                           count_reason(knots_v, "degree_v", "knots_v") + ", got " +
                           std::to_string(row.size()));
      }
      for (int j = 0; j < n; ++j) {
        control_points.row(i * n + j) =
            point(row[static_cast<size_t>(j)], json_index_path(row_path, static_cast<size_t>(j)))
                .transpose();
      }
    }
    Eigen::VectorXd weights = Eigen::VectorXd::Ones(m * n);
    if (const auto found = root.find("weights"); found != root.end()) {
      array(*found, "weights", "rows (along u) of positive numbers");
      if (static_cast<int>(found->size()) != m) {
        fail("weights", "expected " + std::to_string(m) +
                            " rows along u (one per row of control_points), got " +
                            std::to_string(found->size()));
      }
      for (int i = 0; i < m; ++i) {
        const std::string row_path = json_index_path("weights", static_cast<size_t>(i));
        const Json& row = array((*found)[static_cast<size_t>(i)], row_path, "positive numbers");
        if (static_cast<int>(row.size()) != n) {
          fail(row_path, "expected " + std::to_string(n) +
                             " weights (one per control point of the row), got " +
                             std::to_string(row.size()));
        }
        for (int j = 0; j < n; ++j) {
          weights(i * n + j) = weight(row[static_cast<size_t>(j)],
                                      json_index_path(row_path, static_cast<size_t>(j)));
        }
      }
    }
    try {
      return NurbsSurface(knots_u, knots_v, std::move(control_points), std::move(weights));
    } catch (const Error& error) {
      throw Error(source_ + ": invalid surface: " + error.what());
    }
  }

  Shape shape(const Json& root) const {
    if (!root.is_object()) {
      fail("<root>", "expected a JSON object with a \"type\", got " + describe_json_value(root));
    }
    const Json& type = require(root, "type", "\"nurbs_curve\" or \"nurbs_surface\"");
    if (type == "nurbs_curve") {
      return curve(root);
    }
    if (type == "nurbs_surface") {
      return surface(root);
    }
    fail("type", "expected \"nurbs_curve\" or \"nurbs_surface\", got " + describe_json_value(type));
  }

 private:
  std::string source_;
};

// Shortest text that reads back as exactly the same double.
std::string json_number(double value) {
  return Json(value).dump();
}

std::string json_numbers(const std::vector<double>& values) {
  std::string text = "[";
  for (size_t i = 0; i < values.size(); ++i) {
    text.append(i ? ", " : "").append(json_number(values[i]));
  }
  return text + "]";
}

std::string json_point(const Eigen::Vector3d& point) {
  std::string text(1, '[');  // appends: GCC 12 warns falsely (-Wrestrict) on "[" + string
  text.append(json_number(point.x())).append(", ").append(json_number(point.y())).append(", ");
  return text.append(json_number(point.z())).append("]");
}

std::string to_json(const NurbsCurve& curve) {
  std::ostringstream out;
  out << "{\n  \"type\": \"nurbs_curve\",\n  \"degree\": " << curve.degree() << ",\n";
  if (curve.is_periodic()) {
    out << "  \"periodic\": true,\n";
  }
  out << "  \"knots\": " << json_numbers(curve.knots().period_knots()) << ",\n";
  out << "  \"control_points\": [\n";
  for (int i = 0; i < curve.control_point_count(); ++i) {
    out << "    " << json_point(curve.control_points().row(i).transpose())
        << (i + 1 < curve.control_point_count() ? ",\n" : "\n");
  }
  out << "  ]";
  const Eigen::VectorXd& weights = curve.weights();
  if ((weights.array() != 1.0).any()) {
    out << ",\n  \"weights\": "
        << json_numbers(std::vector<double>(weights.data(), weights.data() + weights.size()));
  }
  out << "\n}\n";
  return out.str();
}

std::string to_json(const NurbsSurface& surface) {
  const int m = surface.control_point_count_u();
  const int n = surface.control_point_count_v();
  std::ostringstream out;
  out << "{\n  \"type\": \"nurbs_surface\",\n  \"degree_u\": " << surface.degree_u()
      << ",\n  \"degree_v\": " << surface.degree_v() << ",\n";
  if (surface.knots_u().is_periodic()) {
    out << "  \"periodic_u\": true,\n";
  }
  if (surface.knots_v().is_periodic()) {
    out << "  \"periodic_v\": true,\n";
  }
  out << "  \"knots_u\": " << json_numbers(surface.knots_u().period_knots()) << ",\n";
  out << "  \"knots_v\": " << json_numbers(surface.knots_v().period_knots()) << ",\n";
  out << "  \"control_points\": [\n";
  for (int i = 0; i < m; ++i) {
    out << "    [";
    for (int j = 0; j < n; ++j) {
      out << (j ? ", " : "")
          << json_point(
                 surface.control_points().row(surface.control_point_index(i, j)).transpose());
    }
    out << (i + 1 < m ? "],\n" : "]\n");
  }
  out << "  ]";
  const Eigen::VectorXd& weights = surface.weights();
  if ((weights.array() != 1.0).any()) {
    out << ",\n  \"weights\": [\n";
    for (int i = 0; i < m; ++i) {
      const double* row = weights.data() + surface.control_point_index(i, 0);
      out << "    " << json_numbers(std::vector<double>(row, row + n))
          << (i + 1 < m ? ",\n" : "\n");
    }
    out << "  ]";
  }
  out << "\n}\n";
  return out.str();
}

}  // namespace

Shape parse_shape_json(const std::string& text, const std::string& source) {
  return ShapeReader(source).shape(parse_json_document(text, source));
}

std::vector<Shape> read_exchange_shapes(const std::filesystem::path& path) {
  if (cad_format_of(path)) {
    return read_cad_file(path);
  }
  if (lowercase_extension(path) == ".obj") {
    std::vector<Shape> shapes = read_obj_freeform_file(path);
    if (shapes.empty()) {
      throw make_error(path.string(),
                       ": the OBJ file has no free-form curve or surface (curv or surf)");
    }
    return shapes;
  }
  return {read_shape_file(path)};
}

Shape read_shape_file(const std::filesystem::path& path) {
  if (cad_format_of(path) || lowercase_extension(path) == ".obj") {
    std::vector<Shape> shapes = read_exchange_shapes(path);
    if (shapes.size() != 1) {
      throw make_error(path.string(), ": the file holds ", shapes.size(),
                       " curves and surfaces, and a shape file is one; `dnurbs import ",
                       path.filename().string(), " shape.json` writes each to its own file");
    }
    return std::move(shapes.front());
  }
  return parse_shape_json(read_input_file(path, "shape file"), path.string());
}

std::string shape_summary(const Shape& shape) {
  std::ostringstream text;
  if (const auto* surface = std::get_if<NurbsSurface>(&shape)) {
    text << "nurbs_surface, " << surface->control_point_count_u() << " x "
         << surface->control_point_count_v() << " control points, degrees " << surface->degree_u()
         << " x " << surface->degree_v();
    if (surface->is_rational()) {
      text << ", rational";
    }
    const bool periodic_u = surface->knots_u().is_periodic();
    const bool periodic_v = surface->knots_v().is_periodic();
    if (periodic_u || periodic_v) {
      text << ", periodic" << (periodic_u && periodic_v ? "" : periodic_u ? " in u" : " in v");
    }
  } else {
    const auto& curve = std::get<NurbsCurve>(shape);
    text << "nurbs_curve, " << curve.control_point_count() << " control points, degree "
         << curve.degree();
    if (curve.is_rational()) {
      text << ", rational";
    }
    if (curve.is_periodic()) {
      text << ", periodic";
    }
  }
  return text.str();
}

std::string shape_to_json(const Shape& shape) {
  return std::visit([](const auto& value) { return to_json(value); }, shape);
}

void write_shape_file(const std::filesystem::path& path, const Shape& shape) {
  write_file_atomically(path, shape_to_json(shape));
}

}  // namespace dnurbs
