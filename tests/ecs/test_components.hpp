#pragma once

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "luxel/ecs/entity.hpp"

// Components shared by the ECS suites: plain aggregates, a non-aggregate, a move-only type and a
// tag, since any movable type must work without registration.
namespace luxel::ecs::test {

struct Position {
    float x = 0.0f;
    float y = 0.0f;
    float z = 0.0f;
};

struct Velocity {
    float x = 0.0f;
    float y = 0.0f;
    float z = 0.0f;
};

/// Four distinct components carrying a value derived from their entity, for view tests.
template <int Tag>
struct Marker {
    std::uint32_t value = 0;
};
using A = Marker<0>;
using B = Marker<1>;
using C = Marker<2>;
using D = Marker<3>;
using E = Marker<4>;

/// A non-aggregate, built through its constructor.
class Name {
  public:
    explicit Name(std::string text) : text_(std::move(text)) {}
    [[nodiscard]] const std::string& text() const { return text_; }

  private:
    std::string text_;
};

/// Move-only.
struct Mesh {
    std::unique_ptr<std::vector<float>> vertices;
};

/// Empty.
struct Frozen {};

inline std::vector<Entity> sorted(std::vector<Entity> entities) {
    std::sort(entities.begin(), entities.end());
    return entities;
}

}  // namespace luxel::ecs::test
