#include "dnurbs/io/triangular_shape_file.h"

#include <fstream>
#include <memory>
#include <sstream>
#include <utility>

#include "dnurbs/core/error.h"
#include "dnurbs/core/input_file.h"
#include "dnurbs/io/atomic_write.h"
#include "dnurbs/io/json_messages.h"
#include "dnurbs/nurbs/triangular_knot_clouds.h"

namespace dnurbs {
namespace {

constexpr const char* kKeys[] = {"type",        "degree",         "vertices", "triangles",
                                 "knot_clouds", "control_points", "weights"};

// Runs `make` and rewraps a library Error as "<source>: <path>: invalid <what>: <message>".
template <typename Make>
auto wrapped(const SceneReader& reader, const std::string& path, const char* what, Make&& make) {
  try {
    return make();
  } catch (const Error& error) {
    reader.fail(path, std::string("invalid ") + what + ": " + error.what());
  }
}

Triangulation read_triangulation(const SceneReader& reader, const JsonValue& shape,
                                 const std::string& path) {
  const std::string vertices_path = join_json_path(path, "vertices");
  const JsonValue& vertices =
      reader.array(reader.require(shape, path, "vertices", "an array of [u, v] vertices"),
                   vertices_path, "[u, v] vertices");
  Eigen::MatrixX2d uv(static_cast<Eigen::Index>(vertices.size()), 2);
  for (size_t i = 0; i < vertices.size(); ++i) {
    uv.row(static_cast<Eigen::Index>(i)) =
        reader.vector<2>(vertices[i], json_index_path(vertices_path, i), "[u, v]").transpose();
  }
  const std::string triangles_path = join_json_path(path, "triangles");
  const JsonValue& triangles =
      reader.array(reader.require(shape, path, "triangles", "an array of [i, j, k] vertex indices"),
                   triangles_path, "[i, j, k] vertex indices");
  Eigen::MatrixX3i corners(static_cast<Eigen::Index>(triangles.size()), 3);
  for (size_t t = 0; t < triangles.size(); ++t) {
    const std::string triangle_path = json_index_path(triangles_path, t);
    const std::vector<int> indices = reader.indices(triangles[t], triangle_path);
    if (indices.size() != 3) {
      reader.fail(triangle_path, "expected three vertex indices [i, j, k], got " +
                                     describe_json_value(triangles[t]));
    }
    for (int c = 0; c < 3; ++c) {
      corners(static_cast<Eigen::Index>(t), c) = indices[static_cast<size_t>(c)];
    }
  }
  return wrapped(reader, triangles_path, "triangulation",
                 [&] { return Triangulation(std::move(uv), std::move(corners)); });
}

TriangularKnotClouds read_knot_clouds(const SceneReader& reader, const JsonValue& shape,
                                      const std::string& path, const Triangulation& triangulation,
                                      int degree) {
  const std::string clouds_path = join_json_path(path, "knot_clouds");
  const JsonValue* clouds = reader.find(shape, "knot_clouds");
  if (clouds == nullptr) {
    return wrapped(reader, clouds_path, "standard knot clouds",
                   [&] { return standard_knot_clouds(triangulation, degree); });
  }
  reader.array(*clouds, clouds_path, "knot clouds (one per vertex)");
  if (static_cast<int>(clouds->size()) != triangulation.vertex_count()) {
    reader.fail(clouds_path, "expected " + std::to_string(triangulation.vertex_count()) +
                                 " knot clouds (one per vertex), got " +
                                 std::to_string(clouds->size()));
  }
  Eigen::MatrixX2d knots(triangulation.vertex_count() * (degree + 1), 2);
  for (int i = 0; i < triangulation.vertex_count(); ++i) {
    const std::string cloud_path = json_index_path(clouds_path, static_cast<size_t>(i));
    const JsonValue& cloud =
        reader.array((*clouds)[static_cast<size_t>(i)], cloud_path, "[u, v] knots");
    if (static_cast<int>(cloud.size()) != degree) {
      reader.fail(cloud_path, "expected " + std::to_string(degree) + " knots t_1..t_n for degree " +
                                  std::to_string(degree) + " (t_0 is the vertex), got " +
                                  std::to_string(cloud.size()));
    }
    knots.row(i * (degree + 1)) = triangulation.vertex(i).transpose();
    for (int b = 1; b <= degree; ++b) {
      knots.row(i * (degree + 1) + b) =
          reader
              .vector<2>(cloud[static_cast<size_t>(b - 1)],
                         json_index_path(cloud_path, static_cast<size_t>(b - 1)), "[u, v]")
              .transpose();
    }
  }
  return wrapped(reader, clouds_path, "knot clouds", [&] {
    TriangularKnotClouds result(triangulation, degree, std::move(knots));
    check_knot_clouds(triangulation, result);
    return result;
  });
}

// The control points (count by 3) and weights (count; all 1 when absent)
std::pair<Eigen::MatrixX3d, Eigen::VectorXd> read_control_net(const SceneReader& reader,
                                                              const JsonValue& shape,
                                                              const std::string& path, int count,
                                                              int degree) {
  const std::string points_path = join_json_path(path, "control_points");
  const JsonValue& points =
      reader.array(reader.require(shape, path, "control_points", "an array of [x, y, z] points"),
                   points_path, "[x, y, z] points");
  if (static_cast<int>(points.size()) != count) {
    reader.fail(points_path, "expected " + std::to_string(count) +
                                 " control points (triangles times (n + 1)(n + 2) / 2 for degree " +
                                 std::to_string(degree) + "), got " +
                                 std::to_string(points.size()));
  }
  Eigen::MatrixX3d control_points(count, 3);
  for (int i = 0; i < count; ++i) {
    control_points.row(i) =
        reader.point(points[static_cast<size_t>(i)], json_index_path(points_path, i)).transpose();
  }
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(count);
  if (const JsonValue* found = reader.find(shape, "weights")) {
    const std::string weights_path = join_json_path(path, "weights");
    reader.array(*found, weights_path, "positive numbers");
    if (static_cast<int>(found->size()) != count) {
      reader.fail(weights_path, "expected " + std::to_string(count) +
                                    " weights (one per control point), got " +
                                    std::to_string(found->size()));
    }
    for (int i = 0; i < count; ++i) {
      weights[i] = reader.bounded((*found)[static_cast<size_t>(i)],
                                  json_index_path(weights_path, i), 0.0, true);
    }
  }
  return {std::move(control_points), std::move(weights)};
}

// Shortest text that reads back as exactly the same number, and rows of such numbers.
template <typename Scalar>
std::string json_row(const Scalar* values, int count) {
  std::string text = "[";
  for (int i = 0; i < count; ++i) {
    text.append(i ? ", " : "").append(JsonValue(values[i]).dump());
  }
  return text + "]";
}

template <typename Matrix>
void write_rows(std::ostringstream& out, const char* key, const Matrix& rows) {
  out << ",\n  \"" << key << "\": [";
  for (Eigen::Index i = 0; i < rows.rows(); ++i) {
    const Eigen::Matrix<typename Matrix::Scalar, 1, Eigen::Dynamic> row = rows.row(i);
    out << (i ? ",\n    " : "\n    ") << json_row(row.data(), static_cast<int>(row.size()));
  }
  out << "\n  ]";
}

}  // namespace

TriangularNurbsSurface read_triangular_shape(const SceneReader& reader, const JsonValue& shape,
                                             const std::string& path) {
  reader.object(shape, path, std::vector<const char*>(std::begin(kKeys), std::end(kKeys)),
                "a triangular_nurbs shape");
  const JsonValue& type =
      reader.require(shape, path, "type", std::string("\"") + kTriangularShapeType + "\"");
  if (type != kTriangularShapeType) {
    reader.fail(join_json_path(path, "type"), std::string("expected \"") + kTriangularShapeType +
                                                  "\", got " + describe_json_value(type));
  }
  const int degree = reader.integer(reader.require(shape, path, "degree", "an integer degree"),
                                    join_json_path(path, "degree"), 1, kMaxTriangularDegree);
  Triangulation triangulation = read_triangulation(reader, shape, path);
  TriangularKnotClouds clouds = read_knot_clouds(reader, shape, path, triangulation, degree);
  const int count =
      triangulation.triangle_count() * (degree + 1) * (degree + 2) / 2;  // function_count
  auto [points, weights] = read_control_net(reader, shape, path, count, degree);
  auto basis = wrapped(reader, join_json_path(path, "knot_clouds"), "knot clouds", [&] {
    return std::make_shared<const TriangularBSplineBasis>(std::move(triangulation),
                                                          std::move(clouds));
  });
  return TriangularNurbsSurface(std::move(basis), std::move(points), std::move(weights));
}

TriangularNurbsSurface parse_triangular_shape_json(const std::string& text,
                                                   const std::string& source) {
  const SceneReader reader(source, ".");
  return read_triangular_shape(reader, parse_json_document(text, source), "");
}

TriangularNurbsSurface read_triangular_shape_file(const std::filesystem::path& path) {
  return parse_triangular_shape_json(read_input_file(path, "shape file"), path.string());
}

std::string triangular_shape_to_json(const TriangularNurbsSurface& surface) {
  const TriangularBSplineBasis& basis = surface.basis();
  const Triangulation& triangulation = basis.triangulation();
  const int n = basis.degree();
  std::ostringstream out;
  out << "{\n  \"type\": \"" << kTriangularShapeType << "\",\n  \"degree\": " << n;
  write_rows(out, "vertices", triangulation.vertices());
  write_rows(out, "triangles", triangulation.triangles());
  out << ",\n  \"knot_clouds\": [";
  for (int i = 0; i < triangulation.vertex_count(); ++i) {
    out << (i ? ",\n    [" : "\n    [");
    for (int b = 1; b <= n; ++b) {
      const Eigen::Vector2d knot = basis.knot_clouds().knot(i, b);
      out << (b > 1 ? ", " : "") << json_row(knot.data(), 2);
    }
    out << "]";
  }
  out << "\n  ]";
  write_rows(out, "control_points", surface.control_points());
  const Eigen::VectorXd& weights = surface.weights();
  if ((weights.array() != 1.0).any()) {
    out << ",\n  \"weights\": " << json_row(weights.data(), static_cast<int>(weights.size()));
  }
  out << "\n}\n";
  return out.str();
}

void write_triangular_shape_file(const std::filesystem::path& path,
                                 const TriangularNurbsSurface& surface) {
  write_file_atomically(path, triangular_shape_to_json(surface));
}

bool is_triangular_shape_file(const std::filesystem::path& path) {
  std::string text;
  try {
    text = read_input_file(path, "shape file");
  } catch (const Error&) {
    return false;  // read_shape_file then says why
  }
  const JsonValue root = JsonValue::parse(text, nullptr, false);
  return root.is_object() && root.contains("type") && root["type"] == kTriangularShapeType;
}

}  // namespace dnurbs
