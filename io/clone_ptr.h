#pragma once
// A polymorphic value: an owning pointer that copies what it points to (through T::clone), so
// that the parsed scene, whose model, force and constraint specs are of many types, copies and
// compares like a value.

#include <memory>
#include <type_traits>
#include <utility>

namespace dnurbs {

/// Owns a T (or a type derived from it) and deep-copies it; T must have
/// `std::unique_ptr<T> clone() const`.
template <typename T>
class ClonePtr {
 public:
  ClonePtr() = default;
  /// Takes ownership of a T or of a type derived from it (implicit, like unique_ptr's own).
  template <typename U>
  requires std::is_convertible_v<U*, T*> ClonePtr(std::unique_ptr<U> value)
      : value_(std::move(value)) {}  // NOLINT(google-explicit-constructor)
  ClonePtr(const ClonePtr& other) : value_(other.value_ ? other.value_->clone() : nullptr) {}
  ClonePtr& operator=(const ClonePtr& other) {
    if (this != &other) {
      value_ = other.value_ ? other.value_->clone() : nullptr;
    }
    return *this;
  }
  ClonePtr(ClonePtr&&) noexcept = default;
  ClonePtr& operator=(ClonePtr&&) noexcept = default;
  ~ClonePtr() = default;

  explicit operator bool() const { return static_cast<bool>(value_); }
  T& operator*() const { return *value_; }
  T* operator->() const { return value_.get(); }
  T* get() const { return value_.get(); }

 private:
  std::unique_ptr<T> value_;
};

}  // namespace dnurbs
