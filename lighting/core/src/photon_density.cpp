#include "luxel/lighting/core/photon_density.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>
#include <nanoflann.hpp>

namespace luxel::lighting {

/// nanoflann's dataset interface over a flat array of photons.
struct PhotonDensity::Tree {
    struct Photon {
        glm::vec3 position;
        glm::vec3 power;
    };
    std::vector<Photon> photons;

    [[nodiscard]] std::size_t kdtree_get_point_count() const { return photons.size(); }
    [[nodiscard]] float kdtree_get_pt(std::size_t photon, std::size_t dim) const {
        return photons[photon].position[static_cast<glm::length_t>(dim)];
    }
    template <class Box>
    bool kdtree_get_bbox(Box& /*box*/) const {
        return false;  // let nanoflann compute the bounds
    }

    using Index = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Tree>,
                                                      Tree, 3, std::uint32_t>;
    std::unique_ptr<Index> index;
};

PhotonDensity::PhotonDensity(const PhotonMap& map, std::span<const std::uint32_t> surfaces,
                             PhotonSelection selection)
    : tree_(std::make_unique<Tree>()) {
    for (std::uint32_t surface : surfaces) {
        for (std::size_t i = 0; i < map.surface(surface).hit_count(); ++i) {
            const StoredHit hit = map.hit(surface, i);
            if (selection == PhotonSelection::IndirectOnly && hit.bounces == 0) {
                continue;
            }
            tree_->photons.push_back({hit.position, hit.power});
        }
    }
    if (!tree_->photons.empty()) {
        tree_->index =
            std::make_unique<Tree::Index>(3, *tree_, nanoflann::KDTreeSingleIndexAdaptorParams(16));
    }
}

PhotonDensity::~PhotonDensity() = default;

std::size_t PhotonDensity::photon_count() const {
    return tree_->photons.size();
}

DensitySample PhotonDensity::sample(const glm::vec3& position, const glm::vec3& normal,
                                    const DensitySettings& settings) const {
    if (!tree_->index || settings.nearest == 0 || !(settings.max_radius > 0.0f)) {
        return {};
    }
    const std::size_t wanted = std::min<std::size_t>(settings.nearest, tree_->photons.size());
    std::vector<std::uint32_t> indices(wanted);
    std::vector<float> distances_squared(wanted);
    const float query[3] = {position.x, position.y, position.z};
    const std::size_t found =
        tree_->index->knnSearch(query, wanted, indices.data(), distances_squared.data());
    // r is the distance to the N-th neighbour, capped. The N-th photon itself lies on the disc's
    // rim and is left out: (N - 1) photons over pi r^2 is the unbiased k-nearest-neighbour
    // density for uniformly scattered photons, while counting all N overestimates by N/(N-1).
    // With fewer than N photons within the cap, all found count and the cap is the radius.
    const float cap_squared = settings.max_radius * settings.max_radius;
    float radius_squared = cap_squared;
    std::size_t counted = found;
    if (found == settings.nearest && distances_squared[found - 1] < cap_squared) {
        radius_squared = distances_squared[found - 1];
        counted = found - 1;
    }
    // A pile-up (N photons within a hair of the query: kd-tree ties, a focused caustic) would
    // divide by an area of zero. The radius has a floor of 1/1000 of the cap, inside which every
    // photon found counts: large where light really concentrates, but finite and bounded.
    const float floor_squared = cap_squared * 1e-6f;
    if (!(radius_squared >= floor_squared)) {
        radius_squared = floor_squared;
        counted = found;
    }
    if (!(radius_squared > 0.0f)) {
        return {};
    }
    const float slab = settings.disc_thickness * std::sqrt(radius_squared);
    glm::dvec3 total(0.0);
    for (std::size_t k = 0; k < counted; ++k) {
        if (distances_squared[k] > radius_squared) {
            break;  // sorted by distance
        }
        const Tree::Photon& photon = tree_->photons[indices[k]];
        if (std::abs(glm::dot(photon.position - position, normal)) > slab) {
            continue;
        }
        double weight = 1.0;
        if (settings.kernel == DensityKernel::Epanechnikov) {
            // Normalised over the disc: the integral of (1 - d^2/r^2) is pi r^2 / 2.
            weight = 2.0 * (1.0 - static_cast<double>(distances_squared[k]) /
                                      static_cast<double>(radius_squared));
        }
        total += weight * glm::dvec3(photon.power);
    }
    return {total, std::sqrt(static_cast<double>(radius_squared))};
}

glm::vec3 PhotonDensity::irradiance(const glm::vec3& position, const glm::vec3& normal,
                                    const DensitySettings& settings) const {
    const DensitySample found = sample(position, normal, settings);
    if (!(found.radius > 0.0)) {
        return glm::vec3(0.0f);
    }
    return glm::vec3(found.power / (glm::pi<double>() * found.radius * found.radius));
}

glm::vec3 PhotonDensity::radiance(const glm::vec3& position, const glm::vec3& normal,
                                  const glm::vec3& albedo, const DensitySettings& settings) const {
    return albedo * irradiance(position, normal, settings) / glm::pi<float>();
}

}  // namespace luxel::lighting
