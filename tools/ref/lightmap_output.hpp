#pragma once

// Writing reference light maps: JSON (per surface, per texel, every component with its
// standard error) or OpenEXR pages.

#include <filesystem>
#include <string>

#include "luxel/lighting/reference/reference_integrator.hpp"

namespace luxel::ref {

/// What the files record about the run besides the texels.
struct RunInfo {
    std::string level;
    double time = 0.0;
    std::uint32_t seed = 1;
    double seconds = 0.0;
};

/// JSON: {"level", "time", "seed", "samples_per_texel", "caustic_photons",
/// "relative_standard_error": {direct, indirect, caustic}, "surfaces": [{"surface", "page",
/// "page_size", "x": [...], "y": [...], "area": [...], "direct": [[r, g, b], ...],
/// "direct_se": [...], "indirect", "indirect_se", "caustic", "caustic_se"}]}. Irradiance in
/// W/m^2, areas in m^2. Throws luxel::Error naming the file when it cannot be written.
void write_lightmaps_json(const std::filesystem::path& file,
                          const lighting::reference::ReferenceIntegrator& integrator,
                          const RunInfo& info);

/// EXR pages: for each light-map page P and component C, STEM.pageP.C.exr (page-sized, RGB
/// irradiance, alpha 1 where a texel has a value and 0 elsewhere), plus C_se for the standard
/// errors. Returns how many files were written.
std::size_t write_lightmap_pages(const std::filesystem::path& file,
                                 const lighting::reference::ReferenceIntegrator& integrator);

}  // namespace luxel::ref
