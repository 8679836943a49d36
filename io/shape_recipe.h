#pragma once
// Shape recipes: a JSON object {"kind": "plane", "size": [3, 3], ...} that names a generator of
// nurbs/shape_generators.h or nurbs/primitive_shapes.h and its arguments. Scenes take one as a
// model's "make" key, `dnurbs make KIND --key value ... OUT.json` builds one from its flags, and
// docs/scene-format.md ("Generated shapes") lists the kinds and keys.

#include <string>
#include <vector>

#include "dnurbs/io/scene_reader.h"
#include "dnurbs/nurbs/shape.h"

namespace dnurbs {

/// The recipe kinds, in the order messages list them: line, plane, box, cylinder, cone, sphere,
/// torus, revolve, extrude, loft.
const std::vector<const char*>& shape_recipe_kinds();

/// Every key a recipe of some kind takes besides "kind" (the kinds' own keys, then "split" and
/// "translate"), each once, in the order the kinds list them.
const std::vector<const char*>& shape_recipe_keys();

/// Builds the shape of `recipe` (a JSON object at `path`). Every key is checked; curves inside a
/// recipe (revolve's "profile", extrude's "curve", loft's "sections") are a nurbs_curve object in
/// the shape format, a shape file name (resolved by `reader`) or a nested recipe. The common keys
/// "split" (split_spans: [parts_u, parts_v] for surfaces, parts for curves) and "translate"
/// ([x, y, z], added to every control point) apply last. A shape over 100,000 control points is
/// refused. Throws Error "<source>: <path>.<key>: <what was expected>" (SceneReader::fail), also
/// for what a generator rejects.
Shape make_shape(const SceneReader& reader, const JsonValue& recipe, const std::string& path);

}  // namespace dnurbs
