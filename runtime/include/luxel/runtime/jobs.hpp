#pragma once

#include <cstddef>
#include <memory>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace luxel {

/// The job system: a TBB task arena with a fixed number of worker threads. Parallel work in luxel
/// runs inside it, so `--threads N` bounds everything the engine does at once (the game keeps the
/// rest of the machine).
class JobSystem {
  public:
    /// thread_count <= 0 means every hardware thread.
    explicit JobSystem(int thread_count = 0);
    ~JobSystem();
    JobSystem(const JobSystem&) = delete;
    JobSystem& operator=(const JobSystem&) = delete;

    [[nodiscard]] int thread_count() const { return thread_count_; }
    [[nodiscard]] static int hardware_threads();

    /// Calls body(i) for every i in [begin, end), in parallel, chunks of at least `grain`.
    template <class Body>
    void parallel_for(std::size_t begin, std::size_t end, Body&& body, std::size_t grain = 1) {
        arena_->execute([&] {
            tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, grain),
                              [&](const tbb::blocked_range<std::size_t>& range) {
                                  for (std::size_t i = range.begin(); i != range.end(); ++i) {
                                      body(i);
                                  }
                              });
        });
    }

    /// Runs fn inside the arena (so nested TBB algorithms use this system's threads).
    template <class Fn>
    decltype(auto) run(Fn&& fn) {
        return arena_->execute(std::forward<Fn>(fn));
    }

  private:
    int thread_count_;
    std::unique_ptr<tbb::task_arena> arena_;
};

}  // namespace luxel
