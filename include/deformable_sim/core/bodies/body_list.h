// The bodies of a simulation, each of its own model, in scene order. Each stays where it was made
// (contact keeps pointers to them); indexing and iteration give the bodies themselves. Only the
// simulation adds bodies, while it is built: what contact sized for them stays right.
#pragma once

#include <cstddef>
#include <iterator>
#include <memory>
#include <vector>

#include "deformable_sim/core/bodies/body.h"

namespace deformable_sim::core {

class Simulation;

class BodyList {
  using Owned = std::vector<std::unique_ptr<Body>>;

  /// Walks the owned bodies, handing out references (`Value`: Body or const Body).
  template <class Value, class Inner>
  class Iterator {
   public:
    using iterator_category = std::forward_iterator_tag;
    using value_type = Body;
    using difference_type = std::ptrdiff_t;
    using pointer = Value*;
    using reference = Value&;

    explicit Iterator(Inner at) : at_(at) {}
    Value& operator*() const { return **at_; }
    Value* operator->() const { return at_->get(); }
    Iterator& operator++() {
      ++at_;
      return *this;
    }
    bool operator==(const Iterator& other) const { return at_ == other.at_; }
    bool operator!=(const Iterator& other) const { return at_ != other.at_; }

   private:
    Inner at_;
  };

 public:
  using iterator = Iterator<Body, Owned::const_iterator>;
  using const_iterator = Iterator<const Body, Owned::const_iterator>;

  size_t size() const { return bodies_.size(); }
  bool empty() const { return bodies_.empty(); }
  Body& operator[](size_t i) { return *bodies_[i]; }
  const Body& operator[](size_t i) const { return *bodies_[i]; }
  Body& front() { return *bodies_.front(); }
  const Body& front() const { return *bodies_.front(); }
  Body& back() { return *bodies_.back(); }
  const Body& back() const { return *bodies_.back(); }

  iterator begin() { return iterator(bodies_.cbegin()); }
  iterator end() { return iterator(bodies_.cend()); }
  const_iterator begin() const { return const_iterator(bodies_.cbegin()); }
  const_iterator end() const { return const_iterator(bodies_.cend()); }

 private:
  friend class Simulation;
  void reserve(size_t count) { bodies_.reserve(count); }
  Body& add(std::unique_ptr<Body> body) { return *bodies_.emplace_back(std::move(body)); }

  Owned bodies_;
};

}  // namespace deformable_sim::core
