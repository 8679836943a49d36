#include "design/point_set.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "core/error.h"

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
    std::istringstream stream(line);
    Eigen::Vector3d point;
    std::string extra;
    // Read as strings so that "nan" and "inf" are recognized and reported as non-finite.
    std::string x;
    std::string y;
    std::string z;
    if (!(stream >> x >> y >> z) || (stream >> extra)) {
      throw make_error("line ", line_number, " of the point file '", path.string(),
                       "' does not hold three numbers: '", line, "'");
    }
    const std::string* parts[3] = {&x, &y, &z};
    for (int c = 0; c < 3; ++c) {
      size_t used = 0;
      try {
        point[c] = std::stod(*parts[c], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != parts[c]->size()) {
        throw make_error("line ", line_number, " of the point file '", path.string(), "': '",
                         *parts[c], "' is not a number");
      }
      if (!std::isfinite(point[c])) {
        throw make_error("line ", line_number, " of the point file '", path.string(),
                         "' has a non-finite coordinate (", *parts[c], ")");
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
