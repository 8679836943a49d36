#include "dnurbs/io/models/grid_scene_keys.h"

#include "dnurbs/io/json_messages.h"

namespace dnurbs {

Grid SceneGrid::grid() const {
  return Grid(nodes_u, nodes_v, spacing, 3);
}

NodePositions SceneGrid::rest_positions() const {
  return flat_grid_positions(grid(), origin, axis_u, axis_v);
}

SceneGrid read_scene_grid(const SceneReader& reader, const JsonValue& model,
                          const std::string& path) {
  const std::string grid_path = join_json_path(path, "grid");
  const JsonValue& grid = reader.require(model, path, "grid", "a grid object");
  reader.object(grid, grid_path, {"nodes", "spacing", "origin", "axis_u", "axis_v"});
  SceneGrid result;
  const std::string nodes_path = join_json_path(grid_path, "nodes");
  const JsonValue& nodes = reader.require(grid, grid_path, "nodes", "[nodes_u, nodes_v]");
  if (!nodes.is_array() || nodes.size() != 2) {
    reader.fail(nodes_path, "expected [nodes_u, nodes_v], got " + describe_json_value(nodes));
  }
  result.nodes_u = reader.integer(nodes[0], json_index_path(nodes_path, 0), 3, 4096);
  result.nodes_v = reader.integer(nodes[1], json_index_path(nodes_path, 1), 3, 4096);
  result.spacing = reader.bounded(reader.require(grid, grid_path, "spacing", "a spacing > 0"),
                                  join_json_path(grid_path, "spacing"), 0.0, true);
  if (const JsonValue* origin = reader.find(grid, "origin")) {
    result.origin = reader.point(*origin, join_json_path(grid_path, "origin"));
  }
  if (const JsonValue* axis = reader.find(grid, "axis_u")) {
    result.axis_u = reader.point(*axis, join_json_path(grid_path, "axis_u"));
  }
  if (const JsonValue* axis = reader.find(grid, "axis_v")) {
    result.axis_v = reader.point(*axis, join_json_path(grid_path, "axis_v"));
  }
  return result;
}

JsonOut scene_grid_json(const SceneGrid& grid) {
  return JsonOut{{"nodes", {grid.nodes_u, grid.nodes_v}},
                 {"spacing", grid.spacing},
                 {"origin", json_array<3>(grid.origin)},
                 {"axis_u", json_array<3>(grid.axis_u)},
                 {"axis_v", json_array<3>(grid.axis_v)}};
}

}  // namespace dnurbs
