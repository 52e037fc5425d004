#include "luxel/runtime/jobs.hpp"

#include <algorithm>

#include <tbb/info.h>

namespace luxel {

int JobSystem::hardware_threads() {
    return std::max(1, tbb::info::default_concurrency());
}

JobSystem::JobSystem(int thread_count)
    : thread_count_(thread_count <= 0 ? hardware_threads() : thread_count),
      arena_(std::make_unique<tbb::task_arena>(thread_count_)) {}

JobSystem::~JobSystem() = default;

}  // namespace luxel
