#include "luxel/lighting/core/seam_stitcher.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

namespace luxel::lighting {

namespace {

/// One texel a lookup reads, and its bilinear weight.
struct Tap {
    std::uint32_t texel = 0;  ///< index into the object's texels
    double weight = 0.0;
};

struct PageTexel {
    std::int32_t page = 0;
    int x = 0;
    int y = 0;
    auto operator<=>(const PageTexel&) const = default;
};

}  // namespace

// Eigen's sparse Cholesky rather than our own solver: the field's library for exactly this
// (symmetric positive definite, a few thousand unknowns, factored once, solved many times).
struct SeamStitcher::Object {
    std::vector<SeamSample> samples;
    std::vector<std::uint32_t> surfaces;
    std::vector<PageTexel> texels;
    /// What the passes last committed at each texel, and what the stitcher last wrote there:
    /// a texel whose page value is not what the stitcher wrote has been gathered again.
    std::vector<glm::vec3> gathered;
    std::vector<glm::vec3> written;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
    bool solvable = false;
};

SeamStitcher::SeamStitcher() = default;
SeamStitcher::~SeamStitcher() = default;

void SeamStitcher::add_object(std::vector<SeamSample> samples, std::span<const IimPage> pages) {
    auto object = std::make_unique<Object>();
    std::map<PageTexel, std::uint32_t> index;
    // The same bilinear taps as RadiancePage::sample and shaders/render/iim.glsl.
    const auto taps = [&](std::int32_t page, const glm::vec2& point, double sign,
                          std::vector<Tap>& out) {
        if (page < 0 || static_cast<std::size_t>(page) >= pages.size()) {
            return false;
        }
        const int size = pages[static_cast<std::size_t>(page)].current.size;
        if (size <= 0) {
            return false;
        }
        const float extent = static_cast<float>(size);
        const float fx = std::clamp(point.x - 0.5f, 0.0f, extent - 1.0f);
        const float fy = std::clamp(point.y - 0.5f, 0.0f, extent - 1.0f);
        const int x0 = static_cast<int>(fx);
        const int y0 = static_cast<int>(fy);
        const int x1 = std::min(x0 + 1, size - 1);
        const int y1 = std::min(y0 + 1, size - 1);
        const double tx = static_cast<double>(fx - static_cast<float>(x0));
        const double ty = static_cast<double>(fy - static_cast<float>(y0));
        const std::array<std::tuple<int, int, double>, 4> corners{
            std::tuple{x0, y0, (1.0 - tx) * (1.0 - ty)}, std::tuple{x1, y0, tx * (1.0 - ty)},
            std::tuple{x0, y1, (1.0 - tx) * ty}, std::tuple{x1, y1, tx * ty}};
        for (const auto& [x, y, w] : corners) {
            if (w <= 0.0) {
                continue;
            }
            const auto [it, added] = index.try_emplace(
                PageTexel{page, x, y}, static_cast<std::uint32_t>(object->texels.size()));
            if (added) {
                object->texels.push_back(it->first);
            }
            out.push_back({it->second, sign * w});
        }
        return true;
    };
    std::vector<Eigen::Triplet<double>> entries;
    std::vector<Tap> row;
    for (const SeamSample& sample : samples) {
        row.clear();
        if (!taps(sample.page_a, sample.point_a, 1.0, row) ||
            !taps(sample.page_b, sample.point_b, -1.0, row)) {
            continue;
        }
        // w * row^T row: the sample's share of J^T J.
        for (const Tap& i : row) {
            for (const Tap& j : row) {
                entries.emplace_back(static_cast<int>(i.texel), static_cast<int>(j.texel),
                                     kSeamWeight * i.weight * j.weight);
            }
        }
        object->surfaces.push_back(sample.surface_a);
        object->surfaces.push_back(sample.surface_b);
    }
    if (object->texels.empty()) {
        return;
    }
    const auto n = static_cast<Eigen::Index>(object->texels.size());
    for (Eigen::Index i = 0; i < n; ++i) {
        entries.emplace_back(static_cast<int>(i), static_cast<int>(i), 1.0);
    }
    Eigen::SparseMatrix<double> system(n, n);
    system.setFromTriplets(entries.begin(), entries.end());
    object->solver.compute(system);
    object->solvable = object->solver.info() == Eigen::Success;
    std::sort(object->surfaces.begin(), object->surfaces.end());
    object->surfaces.erase(std::unique(object->surfaces.begin(), object->surfaces.end()),
                           object->surfaces.end());
    object->gathered.assign(object->texels.size(), glm::vec3(0.0f));
    // NaN never equals a page value, so the first stitch reads every texel as gathered.
    object->written.assign(object->texels.size(),
                           glm::vec3(std::numeric_limits<float>::quiet_NaN()));
    object->samples = std::move(samples);
    for (const std::uint32_t surface : object->surfaces) {
        object_of_[surface] = objects_.size();
        committed_.try_emplace(surface, false);
    }
    objects_.push_back(std::move(object));
}

void SeamStitcher::stitch(std::uint32_t surface, std::span<IimPage> pages, double now_seconds,
                          double fade_seconds) {
    const auto found = object_of_.find(surface);
    if (found == object_of_.end()) {
        return;
    }
    committed_[surface] = true;
    Object& object = *objects_[found->second];
    if (!object.solvable || !std::all_of(object.surfaces.begin(), object.surfaces.end(),
                                         [&](std::uint32_t s) { return committed_[s]; })) {
        return;
    }
    const auto n = static_cast<Eigen::Index>(object.texels.size());
    std::array<Eigen::VectorXd, 3> values;
    for (auto& channel : values) {
        channel.resize(n);
    }
    for (Eigen::Index i = 0; i < n; ++i) {
        const auto t = static_cast<std::size_t>(i);
        const PageTexel& texel = object.texels[t];
        if (static_cast<std::size_t>(texel.page) >= pages.size()) {
            return;
        }
        const glm::vec3 shown =
            pages[static_cast<std::size_t>(texel.page)].current.at(texel.x, texel.y);
        if (shown != object.written[t]) {
            object.gathered[t] = shown;
        }
        for (int c = 0; c < 3; ++c) {
            const double g = static_cast<double>(object.gathered[t][c]);
            values[static_cast<std::size_t>(c)][i] = std::isfinite(g) ? g : 0.0;
        }
    }
    for (auto& channel : values) {
        channel = object.solver.solve(channel);
        if (object.solver.info() != Eigen::Success) {
            return;
        }
    }
    // Per page, the rectangle of the texels written, so the renderer uploads only those.
    std::map<std::int32_t, glm::ivec4> changed;
    for (Eigen::Index i = 0; i < n; ++i) {
        const auto t = static_cast<std::size_t>(i);
        glm::vec3 stitched;
        for (int c = 0; c < 3; ++c) {
            const double v = values[static_cast<std::size_t>(c)][i];
            // The solution of non-negative data can dip a rounding below zero next to a
            // black texel; light never does.
            stitched[c] = std::isfinite(v) ? static_cast<float>(std::max(v, 0.0)) : 0.0f;
        }
        const PageTexel& texel = object.texels[t];
        IimPage& page = pages[static_cast<std::size_t>(texel.page)];
        if (page.current.at(texel.x, texel.y) != stitched) {
            page.commit(texel.x, texel.y, stitched, now_seconds, fade_seconds);
            auto [it, added] =
                changed.try_emplace(texel.page, glm::ivec4(texel.x, texel.y, texel.x, texel.y));
            it->second =
                glm::ivec4(std::min(it->second.x, texel.x), std::min(it->second.y, texel.y),
                           std::max(it->second.z, texel.x), std::max(it->second.w, texel.y));
        }
        object.written[t] = stitched;
    }
    for (const auto& [page, box] : changed) {
        pages[static_cast<std::size_t>(page)].current.mark_changed(
            {box.x, box.y, box.z - box.x + 1, box.w - box.y + 1});
    }
    ++stitches_;
}

std::vector<SeamSample> SeamStitcher::samples() const {
    std::vector<SeamSample> all;
    for (const auto& object : objects_) {
        all.insert(all.end(), object->samples.begin(), object->samples.end());
    }
    return all;
}

std::size_t SeamStitcher::texels() const {
    std::size_t count = 0;
    for (const auto& object : objects_) {
        count += object->texels.size();
    }
    return count;
}

}  // namespace luxel::lighting
