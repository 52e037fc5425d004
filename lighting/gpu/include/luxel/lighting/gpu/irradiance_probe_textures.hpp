#pragma once

#include <cstdint>

#include "luxel/lighting/core/irradiance_probes.hpp"
#include "luxel/runtime/gl_objects.hpp"
#include "luxel/runtime/program.hpp"

namespace luxel::lighting {

/// The irradiance probes on the GPU, for shaders/render/irradiance_probes.glsl: a storage
/// buffer with one record per probe (position with its offset and whether it is active, then
/// its nine SH irradiance coefficients, each a vec4, zero for the octahedral basis), the
/// probes' distance tiles in one RG32F atlas, kProbeDepthTile texels square each with their
/// octahedral border, and with ProbeBasis::Octahedral their irradiance tiles in one RGBA16F
/// atlas the same way (kProbeIrradianceTile square, 2.6 kB a probe), both sampled bilinearly
/// (the border makes the filter seamless across the octahedral folds). Half floats hold 11
/// bits of mantissa (0.05%) up to 65504: irradiance is clamped there before the upload, which
/// no lit room reaches (the sun at noon is about 1000 W/m^2), so no infinity reaches a shader.
///
/// Uploads everything when the probes' version moved (a few hundred kB for a level's probes;
/// it moves while probes gather, a few frames after a change). Without probes it holds
/// nothing.
class IrradianceProbeTextures {
  public:
    /// Texture unit of the distance atlas and storage block of the probe records.
    static constexpr GLuint kDepthUnit = 18;
    static constexpr GLuint kIrradianceUnit = 19;
    static constexpr GLuint kProbeBlock = 2;

    /// Follows `probes` (null: the plan has none, everything is freed).
    void sync(const IrradianceProbes* probes);
    [[nodiscard]] bool empty() const { return count_ == 0; }
    /// Binds the buffer and the atlas and sets the grid's uniforms on `program` (in use).
    void bind(const gl::Program& program) const;
    [[nodiscard]] std::uint64_t uploads() const { return uploads_; }

  private:
    gl::Buffer records_;
    gl::Texture depth_;
    gl::Texture irradiance_;  ///< empty with ProbeBasis::Sh2
    ProbeBasis basis_ = ProbeBasis::Octahedral;
    ProbeGrid grid_;
    std::size_t count_ = 0;
    int tiles_per_row_ = 1;
    const IrradianceProbes* source_ = nullptr;
    std::uint64_t version_ = 0;
    std::uint64_t uploads_ = 0;
};

}  // namespace luxel::lighting
