#include "dnurbs/io/models/triangular_dnurbs_surface_scene.h"

#include <utility>

#include "dnurbs/io/json_messages.h"
#include "dnurbs/io/models/dnurbs_scene_keys.h"
#include "dnurbs/io/scene_model_keys.h"
#include "dnurbs/io/triangular_shape_file.h"
#include "dnurbs/nurbs/triangular_knot_clouds.h"
#include "dnurbs/nurbs/triangulation_shapes.h"

namespace dnurbs {

namespace {

constexpr int kMaxRectangleCells = 256;  // per direction
constexpr int kMaxCellsPerUnit = 64;     // L-shape and square with a hole

SceneTriangularDomain read_domain(const SceneReader& reader, const JsonValue& value,
                                  const std::string& path) {
  reader.object(value, path, {"shape", "cells", "lo", "hi", "degree", "knot_radius"});
  SceneTriangularDomain domain;
  if (const JsonValue* shape = reader.find(value, "shape")) {
    domain.shape = reader.choice(*shape, join_json_path(path, "shape"),
                                 {"rectangle", "l_shape", "square_with_hole"});
  }
  const bool rectangle = domain.shape == "rectangle";
  const std::string cells_path = join_json_path(path, "cells");
  if (const JsonValue* cells = reader.find(value, "cells")) {
    if (rectangle) {
      const std::vector<int> counts = reader.indices(*cells, cells_path);
      if (counts.size() != 2 || counts[0] < 1 || counts[1] < 1 || counts[0] > kMaxRectangleCells ||
          counts[1] > kMaxRectangleCells) {
        reader.fail(cells_path, "expected [cells_u, cells_v], each 1.." +
                                    std::to_string(kMaxRectangleCells) + ", got " +
                                    describe_json_value(*cells));
      }
      domain.cells = {counts[0], counts[1]};
    } else {
      domain.cells.setConstant(reader.integer(*cells, cells_path, 1, kMaxCellsPerUnit));
    }
  } else if (!rectangle) {
    domain.cells.setConstant(2);
  }
  if (rectangle) {
    if (const JsonValue* lo = reader.find(value, "lo")) {
      domain.lo = reader.vector<2>(*lo, join_json_path(path, "lo"), "[u, v]");
    }
    if (const JsonValue* hi = reader.find(value, "hi")) {
      domain.hi = reader.vector<2>(*hi, join_json_path(path, "hi"), "[u, v]");
    }
  } else {
    for (const char* key : {"lo", "hi"}) {
      if (reader.find(value, key) != nullptr) {
        reader.fail(join_json_path(path, key),
                    "only a rectangle has corners (the " + domain.shape + " is fixed)");
      }
    }
  }
  reader.integer_key(value, path, "degree", domain.degree, 1, kMaxTriangularDegree);
  reader.number_key(value, path, "knot_radius", domain.knot_radius, 0.0, true);
  return domain;
}

JsonOut domain_json(const SceneTriangularDomain& domain) {
  JsonOut result = {{"shape", domain.shape}};
  if (domain.shape == "rectangle") {
    result["cells"] = {domain.cells.x(), domain.cells.y()};
    result["lo"] = parameter_json(domain.lo);
    result["hi"] = parameter_json(domain.hi);
  } else {
    result["cells"] = domain.cells.x();
  }
  result["degree"] = domain.degree;
  result["knot_radius"] = domain.knot_radius;
  return result;
}

// The initial shape from exactly one of "shape", "shape_file" and "domain".
void read_shape(const SceneReader& reader, const JsonValue& model, const std::string& path,
                SceneTriangularDNurbsSurface& spec) {
  const JsonValue* shape = reader.find(model, "shape");
  const JsonValue* file = reader.find(model, "shape_file");
  const JsonValue* domain = reader.find(model, "domain");
  if ((shape != nullptr) + (file != nullptr) + (domain != nullptr) != 1) {
    reader.fail(join_json_path(path, "shape"),
                "expected exactly one of \"shape\" (a triangular_nurbs shape), \"shape_file\" "
                "and \"domain\"");
  }
  if (shape != nullptr) {
    spec.surface = read_triangular_shape(reader, *shape, join_json_path(path, "shape"));
  } else if (file != nullptr) {
    const std::string file_path = join_json_path(path, "shape_file");
    spec.shape_file = reader.string(*file, file_path);
    try {
      spec.surface = read_triangular_shape_file(reader.resolve(spec.shape_file));
    } catch (const Error& error) {
      reader.fail(file_path, error.what());
    }
  } else {
    const std::string domain_path = join_json_path(path, "domain");
    spec.domain = read_domain(reader, *domain, domain_path);
    try {
      spec.surface = triangular_domain_surface(*spec.domain);
    } catch (const Error& error) {
      reader.fail(domain_path, error.what());
    }
  }
}

void read_tessellation(const SceneReader& reader, const JsonValue& model, const std::string& path,
                       TriangularDNurbsSettings& settings) {
  const JsonValue* value = reader.find(model, "tessellation");
  if (value == nullptr) {
    return;
  }
  const std::string tessellation_path = join_json_path(path, "tessellation");
  reader.object(*value, tessellation_path, {"subdivisions", "max_error", "max_level"});
  reader.integer_key(*value, tessellation_path, "subdivisions", settings.tessellation_subdivisions,
                     0, 1024);
  reader.number_key(*value, tessellation_path, "max_error", settings.tessellation_max_error, 0.0,
                    false);
  reader.integer_key(*value, tessellation_path, "max_level", settings.tessellation_max_level, 1,
                     40);
}

}  // namespace

TriangularNurbsSurface triangular_domain_surface(const SceneTriangularDomain& domain) {
  Triangulation triangulation =
      domain.shape == "l_shape" ? l_shape_triangulation(domain.cells.x())
      : domain.shape == "square_with_hole"
          ? square_with_hole_triangulation(domain.cells.x())
          : rectangle_triangulation(domain.lo, domain.hi, domain.cells.x(), domain.cells.y());
  KnotCloudSettings clouds;
  clouds.radius = domain.knot_radius;
  TriangularKnotClouds knots = standard_knot_clouds(triangulation, domain.degree, clouds);
  return flat_triangular_surface(
      std::make_shared<const TriangularBSplineBasis>(std::move(triangulation), std::move(knots)));
}

std::unique_ptr<SceneModelSpec> SceneTriangularDNurbsSurface::clone() const {
  return std::make_unique<SceneTriangularDNurbsSurface>(*this);
}

void SceneTriangularDNurbsSurface::write(JsonOut& model) const {
  if (domain) {
    model["domain"] = domain_json(*domain);
  } else if (!shape_file.empty()) {
    model["shape_file"] = shape_file;
  } else {
    model["shape"] = JsonOut::parse(triangular_shape_to_json(surface.value()));
  }
  model["material"] = dnurbs_surface_material_json(material);
  model["weights"] = settings.weight_mode == WeightMode::kFree ? "free" : "fixed";
  model["minimum_weight"] = settings.minimum_weight;
  model["weight_inertia"] = settings.weight_inertia;
  model["quadrature_degree"] = settings.quadrature_degree;
  model["quadrature_subdivisions"] = settings.quadrature_subdivisions;
  model["tessellation"] = {{"subdivisions", settings.tessellation_subdivisions},
                           {"max_error", settings.tessellation_max_error},
                           {"max_level", settings.tessellation_max_level}};
  write_rest_shape_keys(settings.initial_shape_at_rest, settings.plastic_flow, model);
}

std::unique_ptr<Model> SceneTriangularDNurbsSurface::build() const {
  return std::make_unique<TriangularDNurbsSurface>(surface.value(), material, settings);
}

std::optional<std::pair<std::unique_ptr<SceneModelSpec>, std::string>>
SceneTriangularDNurbsSurface::naive_variant() const {
  return free_weights_variant(*this);
}

std::unique_ptr<SceneModelSpec> read_triangular_dnurbs_surface_scene(const SceneReader& reader,
                                                                     const JsonValue& model,
                                                                     const std::string& path) {
  check_model_keys(
      reader, model, path, "triangular_dnurbs_surface",
      {"shape", "shape_file", "domain", "weights", "minimum_weight", "weight_inertia",
       "quadrature_degree", "quadrature_subdivisions", "tessellation", "rest_shape", "plastic"});
  auto spec = std::make_unique<SceneTriangularDNurbsSurface>();
  read_dnurbs_surface_material(reader, model, path, spec->material);
  TriangularDNurbsSettings& settings = spec->settings;
  if (const JsonValue* weights = reader.find(model, "weights")) {
    settings.weight_mode =
        reader.choice(*weights, join_json_path(path, "weights"), {"fixed", "free"}) == "free"
            ? WeightMode::kFree
            : WeightMode::kFixed;
  }
  reader.number_key(model, path, "minimum_weight", settings.minimum_weight, 0.0, true);
  reader.number_key(model, path, "weight_inertia", settings.weight_inertia, 0.0, false);
  reader.integer_key(model, path, "quadrature_degree", settings.quadrature_degree, 0,
                     kMaxDunavantDegree);
  reader.integer_key(model, path, "quadrature_subdivisions", settings.quadrature_subdivisions, 0,
                     64);
  read_tessellation(reader, model, path, settings);
  read_rest_shape_keys(reader, model, path, settings.initial_shape_at_rest, settings.plastic_flow);
  read_shape(reader, model, path, *spec);
  return spec;
}

}  // namespace dnurbs
