#pragma once
// The scene force "image_potential" (docs/scene-format.md, "forces"): the edge force -grad P of
// a 2-D image or a 3-D volume, P = -c |grad(G_sigma * I)| (Terzopoulos, Deformable Models:
// Classic, Topology-Adaptive and Generalized Formulations, 2003, below eq. 1.3 and eq. 1.5),
// placed in model space by an origin and a pixel size (dynamics/core/image_force.h).

#include <memory>
#include <string>

#include <Eigen/Core>

#include "dnurbs/io/scene_reader.h"
#include "dnurbs/io/scene_spec.h"
#include "dnurbs/vision/edge_potential.h"
#include "dnurbs/vision/volume_edge_potential.h"

namespace dnurbs {

/// "image_potential": keys model, image (a PNG or PGM file) or volume (a NRRD file), sigma
/// (pixels, >= 0), c (the potential's magnitude, default 1), origin ([x, y, z], default 0),
/// pixel_size (a number or [sx, sy, sz] > 0; default 1 for images and the NRRD spacings for
/// volumes), start, end. The file is read and its potential computed once, when the scene is
/// read; clones share it.
struct SceneImagePotential final : SceneForceSpec {
  int model = 0;
  std::string file;     ///< as written in the scene (relative to the scene's folder)
  bool volume = false;  ///< "volume" (3-D) rather than "image" (2-D)
  double sigma = 0.0;
  double c = 1.0;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d pixel_size = Eigen::Vector3d::Ones();
  bool pixel_size_given = false;  ///< written back only when the scene gave it
  std::shared_ptr<const ImageEdgePotential> image_potential;    ///< when !volume
  std::shared_ptr<const VolumeEdgePotential> volume_potential;  ///< when volume

  std::unique_ptr<SceneForceSpec> clone() const override;
  std::string type() const override { return "image_potential"; }
  void write(JsonOut& json) const override;
  void apply(System& system, double start, double end) const override;
  bool add_to_region(int index, SculptedRegion& region) const override;
};

/// The reader of io/scene_registry.cpp's force table. Fails naming the key for a missing or
/// unreadable file, both or neither of "image" and "volume", and bad numbers.
std::unique_ptr<SceneForceSpec> read_image_potential(const SceneReader& reader,
                                                     const ModelNames& names,
                                                     const JsonValue& force,
                                                     const std::string& path);

}  // namespace dnurbs
