#include "dnurbs/io/scene_data_force.h"

#include <utility>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/io/json_messages.h"
#include "dnurbs/io/scene_fit.h"
#include "dnurbs/io/scene_writer.h"
#include "dnurbs/io/schedule.h"

namespace dnurbs {

std::unique_ptr<SceneForceSpec> SceneDataPoints::clone() const {
  return std::make_unique<SceneDataPoints>(*this);
}

void SceneDataPoints::write(JsonOut& json) const {
  json = {{"type", type()}, {"model", model}};
  if (!file.empty()) {
    json["points"] = file;
  } else {
    JsonOut list = JsonOut::array();
    for (Eigen::Index k = 0; k < points.rows(); ++k) {
      list.push_back(json_array<3>(Eigen::Vector3d(points.row(k).transpose())));
    }
    json["points"] = list;
  }
  json["stiffness"] = settings.stiffness;
  if (has_offset) {
    json["offset"] = schedule_json(offset);
  }
  json["search_segments"] = settings.search_segments;
}

void SceneDataPoints::apply(System& system, double start, double end) const {
  Force force = has_offset ? moving_data_force(
                                 [points = points, offset = vector_of_time(offset)](double t) {
                                   Eigen::MatrixX3d moved = points;
                                   moved.rowwise() += offset(t).transpose();
                                   return moved;
                                 },
                                 settings)
                           : data_force(points, settings);
  system.add_force(model, windowed(std::move(force), start, end));
}

bool SceneDataPoints::add_to_region(int index, SculptedRegion& /*region*/) const {
  return model == index;
}

std::unique_ptr<SceneForceSpec> read_data_points(const SceneReader& reader, const ModelNames& names,
                                                 const JsonValue& force, const std::string& path) {
  reader.object(
      force, path,
      {"type", "model", "points", "stiffness", "offset", "search_segments", "start", "end"});
  auto spec = std::make_unique<SceneDataPoints>();
  spec->model = names.require(reader, force, path, "model");
  const std::string points_path = join_json_path(path, "points");
  const JsonValue& points =
      reader.require(force, path, "points", "a file of points or [[x, y, z], ...]");
  if (points.is_string()) {
    spec->file = reader.string(points, points_path);
    try {
      spec->points = read_fit_points(reader.resolve(spec->file));
    } catch (const Error& error) {
      reader.fail(points_path, error.what());
    }
  } else {
    reader.array(points, points_path, "[x, y, z] points");
    spec->points.resize(static_cast<Eigen::Index>(points.size()), 3);
    for (size_t k = 0; k < points.size(); ++k) {
      spec->points.row(static_cast<Eigen::Index>(k)) =
          reader.point(points[k], json_index_path(points_path, k)).transpose();
    }
  }
  if (spec->points.rows() == 0) {
    reader.fail(points_path, "expected at least one point, got none");
  }
  spec->settings.stiffness =
      reader.bounded(reader.require(force, path, "stiffness", "a stiffness >= 0"),
                     join_json_path(path, "stiffness"), 0.0, false);
  if (const JsonValue* offset = reader.find(force, "offset")) {
    spec->offset = reader.vector_schedule(*offset, join_json_path(path, "offset"));
    spec->has_offset = true;
  }
  reader.integer_key(force, path, "search_segments", spec->settings.search_segments, 2, 4096);
  return spec;
}

}  // namespace dnurbs
