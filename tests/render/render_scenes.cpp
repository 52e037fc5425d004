#include "render_scenes.hpp"

#include <algorithm>

#include <stb_image_write.h>

#include "luxel/ecs/transform.hpp"
#include "luxel/scene/components.hpp"
#include "luxel/scene/gltf.hpp"
#include "test_paths.hpp"

namespace luxel::test {
namespace {

void append_bytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), bytes, bytes + size);
}

}  // namespace

std::vector<std::uint8_t> encode_png(int width, int height, const std::vector<std::uint8_t>& rgba) {
    std::vector<std::uint8_t> out;
    if (stbi_write_png_to_func(append_bytes, &out, width, height, 4, rgba.data(), width * 4) == 0) {
        out.clear();  // decoding it then fails with an error naming the image
    }
    return out;
}

std::unique_ptr<GlContext> make_render_context() {
    GlContextOptions options;
    options.backend = GlBackend::Egl;
    options.width = 16;
    options.height = 16;
    return create_gl_context(options);
}

scene::Primitive horizontal_square(const glm::vec3& centre, float half, bool facing_up) {
    scene::Primitive p;
    const float s = facing_up ? 1.0f : -1.0f;
    p.positions = {centre + glm::vec3(-half, 0.0f, -half), centre + glm::vec3(half, 0.0f, -half),
                   centre + glm::vec3(half, 0.0f, half), centre + glm::vec3(-half, 0.0f, half)};
    p.normals.assign(4, glm::vec3(0.0f, s, 0.0f));
    p.texcoords0 = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    p.texcoords1 = p.texcoords0;
    // Counter-clockwise seen from the side the normal points to.
    p.indices = facing_up ? std::vector<std::uint32_t>{0, 2, 1, 0, 3, 2}
                          : std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3};
    p.material = 0;
    return p;
}

std::shared_ptr<scene::Scene> single_mesh_scene(scene::Primitive primitive, const glm::vec3& albedo,
                                                bool textured) {
    auto result = std::make_shared<scene::Scene>();
    scene::Material material;
    material.base_color = glm::vec4(albedo, 1.0f);
    material.metallic = 0.0f;
    if (textured) {
        // A real 1x1 white PNG: the renderer and the photon tracer decode it, and white
        // leaves the factor as the albedo.
        result->images.push_back({"white", "image/png", encode_png(1, 1, {255, 255, 255, 255})});
        material.base_color_image = 0;
    }
    result->materials.push_back(material);
    result->meshes.push_back({"mesh", {std::move(primitive)}});
    return result;
}

scene::LightmapLayout whole_page_layout(int page_size, double area) {
    scene::LightmapLayout layout;
    layout.page_size = page_size;
    layout.texel_size = 0.1f;
    scene::LightmapSurface surface;
    surface.id = 0;
    surface.primitive = 0;
    surface.page = 0;
    surface.rect = {0, 0, page_size, page_size};
    surface.charts = {surface.rect};
    surface.area = area;
    surface.texels = static_cast<std::int64_t>(page_size) * page_size;
    layout.surfaces.push_back(surface);
    return layout;
}

lighting::LightingConfig small_lighting_config() {
    lighting::LightingConfig config;
    config.photons.selective.groups = 16;
    config.photons.selective.per_group = 8;
    config.photons.caustics.photons_per_pair = 2000;
    config.photons.caustics.slices = 4;
    config.gather.rays_per_texel = 8;
    config.texels_per_gather_unit = 4096;
    return config;
}

ecs::Entity RenderWorld::add_mesh(std::shared_ptr<const scene::Scene> scene,
                                  const glm::vec3& position) {
    const ecs::Entity entity = registry.create();
    registry.emplace<scene::MeshInstance>(entity, std::move(scene), 0);
    registry.emplace<ecs::Transform>(entity, position);
    return entity;
}

void RenderWorld::load_level(const std::string& name, const std::optional<scene::SkySpec>& sky) {
    world::InstantiateOptions options;
    options.sky = sky;
    world::instantiate(
        registry, std::make_shared<scene::Scene>(scene::load_gltf(prepared_level(name))), options);
}

ecs::Entity RenderWorld::add_point_light(const glm::vec3& position, const glm::vec3& power) {
    const ecs::Entity entity = registry.create();
    registry.emplace<lighting::PointLight>(entity, power, 0.0f, true);
    registry.emplace<ecs::Transform>(entity, position);
    return entity;
}

void RenderWorld::start(const lighting::LightingConfig& config) {
    transforms.update();
    if (!lighting) {
        lighting = std::make_unique<lighting::LightingSystem>(registry, jobs, config);
    }
}

void RenderWorld::update(double budget_ms, double dt) {
    time += dt;
    transforms.update();
    lighting->update(budget_ms, time);
}

std::filesystem::path prepared_level(const std::string& name) {
    return luxel::testing::source_dir() / "assets" / "levels" / "prepared" / (name + ".glb");
}

std::vector<std::string> prepared_levels() {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(
             luxel::testing::source_dir() / "assets" / "levels" / "prepared")) {
        if (entry.path().extension() == ".glb") {
            names.push_back(entry.path().stem().string());
        }
    }
    std::sort(names.begin(), names.end());
    return names;
}

renderer::FrameCamera level_camera(ecs::Registry& registry, float aspect) {
    for (auto [entity, camera] : registry.view<scene::CameraComponent>()) {
        const auto* world = registry.try_get<ecs::WorldTransform>(entity);
        return renderer::FrameCamera::from_scene(camera.camera,
                                                 world ? world->matrix : glm::mat4(1.0f), aspect);
    }
    return renderer::FrameCamera::look_at({0.0f, 1.0f, 4.0f}, {0.0f, 1.0f, 0.0f},
                                          {0.0f, 1.0f, 0.0f}, 0.9f, aspect);
}

std::vector<glm::vec4> read_texture(GLuint texture, int width, int height) {
    std::vector<glm::vec4> texels(static_cast<std::size_t>(width) *
                                  static_cast<std::size_t>(height));
    glFinish();  // see FrameRenderer::read: llvmpipe may otherwise return stale contents
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT,
                      static_cast<GLsizei>(texels.size() * sizeof(glm::vec4)), texels.data());
    gl::check_error("read_texture");
    return texels;
}

}  // namespace luxel::test
