#include "dnurbs/io/scene_image_force.h"

#include <string>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/forces.h"
#include "dnurbs/dynamics/core/image_force.h"
#include "dnurbs/io/scene_writer.h"
#include "dnurbs/vision/gaussian_filter.h"
#include "dnurbs/vision/image.h"
#include "dnurbs/vision/volume.h"

namespace dnurbs {

std::unique_ptr<SceneForceSpec> SceneImagePotential::clone() const {
  return std::make_unique<SceneImagePotential>(*this);
}

void SceneImagePotential::write(JsonOut& json) const {
  json = {{"type", type()}, {"model", model}, {volume ? "volume" : "image", file},
          {"sigma", sigma}, {"c", c},         {"origin", json_array<3>(origin)}};
  if (pixel_size_given) {
    json["pixel_size"] = json_array<3>(pixel_size);
  }
}

void SceneImagePotential::apply(System& system, double start, double end) const {
  const ImageFrame frame{origin, pixel_size};
  system.add_force(model, windowed(volume ? volume_edge_force(volume_potential, frame)
                                          : image_edge_force(image_potential, frame),
                                   start, end));
}

bool SceneImagePotential::add_to_region(int index, SculptedRegion& /*region*/) const {
  return model == index;
}

std::unique_ptr<SceneForceSpec> read_image_potential(const SceneReader& reader,
                                                     const ModelNames& names,
                                                     const JsonValue& force,
                                                     const std::string& path) {
  reader.object(
      force, path,
      {"type", "model", "image", "volume", "sigma", "c", "origin", "pixel_size", "start", "end"});
  auto spec = std::make_unique<SceneImagePotential>();
  spec->model = names.require(reader, force, path, "model");
  const JsonValue* image = reader.find(force, "image");
  const JsonValue* volume = reader.find(force, "volume");
  if ((image == nullptr) == (volume == nullptr)) {
    reader.fail(path, image == nullptr
                          ? "missing key \"image\" (a PNG or PGM file) or \"volume\" (a NRRD file)"
                          : "both \"image\" and \"volume\" given (expected one of them)");
  }
  spec->volume = volume != nullptr;
  const char* file_key = spec->volume ? "volume" : "image";
  spec->file = reader.string(spec->volume ? *volume : *image, join_json_path(path, file_key));
  spec->sigma =
      reader.bounded(reader.require(force, path, "sigma", "a smoothing width in pixels >= 0"),
                     join_json_path(path, "sigma"), 0.0, false);
  if (spec->sigma > kMaxGaussianSigma) {
    reader.fail(
        join_json_path(path, "sigma"),
        make_error("expected at most ", kMaxGaussianSigma, " pixels, got ", spec->sigma).what());
  }
  reader.number_key(force, path, "c", spec->c);
  if (const JsonValue* origin = reader.find(force, "origin")) {
    spec->origin = reader.point(*origin, join_json_path(path, "origin"));
  }
  if (const JsonValue* size = reader.find(force, "pixel_size")) {
    const std::string size_path = join_json_path(path, "pixel_size");
    spec->pixel_size = size->is_number()
                           ? Eigen::Vector3d::Constant(reader.number(*size, size_path))
                           : reader.point(*size, size_path);
    spec->pixel_size_given = true;
    try {
      ImageFrame{spec->origin, spec->pixel_size}.validate();
    } catch (const Error& error) {
      reader.fail(size_path, error.what());
    }
  }
  const std::string file_path = join_json_path(path, file_key);
  try {
    const std::string file = reader.resolve(spec->file).string();
    if (spec->volume) {
      const Volume data = read_nrrd(file);
      if (!spec->pixel_size_given) {
        spec->pixel_size = data.spacing;
      }
      spec->volume_potential =
          std::make_shared<const VolumeEdgePotential>(data, spec->sigma, spec->c);
    } else {
      spec->image_potential =
          std::make_shared<const ImageEdgePotential>(read_image(file), spec->sigma, spec->c);
    }
  } catch (const Error& error) {
    reader.fail(file_path, error.what());
  }
  return spec;
}

}  // namespace dnurbs
