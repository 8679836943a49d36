#include "dnurbs/design/point_set.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "dnurbs/core/error.h"
#include "dnurbs/core/input_file.h"

namespace dnurbs {

void check_points(const Eigen::MatrixX3d& points, const char* what) {
  if (points.rows() == 0) {
    throw make_error("the ", what, " are empty (0 points)");
  }
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(points(i, c))) {
        throw make_error("point ", i, " of the ", what, " has a non-finite coordinate ", c, " (",
                         points(i, c), ")");
      }
    }
  }
}

Eigen::MatrixX3d load_points(const std::filesystem::path& path) {
  check_input_file(path, "point file");
  std::ifstream file(path);
  if (!file) {
    throw make_error("cannot open the point file '", path.string(), "'");
  }
  std::vector<Eigen::Vector3d> points;
  std::string line;
  int line_number = 0;
  while (std::getline(file, line)) {
    ++line_number;
    for (char& c : line) {
      if (c == ',' || c == ';' || c == '\t' || c == '\r') {
        c = ' ';
      }
    }
    const auto first = line.find_first_not_of(' ');
    if (first == std::string::npos || line[first] == '#') {
      continue;
    }
    // Messages describe a bad line and never quote it: the path may lead to any file (a link to
    // a secret one), whose contents must not reach the terminal or a log.
    std::istringstream stream(line);
    std::vector<std::string> fields;
    for (std::string field; stream >> field;) {
      fields.push_back(field);
    }
    if (fields.size() != 3) {
      throw make_error("line ", line_number, " of the point file '", path.string(), "' holds ",
                       fields.size(), fields.size() == 1 ? " field" : " fields",
                       " where three numbers x y z were expected");
    }
    Eigen::Vector3d point;
    for (int c = 0; c < 3; ++c) {
      const std::string& field = fields[static_cast<size_t>(c)];
      size_t used = 0;
      try {
        point[c] = std::stod(field, &used);  // "nan" and "inf" are read, then refused below
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != field.size()) {
        throw make_error("line ", line_number, " of the point file '", path.string(),
                         "': coordinate ", "xyz"[c], " is not a number");
      }
      if (!std::isfinite(point[c])) {
        throw make_error("line ", line_number, " of the point file '", path.string(),
                         "': coordinate ", "xyz"[c], " is not finite");
      }
    }
    points.push_back(point);
  }
  if (points.empty()) {
    throw make_error("the point file '", path.string(), "' holds no point");
  }
  Eigen::MatrixX3d result(static_cast<Eigen::Index>(points.size()), 3);
  for (size_t i = 0; i < points.size(); ++i) {
    result.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  }
  return result;
}

Eigen::MatrixX3d mesh_vertices(const std::vector<TriangleMesh>& meshes) {
  Eigen::Index count = 0;
  for (const TriangleMesh& mesh : meshes) {
    count += mesh.vertices.rows();
  }
  Eigen::MatrixX3d result(count, 3);
  Eigen::Index row = 0;
  for (const TriangleMesh& mesh : meshes) {
    result.middleRows(row, mesh.vertices.rows()) = mesh.vertices;
    row += mesh.vertices.rows();
  }
  check_points(result, "mesh vertices");
  return result;
}

}  // namespace dnurbs
