#pragma once
// The messages a sculpting client sends (docs/serve.md, "Client to server"), parsed and
// validated before anything acts on them: a message that fails here changes nothing and is
// answered by an error naming the key and the value.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/core/error.h"

namespace dnurbs {

/// Thrown by parse_sculpt_request for a malformed or out-of-range message. `request()` is the
/// message's type when it could be read ("" otherwise), `id()` its id if it had a valid one.
class SculptRequestError : public Error {
 public:
  SculptRequestError(const std::string& message, std::string request, std::optional<long long> id)
      : Error(message), request_(std::move(request)), id_(id) {}
  const std::string& request() const { return request_; }
  std::optional<long long> id() const { return id_; }

 private:
  std::string request_;
  std::optional<long long> id_;
};

enum class SculptRequestType {
  kGrab,     ///< a mouse spring at (model, at) toward target
  kPush,     ///< a point force at (model, at)
  kMove,     ///< a drag's new target / force (and material point)
  kRelease,  ///< a drag ends
  kPin,      ///< a point constraint at (model, at), where it is now
  kSet,      ///< a setting (key, value)
  kPlay,
  kPause,
  kStep,
  kReset,
  kUndo,
  kSave,
  kQuery,  ///< x(at) of a model
  kShape,  ///< a model's exact shape
};

/// The settings a `set` message may change, in the order of kSculptSettingNames.
enum class SculptSetting { kStiffness, kTension, kRigidity, kDensity, kDamping, kDt };

/// One validated message. Only the keys of its type are meaningful.
struct SculptRequest {
  SculptRequestType type = SculptRequestType::kPlay;
  std::string name;                   ///< the type as sent ("grab", ...)
  std::optional<long long> id;        ///< echoed in the reply
  int model = -1;                     ///< grab, push, pin, query, shape
  std::optional<Eigen::Vector2d> at;  ///< material point ([u] becomes (u, 0))
  std::optional<Eigen::Vector3d> target;
  std::optional<Eigen::Vector3d> force;
  int drag = -1;  ///< move, release
  SculptSetting setting = SculptSetting::kStiffness;
  double value = 0.0;  ///< set
};

/// What the parser checks a message against: the scene's models.
struct SculptRequestLimits {
  /// Per model: its parametric dimension (1: `at` is [u], 2: [u, v]) and domain
  /// [u_min, u_max] x [v_min, v_max] (v ignored for curves).
  struct ModelLimits {
    int parametric_dimension = 2;
    Eigen::Vector2d min = Eigen::Vector2d::Zero();
    Eigen::Vector2d max = Eigen::Vector2d::Ones();
  };
  std::vector<ModelLimits> models;
  std::size_t max_bytes = 16 * 1024;  ///< longer messages are refused unread
};

/// The accepted range of each setting: [min, max], `open_min` when min itself is refused.
struct SculptSettingRange {
  const char* name;
  double min;
  double max;
  bool open_min;
};
/// Ranges of stiffness, tension, rigidity, density, damping, dt (SculptSetting order).
const SculptSettingRange& sculpt_setting_range(SculptSetting setting);

/// Parses one client message. Throws SculptRequestError naming the key and the value for
/// malformed JSON, a missing or unknown type, a missing key, a key of the wrong kind, a
/// non-finite number, a model index out of range, a material point outside the model's domain
/// or a setting out of its range; unknown keys are refused too (a misspelt key is not ignored).
SculptRequest parse_sculpt_request(std::string_view text, const SculptRequestLimits& limits);

}  // namespace dnurbs
