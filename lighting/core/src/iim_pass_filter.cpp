#include "iim_pass_filter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace luxel::lighting {

IimPassFilter::IimPassFilter(const std::vector<SurfaceTexel>& texels, std::vector<glm::vec3> values,
                             std::vector<double> noise, int radius, double noise_sigmas)
    : values_(std::move(values)),
      noise_(std::move(noise)),
      radius_(std::max(radius, 0)),
      sigmas_(noise_sigmas) {
    const std::size_t count = std::min(texels.size(), values_.size());
    values_.resize(count);
    if (noise_.size() != count) {
        noise_.clear();  // no noise estimate: the plain tent
    }
    positions_.reserve(count);
    int x1 = -1;
    int y1 = -1;
    x0_ = count > 0 ? texels[0].x : 0;
    y0_ = count > 0 ? texels[0].y : 0;
    for (std::size_t i = 0; i < count; ++i) {
        positions_.emplace_back(texels[i].x, texels[i].y);
        x0_ = std::min(x0_, texels[i].x);
        y0_ = std::min(y0_, texels[i].y);
        x1 = std::max(x1, texels[i].x);
        y1 = std::max(y1, texels[i].y);
    }
    width_ = count > 0 ? x1 - x0_ + 1 : 0;
    height_ = count > 0 ? y1 - y0_ + 1 : 0;
    index_.assign(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_), -1);
    for (std::size_t i = 0; i < count; ++i) {
        index_[static_cast<std::size_t>(positions_[i].y - y0_) * static_cast<std::size_t>(width_) +
               static_cast<std::size_t>(positions_[i].x - x0_)] = static_cast<std::int32_t>(i);
    }
    filtered_.assign(count, glm::vec3(0.0f));
    targets_.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
        targets_[i] = static_cast<std::uint32_t>(i);
    }
    bounds_ = {x0_, y0_, x0_ + width_ - 1, y0_ + height_ - 1};
}

std::int32_t IimPassFilter::neighbour(std::size_t i, int dx, int dy) const {
    const int x = positions_[i].x - x0_ + dx;
    const int y = positions_[i].y - y0_ + dy;
    if (x < 0 || y < 0 || x >= width_ || y >= height_) {
        return -1;
    }
    return index_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                  static_cast<std::size_t>(x)];
}

void IimPassFilter::restrict_to(const std::vector<std::uint32_t>& changed) {
    std::vector<std::uint8_t> chosen(values_.size(), 0);
    targets_.clear();
    bounds_ = {0, 0, -1, -1};
    for (const std::uint32_t i : changed) {
        if (i >= positions_.size()) {
            continue;
        }
        for (int dy = -radius_; dy <= radius_; ++dy) {
            for (int dx = -radius_; dx <= radius_; ++dx) {
                const std::int32_t j = neighbour(i, dx, dy);
                if (j < 0 || chosen[static_cast<std::size_t>(j)] != 0) {
                    continue;
                }
                chosen[static_cast<std::size_t>(j)] = 1;
                targets_.push_back(static_cast<std::uint32_t>(j));
                const glm::ivec2 p = positions_[static_cast<std::size_t>(j)];
                bounds_ = bounds_.z < bounds_.x
                              ? glm::ivec4(p, p)
                              : glm::ivec4(glm::min(glm::ivec2(bounds_), p),
                                           glm::max(glm::ivec2(bounds_.z, bounds_.w), p));
            }
        }
    }
    std::sort(targets_.begin(), targets_.end());
    cursor_ = 0;
}

void IimPassFilter::leave_out_enclosed(std::span<const TexelCover> cover) {
    left_out_.clear();
    // A cover of another texel count (never expected) leaves nothing out.
    if (cover.size() != values_.size()) {
        return;
    }
    for (std::size_t i = 0; i < cover.size(); ++i) {
        if (cover[i] == TexelCover::Enclosed) {
            left_out_.resize(values_.size(), 0);
            left_out_[i] = 1;
        }
    }
}

std::size_t IimPassFilter::run(std::size_t max_texels) {
    const std::size_t end = std::min(targets_.size(), cursor_ + max_texels);
    const bool noise_aware = !noise_.empty() && sigmas_ > 0.0;
    const int radius = radius_;
    for (std::size_t t = cursor_; t < end; ++t) {
        const std::size_t i = targets_[t];
        if (!left_out_.empty() && left_out_[i] != 0) {
            filtered_[i] = values_[i];
            continue;
        }
        glm::dvec3 sum(0.0);
        double weights = 0.0;
        for (int dy = -radius; dy <= radius; ++dy) {
            for (int dx = -radius; dx <= radius; ++dx) {
                const std::int32_t j = neighbour(i, dx, dy);
                if (j < 0 || (!left_out_.empty() && left_out_[static_cast<std::size_t>(j)] != 0)) {
                    continue;
                }
                const auto other = static_cast<std::size_t>(j);
                double w =
                    static_cast<double>((radius + 1 - std::abs(dx)) * (radius + 1 - std::abs(dy)));
                if (noise_aware && other != i) {
                    const glm::dvec3 d = glm::dvec3(values_[other]) - glm::dvec3(values_[i]);
                    const double difference = glm::dot(d, d);
                    const double spread = sigmas_ * sigmas_ * (noise_[i] + noise_[other]);
                    // No noise at all (e.g. two black texels): any difference is real.
                    w *= spread > 0.0 ? std::exp(-0.5 * difference / spread)
                                      : (difference > 0.0 ? 0.0 : 1.0);
                }
                sum += w * glm::dvec3(values_[other]);
                weights += w;
            }
        }
        filtered_[i] = weights > 0.0 ? glm::vec3(sum / weights) : glm::vec3(0.0f);
    }
    const std::size_t done = end - cursor_;
    cursor_ = end;
    return done;
}

}  // namespace luxel::lighting
