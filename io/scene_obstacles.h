#pragma once
// Rigid obstacles in scene files (docs/scene-format.md, "Obstacles"): the top-level keys
// "obstacles" (planes, boxes and spheres) and "contact" (how the models meet them), their reader
// and writer, and SceneContacts, which puts them into a running simulation with
// dynamics/core/obstacles.h: penalty forces added to the System, or the projection of the nodes
// after every step. The obstacles of Terzopoulos, Platt, Barr & Fleischer, "Elastically
// deformable models", SIGGRAPH 1987 (a rug falling over geometric obstacles).

#include <string>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/obstacles.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/io/scene_reader.h"
#include "dnurbs/io/scene_writer.h"

namespace dnurbs {

struct Scene;

/// How every model of the scene meets the obstacles. JSON key "contact".
struct SceneContact {
  /// "penalty" (penalty_contact, a Force on every model) or "projection" (project_contacts
  /// after every step; models whose material points are nodes only).
  std::string method = "penalty";
  /// stiffness, damping and friction (the keys of the same names); sliding_velocity keeps its
  /// default.
  ContactSettings settings;
};

/// Reads the top-level keys "obstacles" (an array of {"type": "plane" | "box" | "sphere", ...})
/// and "contact" of `root` into `obstacles` and `contact`; every bad value fails with its JSON
/// path ("obstacles[1].radius"). "contact" without "obstacles" is refused.
void read_scene_obstacles(const SceneReader& reader, const JsonValue& root,
                          std::vector<Obstacle>& obstacles, SceneContact& contact);
/// Writes "obstacles" and "contact" into `root` when there are obstacles (nothing otherwise, so
/// that the state hash of a scene without obstacles is what it was before obstacles existed).
void write_scene_obstacles(const std::vector<Obstacle>& obstacles, const SceneContact& contact,
                           JsonOut& root);

/// The material points of `model` at coordinates q that meet obstacles: every node when the
/// model's material points are nodes (grid surfaces and snakes: the vertices of its
/// tessellation, or N evenly spaced parameters of a curve of N points, each picked by L(u) with
/// weight 1 to within 1e-12, or not at all where a node is not simulated), else an empty vector.
std::vector<Eigen::Vector2d> contact_nodes(const Model& model, ConstVectorRef q);
/// A uniform lattice of material points over the model's parameter domain (closed directions
/// without their repeated end): `surface_count` by `surface_count` on a surface, `curve_count`
/// on a curve.
std::vector<Eigen::Vector2d> contact_samples(const Model& model, ConstVectorRef q,
                                             int surface_count = 16, int curve_count = 32);

/// The scene's obstacles in a running simulation.
class SceneContacts {
 public:
  SceneContacts() = default;
  /// Chooses the contact points of every model of `system` (the models of `scene`, in order:
  /// contact_nodes, or contact_samples for penalty contact) and, for penalty contact, adds one
  /// penalty_contact force per model to `system`. Throws SceneKeyError with the key's JSON path
  /// ("contact.method" when projection meets a model without nodes, or a snake node that its
  /// parameter k h does not pick exactly, naming it; "obstacles" for anything else the library
  /// refuses).
  SceneContacts(const Scene& scene, System& system);

  bool empty() const { return obstacles_.empty(); }
  /// Projection contact: project_contacts on every model after a committed step (nothing for
  /// penalty contact or without obstacles). Returns the deepest penetration found before
  /// projecting. Deterministic: the same state gives the same projection, so a run resumed from
  /// a checkpoint repeats the uninterrupted one.
  double project(System& system) const;
  /// The deepest penetration of any contact point of any model at the current state.
  double max_penetration(const System& system) const;
  /// The contact points of model i (material parameters).
  const std::vector<Eigen::Vector2d>& points(int i) const {
    return points_.at(static_cast<size_t>(i));
  }

 private:
  std::vector<Obstacle> obstacles_;
  SceneContact contact_;
  std::vector<std::vector<Eigen::Vector2d>> points_;  // per model
};

}  // namespace dnurbs
