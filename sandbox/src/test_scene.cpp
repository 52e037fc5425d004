#include "test_scene.hpp"

#include <array>
#include <cmath>
#include <vector>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace luxel::sandbox {
namespace {

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec3 albedo;
};

/// Appends a quad (two triangles) with corners a, b, c, d in counter-clockwise order seen from
/// the side its normal points to.
void add_quad(std::vector<Vertex>& out, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d,
              glm::vec3 albedo) {
    const glm::vec3 normal = glm::normalize(glm::cross(b - a, c - a));
    for (const glm::vec3& p : {a, b, c, a, c, d}) {
        out.push_back({p, normal, albedo});
    }
}

/// An axis-aligned block standing on the floor, centred at (x, z), with outward normals.
void add_block(std::vector<Vertex>& out, float x, float z, glm::vec3 size, glm::vec3 albedo) {
    const glm::vec3 lo(x - size.x / 2, 0.0f, z - size.z / 2);
    const glm::vec3 hi(x + size.x / 2, size.y, z + size.z / 2);
    add_quad(out, {lo.x, hi.y, lo.z}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, hi.y, lo.z},
             albedo);  // top
    add_quad(out, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z},
             albedo);  // +z
    add_quad(out, {hi.x, lo.y, lo.z}, {lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z},
             albedo);  // -z
    add_quad(out, {hi.x, lo.y, hi.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z},
             albedo);  // +x
    add_quad(out, {lo.x, lo.y, lo.z}, {lo.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {lo.x, hi.y, lo.z},
             albedo);  // -x
}

std::vector<Vertex> build_room() {
    constexpr float h = 2.0f;  // half extent of the 4 m room in x and z
    constexpr float ceiling = 3.0f;
    const glm::vec3 white(0.75f);
    const glm::vec3 red(0.75f, 0.12f, 0.10f);
    const glm::vec3 green(0.12f, 0.60f, 0.15f);
    std::vector<Vertex> v;
    add_quad(v, {-h, 0, -h}, {-h, 0, h}, {h, 0, h}, {h, 0, -h}, white);  // floor
    add_quad(v, {-h, ceiling, -h}, {h, ceiling, -h}, {h, ceiling, h}, {-h, ceiling, h},
             white);                                                                   // ceiling
    add_quad(v, {-h, 0, -h}, {h, 0, -h}, {h, ceiling, -h}, {-h, ceiling, -h}, white);  // back
    add_quad(v, {-h, 0, h}, {-h, 0, -h}, {-h, ceiling, -h}, {-h, ceiling, h}, red);    // left
    add_quad(v, {h, 0, -h}, {h, 0, h}, {h, ceiling, h}, {h, ceiling, -h}, green);      // right
    add_block(v, -0.7f, -0.6f, {1.0f, 1.6f, 1.0f}, white);
    add_block(v, 0.8f, 0.4f, {0.9f, 0.8f, 0.9f}, glm::vec3(0.55f, 0.55f, 0.7f));
    return v;
}

}  // namespace

TestScene::TestScene(const ShaderLibrary& shaders)
    : program_(shaders.build({{ShaderStage::Vertex, "test_scene/lit.vert"},
                              {ShaderStage::Fragment, "test_scene/lit.frag"}})),
      vertex_array_(gl::VertexArray::create()) {
    const std::vector<Vertex> vertices = build_room();
    vertex_count_ = static_cast<int>(vertices.size());
    vertices_ = gl::Buffer::create(vertices.size() * sizeof(Vertex), vertices.data(), 0);
    const GLuint vao = vertex_array_.id();
    glVertexArrayVertexBuffer(vao, 0, vertices_.id(), 0, sizeof(Vertex));
    const std::array<GLuint, 3> offsets = {offsetof(Vertex, position), offsetof(Vertex, normal),
                                           offsetof(Vertex, albedo)};
    for (GLuint attribute = 0; attribute < offsets.size(); ++attribute) {
        glEnableVertexArrayAttrib(vao, attribute);
        glVertexArrayAttribFormat(vao, attribute, 3, GL_FLOAT, GL_FALSE, offsets[attribute]);
        glVertexArrayAttribBinding(vao, attribute, 0);
    }
    // A 60 W isotropic point light: radiant intensity I = P / (4 pi) W/sr.
    constexpr float light_power_watts = 60.0f;
    program_.set("u_light", glm::vec4(0.0f, 2.7f, 0.3f, 1.0f));
    program_.set("u_light_intensity", glm::vec3(light_power_watts / (4.0f * glm::pi<float>())));
    // A dim constant stand-in for indirect light, so unlit faces are not black.
    program_.set("u_ambient_irradiance", glm::vec3(0.25f));
}

void TestScene::render(const gl::RenderTarget& target, double time_seconds) const {
    const float angle = 0.35f * std::sin(static_cast<float>(time_seconds) * 0.5f);
    const glm::vec3 eye(5.2f * std::sin(angle), 1.6f, 5.2f * std::cos(angle));
    const glm::mat4 view = glm::lookAt(eye, glm::vec3(0.0f, 1.2f, 0.0f), glm::vec3(0, 1, 0));
    const float aspect = static_cast<float>(target.width()) / static_cast<float>(target.height());
    const glm::mat4 projection = glm::perspective(glm::radians(55.0f), aspect, 0.05f, 50.0f);
    program_.set("u_view_projection", projection * view);

    target.bind();
    const std::array<float, 4> background = {0.0f, 0.0f, 0.0f, 1.0f};
    const float far_depth = 1.0f;
    glClearNamedFramebufferfv(target.framebuffer().id(), GL_COLOR, 0, background.data());
    glClearNamedFramebufferfv(target.framebuffer().id(), GL_DEPTH, 0, &far_depth);
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_CULL_FACE);
    program_.use();
    glBindVertexArray(vertex_array_.id());
    glDrawArrays(GL_TRIANGLES, 0, vertex_count_);
    glBindVertexArray(0);
}

}  // namespace luxel::sandbox
