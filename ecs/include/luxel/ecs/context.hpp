#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "luxel/ecs/errors.hpp"
#include "luxel/ecs/type_id.hpp"

namespace luxel::ecs {

/// Per-registry singletons, at most one object per type: the place for state that belongs to one
/// world rather than to one entity (the hierarchy's hooks, a lighting system's caches, the
/// active camera). Owned by the registry, so it is never global: two registries have two
/// contexts. Objects are destroyed in reverse order of creation when the registry is.
class Context {
  public:
    Context() = default;
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;
    ~Context() {
        // Reverse creation order, so a later object may safely refer to an earlier one.
        while (!creation_order_.empty()) {
            entries_[creation_order_.back()].reset();
            creation_order_.pop_back();
        }
    }

    /// Constructs a T from args. Throws EcsError if the context already holds a T.
    template <class T, class... Args>
    T& emplace(Args&&... args) {
        const std::size_t index = type_index<T>();
        if (index < entries_.size() && entries_[index]) {
            throw EcsError("luxel::ecs: context already holds a " + std::string(type_name<T>()));
        }
        if (index >= entries_.size()) {
            entries_.resize(index + 1);
        }
        auto holder = std::make_unique<Holder<T>>(std::forward<Args>(args)...);
        T& value = holder->value;
        entries_[index] = std::move(holder);
        creation_order_.push_back(index);
        return value;
    }

    /// The T, constructing it from args first if absent.
    template <class T, class... Args>
    T& get_or_emplace(Args&&... args) {
        if (T* existing = find<T>()) {
            return *existing;
        }
        return emplace<T>(std::forward<Args>(args)...);
    }

    /// The T, or nullptr. O(1).
    template <class T>
    [[nodiscard]] T* find() noexcept {
        const std::size_t index = type_index<T>();
        if (index >= entries_.size() || !entries_[index]) {
            return nullptr;
        }
        return &static_cast<Holder<T>*>(entries_[index].get())->value;
    }
    template <class T>
    [[nodiscard]] const T* find() const noexcept {
        const std::size_t index = type_index<T>();
        if (index >= entries_.size() || !entries_[index]) {
            return nullptr;
        }
        return &static_cast<const Holder<T>*>(entries_[index].get())->value;
    }

    /// The T; throws EcsError if absent.
    template <class T>
    [[nodiscard]] T& get() {
        if (T* existing = find<T>()) {
            return *existing;
        }
        throw EcsError("luxel::ecs: context holds no " + std::string(type_name<T>()));
    }

    template <class T>
    [[nodiscard]] bool contains() const noexcept {
        return find<T>() != nullptr;
    }

    /// Destroys the T if present; returns whether it was.
    template <class T>
    bool erase() noexcept {
        const std::size_t index = type_index<T>();
        if (index >= entries_.size() || !entries_[index]) {
            return false;
        }
        entries_[index].reset();
        std::erase(creation_order_, index);
        return true;
    }

  private:
    struct Entry {
        Entry() = default;
        Entry(const Entry&) = delete;
        Entry& operator=(const Entry&) = delete;
        virtual ~Entry() = default;
    };
    template <class T>
    struct Holder final : Entry {
        template <class... Args>
        explicit Holder(Args&&... args) : value(std::forward<Args>(args)...) {}
        T value;
    };

    std::vector<std::unique_ptr<Entry>> entries_;
    std::vector<std::size_t> creation_order_;
};

}  // namespace luxel::ecs
