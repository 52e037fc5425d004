#include "luxel/lighting/core/caustic_photons.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>

#include "luxel/lighting/core/photon_differential.hpp"
#include "luxel/runtime/error.hpp"

namespace luxel::lighting {
namespace {

/// Photons per parallel work item. Fixed (not derived from the thread count) so that the
/// per-chunk counters add up in the same order on any machine.
constexpr std::size_t kPhotonsPerChunk = 64;

/// The radius footprint code 1 stands for (encode_footprint_radius); CAUSTIC_FOOTPRINT_BASE
/// in the shaders.
constexpr double kFootprintRadiusBase = 1e-4;

bool has_power(const glm::vec3& power) {
    return power.r > 0.0f || power.g > 0.0f || power.b > 0.0f;
}

/// Turns `differential` as scatter_specular turned the photon from `arriving` to `leaving`
/// (which of reflection and refraction it chose is read from the sides the two lie on).
void follow_differential(const RayScene& scene, const RayHit& hit, const FacingNormals& normals,
                         const TraceMaterial& material, const glm::vec3& arriving,
                         const glm::vec3& leaving, PhotonDifferential& differential) {
    if (!differential.valid) {
        return;
    }
    // The facing shading normal is the hit's, flipped on a back face, or the geometric one
    // where the interpolated normal bends past the face (flat there: no change).
    const float side = glm::dot(normals.shading, hit.shading_normal);
    const glm::mat3 jacobian = side > 0.999f    ? shading_normal_jacobian(scene, hit)
                               : side < -0.999f ? -shading_normal_jacobian(scene, hit)
                                                : glm::mat3(0.0f);
    const bool refracted = glm::dot(leaving, normals.geometric) < 0.0f;
    if (!refracted) {
        reflect(differential, arriving, normals.shading, jacobian);
        return;
    }
    const float eta = normals.front ? 1.0f / material.ior : material.ior;
    refract(differential, arriving, leaving, normals.shading, jacobian, eta);
}

}  // namespace

std::uint32_t encode_lightmap_uv(const glm::vec2& uv) {
    const auto fixed = [](float value) {
        // NaN fails both comparisons of the clamp's guard and reads 0.
        const float clamped = value > 0.0f ? std::min(value, 1.0f) : 0.0f;
        return static_cast<std::uint32_t>(std::lround(clamped * 65535.0f));
    };
    return fixed(uv.x) | (fixed(uv.y) << 16);
}

glm::vec2 decode_lightmap_uv(std::uint32_t bits) {
    return glm::vec2(static_cast<float>(bits & 0xFFFFu), static_cast<float>(bits >> 16)) / 65535.0f;
}

glm::vec2 CausticPhoton::lightmap_uv() const {
    return decode_lightmap_uv(lightmap_uv_bits);
}

CausticTraceCounters& CausticTraceCounters::operator+=(const CausticTraceCounters& other) {
    photons += other.photons;
    traced += other.traced;
    segments += other.segments;
    stored += other.stored;
    direct_diffuse += other.direct_diffuse;
    escaped += other.escaped;
    absorbed += other.absorbed;
    truncated += other.truncated;
    return *this;
}

std::uint32_t encode_footprint_radius(float radius) {
    if (!(radius > 0.0f) || !std::isfinite(radius)) {
        return 0;
    }
    const double code = 1.0 + 16.0 * std::log2(static_cast<double>(radius) / kFootprintRadiusBase);
    return static_cast<std::uint32_t>(std::clamp(std::lround(code), 1L, 255L));
}

float decode_footprint_radius(std::uint32_t code) {
    if (code == 0) {
        return 0.0f;
    }
    return static_cast<float>(kFootprintRadiusBase *
                              std::exp2((static_cast<double>(std::min(code, 255u)) - 1.0) / 16.0));
}

std::optional<CausticPhoton> trace_caustic_photon(
    const RayScene& scene, std::span<const TraceMaterial> materials, const EmittedPhoton& photon,
    PhotonDifferential differential, std::uint64_t sample_index, std::uint32_t seed,
    std::uint32_t max_specular_interactions, CausticTraceCounters& counters, PathCells* cells,
    glm::vec3* incident_direction) {
    // An escaped segment is recorded out to here: beyond any region a list records over.
    constexpr float kEscape = 1e6f;
    glm::vec3 origin = photon.origin;
    glm::vec3 direction = photon.direction;
    glm::vec3 power = photon.power;
    std::uint32_t specular = 0;
    std::uint32_t dim = 4;  // 0-3 chose the emission
    const TraceMaterial fallback{};
    ClosedMedium medium;
    for (;;) {
        ++counters.segments;
        const auto hit = scene.intersect(origin, direction);
        if (cells != nullptr) {
            cells->add_segment(origin, hit ? hit->position : origin + kEscape * direction);
        }
        if (!hit) {
            ++counters.escaped;
            return std::nullopt;
        }
        const TraceMaterial& material =
            hit->material < materials.size() ? materials[hit->material] : fallback;
        const FacingNormals normals = facing_normals(*hit, direction);
        const bool front = normals.front;
        transfer(differential, direction, hit->distance, normals.geometric);

        if (material.scattering == Scattering::Diffuse) {
            if (specular == 0) {
                ++counters.direct_diffuse;
                return std::nullopt;
            }
            if (!front) {
                // As for global photons: a one-sided surface has no light map behind it.
                ++counters.absorbed;
                return std::nullopt;
            }
            ++counters.stored;
            medium.absorb(hit->distance, power);
            if (incident_direction != nullptr) {
                *incident_direction = direction;
            }
            const std::int32_t surface = hit->surface <= kMaxCausticSurface ? hit->surface : -1;
            const std::uint32_t uv = surface >= 0 ? encode_lightmap_uv(hit->lightmap_uv) : 0;
            // The disc of the patch's area; half its longer side was tried and blurred the
            // ring's sharp caustic lines close up (caustic error 30% against 22% at 0.8 m).
            const float radius = std::sqrt(footprint_area(differential) / glm::pi<float>());
            return CausticPhoton{hit->position, surface, encode_footprint_radius(radius), power,
                                 uv};
        }

        if (specular >= max_specular_interactions) {
            ++counters.truncated;
            return std::nullopt;
        }
        ++specular;
        const double xi = material.scattering == Scattering::Dielectric
                              ? photon_sample(sample_index, dim++, seed)
                              : 0.0;
        const glm::vec3 arriving = direction;
        medium.update(material, front,
                      scatter_specular(material, *hit, normals, xi, origin, direction, power));
        follow_differential(scene, *hit, normals, material, arriving, direction, differential);
        // A black mirror or a black tint leaves nothing to carry.
        if (!has_power(power)) {
            ++counters.absorbed;
            return std::nullopt;
        }
    }
}

CausticPhotonList::CausticPhotonList(std::uint32_t photon_count, std::uint32_t slices,
                                     std::uint32_t seed, bool stand_in)
    : photon_count_(photon_count),
      seed_(seed),
      slices_per_generation_(slices),
      slice_stride_(slices == 0 ? 0 : (photon_count + slices - 1) / slices),
      slices_(slices),
      dirty_(slices, 1),
      hidden_(slices, 0),
      slice_retraces_(slices, 0),
      dirty_count_(slices),
      stand_in_enabled_(stand_in) {
    if (slices == 0) {
        throw Error("CausticPhotonList: need at least one slice");
    }
}

void CausticPhotonList::set_emitter(CausticEmitter emitter, const AxisBox& path_region) {
    emitter_ = std::move(emitter);
    path_cells_ = PathCells(path_region);
    invalidate();
}

void CausticPhotonList::set_siblings_keeping_photons(std::vector<BoundingSphere> siblings) {
    emitter_.set_siblings(std::move(siblings));
}

bool CausticPhotonList::paths_meet(std::span<const AxisBox> boxes) const {
    return std::any_of(boxes.begin(), boxes.end(),
                       [&](const AxisBox& box) { return path_cells_.meets(box); });
}

void CausticPhotonList::invalidate() {
    // A settled list that a change meets: its stale photons belong to a scene that is gone, so
    // fresh slices will stand in for them. A list still retracing is being hit by something
    // that keeps moving: its stale photons are a few frames old and stay in view.
    const bool was_current = dirty_count_ == 0;
    end_stand_in();
    stand_in_allowed_ = stand_in_enabled_ && was_current;
    catch_up_generations_ = stand_in_allowed_ ? generations_ : 0;
    path_cells_.clear();  // every photon that stays in use is traced again, and recorded then
    std::fill(dirty_.begin(), dirty_.end(), std::uint8_t{1});
    dirty_count_ = slices_per_generation_;
    tracing_ = false;  // a part traced in the old scene would mix two scenes in one slice
    staged_.clear();
    refined_.clear();
    refined_done_.clear();
    refined_count_ = 0;
    if (slice_count() > slices_per_generation_) {
        // Back to the first generation, whose photons carry the pair's power alone again until
        // their retrace replaces them: each of the m slices shown carried 1 / m of it.
        const auto scale = static_cast<float>(static_cast<double>(slice_count()) /
                                              static_cast<double>(slices_per_generation_));
        slices_.resize(slices_per_generation_);
        slice_retraces_.resize(slices_per_generation_);
        for (std::uint32_t k = 0; k < slices_per_generation_; ++k) {
            for (CausticPhoton& photon : slices_[k]) {
                photon.power *= scale;
            }
            ++slice_retraces_[k];
        }
        generations_ = 1;
    }
}

bool CausticPhotonList::catching_up() const {
    if (catch_up_generations_ == 0) {
        return false;
    }
    return dirty_count_ > 0 || generations_ < std::min(catch_up_generations_, generation_limit_);
}

std::optional<std::uint32_t> CausticPhotonList::slice_for_frame(std::uint64_t frame) const {
    if (dirty_count_ == 0) {
        return std::nullopt;
    }
    const std::uint32_t count = slices_per_generation_;
    const auto start = static_cast<std::uint32_t>(frame % count);
    for (std::uint32_t offset = 0; offset < count; ++offset) {
        const std::uint32_t slice = (start + offset) % count;
        if (dirty_[slice] != 0) {
            return slice;
        }
    }
    return std::nullopt;
}

void CausticPhotonList::set_generation_limit(std::uint32_t generations) {
    generation_limit_ = std::max<std::uint32_t>(generations, 1);
}

std::optional<std::uint32_t> CausticPhotonList::refinement_slice() const {
    if (dirty_count_ > 0 || generations_ >= generation_limit_ || photon_count_ == 0) {
        return std::nullopt;
    }
    for (std::uint32_t k = 0; k < slices_per_generation_; ++k) {
        if (k >= refined_done_.size() || refined_done_[k] == 0) {
            return generations_ * slices_per_generation_ + k;
        }
    }
    return std::nullopt;  // not reached: a complete generation is averaged in at once
}

std::uint32_t CausticPhotonList::slice_size(std::uint32_t slice) const {
    const std::uint32_t count = slices_per_generation_;
    const std::uint32_t k = slice % count;
    return k < photon_count_ ? (photon_count_ - k + count - 1) / count : 0;
}

std::uint64_t CausticPhotonList::sample_index(std::uint32_t photon) const {
    const std::uint32_t count = slices_per_generation_;
    return slice_sample_index(photon % count, photon / count);
}

std::uint64_t CausticPhotonList::slice_sample_index(std::uint32_t slice, std::uint32_t i) const {
    return 1 + static_cast<std::uint64_t>(slice) * slice_stride_ + i;
}

void CausticPhotonList::store_slice(std::uint32_t slice,
                                    std::span<const std::optional<CausticPhoton>> traced) {
    std::vector<CausticPhoton> photons;
    photons.reserve(traced.size());
    for (const auto& photon : traced) {
        if (photon) {
            photons.push_back(*photon);
        }
    }
    // A whole slice traced at once supersedes a part of it in progress.
    if (tracing_ && tracing_slice_ == slice) {
        tracing_ = false;
        staged_.clear();
    }
    commit_slice(slice, std::move(photons));
}

void CausticPhotonList::commit_slice(std::uint32_t slice, std::vector<CausticPhoton> photons) {
    // Dirty slices are the first generation's; any later index is a refinement slice.
    if (slice >= slices_per_generation_) {
        const std::uint32_t k = slice % slices_per_generation_;
        const std::uint32_t appended = slice_count() - generations_ * slices_per_generation_;
        if (appended > 0 || (refined_count_ == 0 && catching_up())) {
            append_refined_slice(slice, std::move(photons));
            return;
        }
        refined_.resize(slices_per_generation_);
        refined_done_.resize(slices_per_generation_, 0);
        refined_[k] = std::move(photons);
        if (refined_done_[k] == 0) {
            refined_done_[k] = 1;
            ++refined_count_;
        }
        if (refined_count_ == slices_per_generation_) {
            complete_generation();
        }
        return;
    }
    slices_.at(slice) = std::move(photons);
    if (dirty_[slice] != 0) {
        dirty_[slice] = 0;
        --dirty_count_;
    }
    ++slice_retraces_[slice];
    hidden_[slice] = 0;
    update_stand_in();
}

void CausticPhotonList::update_stand_in() {
    if (!stand_in_allowed_) {
        return;
    }
    if (dirty_count_ == 0) {
        end_stand_in();
        stand_in_allowed_ = false;
        return;
    }
    const std::uint32_t fresh = slices_per_generation_ - dirty_count_;
    // Until a quarter of the slices are fresh they show beside the stale ones: one slice of
    // eight alone, eight times as bright, was measured noisier than the stale ones beside it
    // (docs/RESULTS.md, "After a change").
    if (!standing_in_ && 4 * fresh < slices_per_generation_) {
        return;
    }
    const float scale = static_cast<float>(slices_per_generation_) / static_cast<float>(fresh);
    stand_ins_.resize(slices_per_generation_);
    for (std::uint32_t k = 0; k < slices_per_generation_; ++k) {
        if (dirty_[k] != 0) {
            if (hidden_[k] == 0) {
                hidden_[k] = 1;
                ++slice_retraces_[k];
            }
            continue;
        }
        stand_ins_[k] = slices_[k];
        for (CausticPhoton& photon : stand_ins_[k]) {
            photon.power *= scale;
        }
        ++slice_retraces_[k];
    }
    standing_in_ = true;
}

void CausticPhotonList::end_stand_in() {
    if (!standing_in_) {
        return;
    }
    // Every first-generation slice was hidden or shown scaled: readers re-read them all.
    for (std::uint32_t k = 0; k < slices_per_generation_; ++k) {
        hidden_[k] = 0;
        ++slice_retraces_[k];
    }
    stand_ins_.clear();
    standing_in_ = false;
}

std::uint32_t CausticPhotonList::part_photons_left() const {
    if (tracing_) {
        return slice_size(tracing_slice_) - tracing_next_;
    }
    if (const auto slice = slice_for_frame(part_cursor_)) {
        return slice_size(*slice);
    }
    if (const auto slice = refinement_slice()) {
        return slice_size(*slice);
    }
    return 0;
}

void CausticPhotonList::append_refined_slice(std::uint32_t slice,
                                             std::vector<CausticPhoton> photons) {
    // In order: the slices a catching-up list shows are its first generation's and then
    // refinement slices 0, 1, ... of each generation since.
    if (slice != slice_count()) {
        throw Error("CausticPhotonList: a catching-up list's refinement slices come in order");
    }
    // m slices shown: each carries 1 / m of the pair's power, each photon K / m of the power it
    // was emitted with (a complete generation's G K slices: 1 / G, as complete_generation
    // leaves them).
    const double before = slice_count();
    const double after = before + 1.0;
    const auto keep = static_cast<float>(before / after);
    const auto add = static_cast<float>(static_cast<double>(slices_per_generation_) / after);
    for (std::uint32_t s = 0; s < slice_count(); ++s) {
        for (CausticPhoton& photon : slices_[s]) {
            photon.power *= keep;
        }
        ++slice_retraces_[s];
    }
    for (CausticPhoton& photon : photons) {
        photon.power *= add;
    }
    slices_.push_back(std::move(photons));
    slice_retraces_.push_back(1);
    const std::uint32_t k = slice % slices_per_generation_;
    refined_done_.resize(slices_per_generation_, 0);
    refined_done_[k] = 1;
    ++refined_count_;
    if (refined_count_ == slices_per_generation_) {
        refined_.clear();
        refined_done_.clear();
        refined_count_ = 0;
        ++generations_;
    }
}

std::uint64_t CausticPhotonList::catch_up_photons_left() const {
    if (!catching_up()) {
        return 0;
    }
    const std::uint64_t target =
        static_cast<std::uint64_t>(std::min(catch_up_generations_, generation_limit_)) *
        slices_per_generation_;
    // Dirty slices are the first generation's; the refinement slices shown count (they are
    // appended as they are traced while catching up).
    std::uint64_t slices = dirty_count_;
    if (target > slice_count()) {
        slices += target - slice_count();
    }
    const std::uint64_t left = slices * slice_stride_;
    return tracing_ ? left - std::min<std::uint64_t>(left, tracing_next_) : left;
}

void CausticPhotonList::complete_generation() {
    const double g = generations_;
    const auto keep = static_cast<float>(g / (g + 1.0));
    const auto add = static_cast<float>(1.0 / (g + 1.0));
    for (std::uint32_t s = 0; s < slice_count(); ++s) {
        for (CausticPhoton& photon : slices_[s]) {
            photon.power *= keep;
        }
        ++slice_retraces_[s];
    }
    for (std::vector<CausticPhoton>& photons : refined_) {
        for (CausticPhoton& photon : photons) {
            photon.power *= add;
        }
        slices_.push_back(std::move(photons));
        slice_retraces_.push_back(1);
    }
    refined_.clear();
    refined_done_.clear();
    refined_count_ = 0;
    ++generations_;
}

CausticTraceCounters CausticPhotonList::retrace_slice(const RayScene& scene,
                                                      std::span<const TraceMaterial> materials,
                                                      std::uint32_t slice,
                                                      std::uint32_t max_specular_interactions,
                                                      JobSystem& jobs) {
    const SliceWork work[] = {{this, slice}};
    return retrace(scene, materials, work, max_specular_interactions, jobs);
}

std::optional<CausticPhoton> CausticPhotonList::trace_photon(
    const RayScene& scene, std::span<const TraceMaterial> materials, std::uint32_t slice,
    std::uint32_t i, std::uint32_t max_specular_interactions, CausticTraceCounters& counters,
    PathCells* cells) const {
    const std::uint64_t index = slice_sample_index(slice, i);
    const EmittedPhoton emitted = emitter_.emit(
        {photon_sample(index, 0, seed_), photon_sample(index, 1, seed_)},
        {photon_sample(index, 2, seed_), photon_sample(index, 3, seed_)}, photon_count_);
    ++counters.photons;
    if (!has_power(emitted.power)) {
        return std::nullopt;  // outside the spot's cone or behind the area light
    }
    ++counters.traced;
    return trace_caustic_photon(scene, materials, emitted,
                                emitter_.differential(emitted, photon_count_), index, seed_,
                                max_specular_interactions, counters, cells);
}

CausticTraceCounters CausticPhotonList::trace_part(const RayScene& scene,
                                                   std::span<const TraceMaterial> materials,
                                                   std::uint32_t max_photons,
                                                   std::uint32_t max_specular_interactions,
                                                   JobSystem& jobs) {
    CausticTraceCounters sum;
    if (!tracing_) {
        std::optional<std::uint32_t> slice = slice_for_frame(part_cursor_);
        if (!slice) {
            slice = refinement_slice();
        }
        if (!slice) {
            return sum;
        }
        tracing_ = true;
        tracing_slice_ = *slice;
        tracing_next_ = 0;
        staged_.clear();
        staged_.reserve(slice_size(*slice));
    }
    const std::uint32_t size = slice_size(tracing_slice_);
    const std::uint32_t begin = tracing_next_;
    const std::uint32_t count = std::min(std::max<std::uint32_t>(max_photons, 1), size - begin);
    // Traced into per-photon slots in fixed chunks and appended in photon order, so the slice
    // does not depend on the thread count or on how it was cut into parts.
    std::vector<std::optional<CausticPhoton>> traced(count);
    const std::size_t chunks = (count + kPhotonsPerChunk - 1) / kPhotonsPerChunk;
    std::vector<CausticTraceCounters> chunk_counters(chunks);
    std::vector<PathCells> chunk_cells(chunks, PathCells(path_cells_.region()));
    jobs.parallel_for(0, chunks, [&](std::size_t chunk) {
        const std::size_t end = std::min<std::size_t>(count, (chunk + 1) * kPhotonsPerChunk);
        for (std::size_t i = chunk * kPhotonsPerChunk; i < end; ++i) {
            traced[i] = trace_photon(
                scene, materials, tracing_slice_, begin + static_cast<std::uint32_t>(i),
                max_specular_interactions, chunk_counters[chunk], &chunk_cells[chunk]);
        }
    });
    for (std::size_t chunk = 0; chunk < chunks; ++chunk) {
        sum += chunk_counters[chunk];
        // Recorded as traced, the staged part too: a change where it went discards it.
        path_cells_.merge(chunk_cells[chunk]);
    }
    for (const auto& photon : traced) {
        if (photon) {
            staged_.push_back(*photon);
        }
    }
    tracing_next_ = begin + count;
    if (tracing_next_ >= size) {
        tracing_ = false;
        if (tracing_slice_ < slices_per_generation_) {
            part_cursor_ = tracing_slice_ + 1;  // the next dirty slice after this one
        }
        ++parts_completed_;
        commit_slice(tracing_slice_, std::move(staged_));
        staged_ = {};
    }
    return sum;
}

CausticTraceCounters CausticPhotonList::retrace(const RayScene& scene,
                                                std::span<const TraceMaterial> materials,
                                                std::span<const SliceWork> work,
                                                std::uint32_t max_specular_interactions,
                                                JobSystem& jobs) {
    // All photons of all slices in one index space: work item w owns [first[w], first[w + 1]).
    std::vector<std::size_t> first(work.size() + 1, 0);
    for (std::size_t w = 0; w < work.size(); ++w) {
        // A stored slice, or one of the generation being refined.
        if (work[w].list == nullptr ||
            work[w].slice >= work[w].list->slice_count() + work[w].list->slices_per_generation_) {
            throw Error("CausticPhotonList::retrace: no such list or slice");
        }
        first[w + 1] = first[w] + work[w].list->slice_size(work[w].slice);
    }
    const std::size_t total = first.back();
    std::vector<std::optional<CausticPhoton>> traced(total);
    const std::size_t chunks = (total + kPhotonsPerChunk - 1) / kPhotonsPerChunk;
    std::vector<CausticTraceCounters> chunk_counters(chunks);
    // Each chunk's path cells per work item it reaches (a chunk spans one or two lists).
    std::vector<std::vector<std::pair<std::size_t, PathCells>>> chunk_cells(chunks);
    jobs.parallel_for(0, chunks, [&](std::size_t chunk) {
        CausticTraceCounters& counters = chunk_counters[chunk];
        const std::size_t begin = chunk * kPhotonsPerChunk;
        const std::size_t end = std::min(total, begin + kPhotonsPerChunk);
        auto w = static_cast<std::size_t>(std::upper_bound(first.begin(), first.end(), begin) -
                                          first.begin()) -
                 1;
        auto& cells = chunk_cells[chunk];
        for (std::size_t i = begin; i < end; ++i) {
            while (i >= first[w + 1]) {
                ++w;
            }
            if (cells.empty() || cells.back().first != w) {
                cells.emplace_back(w, PathCells(work[w].list->path_cells_.region()));
            }
            traced[i] = work[w].list->trace_photon(
                scene, materials, work[w].slice, static_cast<std::uint32_t>(i - first[w]),
                max_specular_interactions, counters, &cells.back().second);
        }
    });
    CausticTraceCounters sum;
    for (std::size_t chunk = 0; chunk < chunks; ++chunk) {
        sum += chunk_counters[chunk];
        for (const auto& [w, cells] : chunk_cells[chunk]) {
            work[w].list->path_cells_.merge(cells);
        }
    }
    for (std::size_t w = 0; w < work.size(); ++w) {
        work[w].list->store_slice(
            work[w].slice, std::span<const std::optional<CausticPhoton>>(traced.data() + first[w],
                                                                         first[w + 1] - first[w]));
    }
    return sum;
}

std::size_t CausticPhotonList::stored_count() const {
    std::size_t count = 0;
    for (std::uint32_t k = 0; k < slice_count(); ++k) {
        count += slice(k).size();
    }
    return count;
}

glm::dvec3 CausticPhotonList::stored_power() const {
    glm::dvec3 sum(0.0);
    for (std::uint32_t k = 0; k < slice_count(); ++k) {
        for (const CausticPhoton& photon : slice(k)) {
            sum += glm::dvec3(photon.power);
        }
    }
    return sum;
}

std::size_t CausticPhotonList::bytes_used() const {
    std::size_t bytes = sizeof(*this);
    for (const auto& photons : slices_) {
        bytes += photons.capacity() * sizeof(CausticPhoton);
    }
    for (const auto& photons : refined_) {
        bytes += photons.capacity() * sizeof(CausticPhoton);
    }
    bytes += staged_.capacity() * sizeof(CausticPhoton);
    bytes += (slices_.capacity() + refined_.capacity()) * sizeof(std::vector<CausticPhoton>);
    bytes += refined_done_.capacity() * sizeof(std::uint8_t);
    bytes += (dirty_.capacity() + hidden_.capacity()) * sizeof(std::uint8_t);
    for (const auto& photons : stand_ins_) {
        bytes += photons.capacity() * sizeof(CausticPhoton);
    }
    bytes += slice_retraces_.capacity() * sizeof(std::uint64_t);
    return bytes;
}

}  // namespace luxel::lighting
