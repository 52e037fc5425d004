#pragma once

#include <algorithm>
#include <cstddef>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace luxel::ecs {

namespace detail {

/// What a Connection keeps of its slot: enough to switch it off. Owned by the signal; the
/// connection holds a weak reference, so either side may be destroyed first.
struct SlotControl {
    bool connected = true;
};

}  // namespace detail

/// A link from a Signal to one callback, returned by Signal::connect and Sink::connect.
///
/// RAII: destroying (or move-assigning over) a connected Connection disconnects it. Call
/// release() to keep the callback connected for the signal's whole life instead. Disconnecting
/// is always safe: after the signal is gone it does nothing, and during an emission it stops the
/// callback from being called again (the one running finishes).
class Connection {
  public:
    Connection() noexcept = default;
    explicit Connection(std::weak_ptr<detail::SlotControl> slot) noexcept
        : slot_(std::move(slot)) {}
    Connection(Connection&&) noexcept = default;
    Connection& operator=(Connection&& other) noexcept {
        if (this != &other) {
            disconnect();
            slot_ = std::move(other.slot_);
        }
        return *this;
    }
    Connection(const Connection&) = delete;
    Connection& operator=(const Connection&) = delete;
    ~Connection() { disconnect(); }

    /// Whether the callback will still be called (false once disconnected, released, or after
    /// the signal is destroyed).
    [[nodiscard]] bool connected() const noexcept {
        const auto slot = slot_.lock();
        return slot && slot->connected;
    }

    void disconnect() noexcept {
        if (const auto slot = slot_.lock()) {
            slot->connected = false;
        }
        slot_.reset();
    }

    /// Gives up ownership: the callback stays connected until the signal dies.
    void release() noexcept { slot_.reset(); }

  private:
    std::weak_ptr<detail::SlotControl> slot_;
};

/// A list of callbacks called in connection order by emit(). Used by the registry's
/// on_construct / on_update / on_destroy hooks; usable on its own.
///
/// Emission semantics: callbacks connected during an emission are first called by the next one;
/// callbacks disconnected during an emission are not called after the disconnection. Emitting
/// from inside a callback (re-entrancy) is allowed. Destroying the signal from inside one of its
/// callbacks is not. Not thread-safe.
template <class... Args>
class Signal {
  public:
    using Callback = std::function<void(Args...)>;

    Signal() = default;
    Signal(const Signal&) = delete;
    Signal& operator=(const Signal&) = delete;
    Signal(Signal&&) noexcept = default;
    Signal& operator=(Signal&&) noexcept = default;
    ~Signal() = default;

    /// Adds `callback`; it is called by every later emit() until the returned Connection is
    /// disconnected or destroyed. O(1) amortised.
    [[nodiscard]] Connection connect(Callback callback) {
        compact();
        auto slot = std::make_shared<Slot>();
        slot->callback = std::move(callback);
        slots_.push_back(slot);
        return Connection(std::weak_ptr<detail::SlotControl>(slot));
    }

    /// Calls every connected callback in connection order. O(callbacks).
    void emit(Args... args) {
        if (slots_.empty()) {
            return;
        }
        // Ends the emission even if a callback throws, so later emissions still compact.
        struct EmissionScope {
            Signal* signal;
            explicit EmissionScope(Signal* s) noexcept : signal(s) { ++signal->emitting_; }
            EmissionScope(const EmissionScope&) = delete;
            EmissionScope& operator=(const EmissionScope&) = delete;
            ~EmissionScope() {
                --signal->emitting_;
                signal->compact();
            }
        } scope(this);
        // Index loop with the size taken once: callbacks connected meanwhile wait for the next
        // emission, and a push_back that reallocates the vector leaves our index meaningful. The
        // slot objects themselves never move (they are shared_ptr-owned).
        const std::size_t count = slots_.size();
        for (std::size_t i = 0; i < count; ++i) {
            Slot& slot = *slots_[i];
            if (slot.connected) {
                slot.callback(args...);
            }
        }
    }

    /// O(1): false when emit() would certainly call nothing (the registry's fast path).
    [[nodiscard]] bool has_slots() const noexcept { return !slots_.empty(); }

    /// Number of connected callbacks.
    [[nodiscard]] std::size_t size() const noexcept {
        return static_cast<std::size_t>(std::count_if(
            slots_.begin(), slots_.end(), [](const auto& slot) { return slot->connected; }));
    }
    [[nodiscard]] bool empty() const noexcept { return size() == 0; }

    /// Disconnects every callback.
    void disconnect_all() noexcept {
        for (auto& slot : slots_) {
            slot->connected = false;
        }
        compact();
    }

  private:
    struct Slot : detail::SlotControl {
        Callback callback;
    };

    /// Drops disconnected slots, but never during an emission: the running loop indexes them.
    void compact() noexcept {
        if (emitting_ == 0) {
            std::erase_if(slots_, [](const auto& slot) { return !slot->connected; });
        }
    }

    std::vector<std::shared_ptr<Slot>> slots_;
    int emitting_ = 0;
};

/// The connect-only face of a Signal, which is what the registry hands out: callers may
/// subscribe, only the owner emits.
template <class... Args>
class Sink {
  public:
    explicit Sink(Signal<Args...>& signal) noexcept : signal_(&signal) {}

    /// See Signal::connect.
    [[nodiscard]] Connection connect(typename Signal<Args...>::Callback callback) {
        return signal_->connect(std::move(callback));
    }
    [[nodiscard]] std::size_t size() const noexcept { return signal_->size(); }
    [[nodiscard]] bool empty() const noexcept { return signal_->empty(); }

  private:
    Signal<Args...>* signal_;
};

}  // namespace luxel::ecs
