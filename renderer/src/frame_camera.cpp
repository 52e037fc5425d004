#include "luxel/renderer/frame_camera.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace luxel::renderer {

FrameCamera FrameCamera::look_at(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up,
                                 float yfov, float aspect, float znear, float zfar) {
    FrameCamera camera;
    camera.view = glm::lookAt(eye, target, up);
    camera.projection = glm::perspective(yfov, aspect, znear, zfar);
    camera.position = eye;
    camera.yfov = yfov;
    return camera;
}

FrameCamera FrameCamera::from_scene(const scene::Camera& camera, const glm::mat4& world,
                                    float aspect, float default_far) {
    FrameCamera result;
    // The view matrix is the inverse of the camera's placement (scale removed, so a scaled
    // parent does not distort the view).
    const glm::vec3 position(world[3]);
    const glm::vec3 forward = -glm::normalize(glm::vec3(world[2]));
    const glm::vec3 up = glm::normalize(glm::vec3(world[1]));
    result.view = glm::lookAt(position, position + forward, up);
    result.position = position;
    // The viewport decides the aspect, as game engines do: a glTF camera's aspect ratio that
    // differs from the window's would stretch the frame.
    const float ratio = aspect;
    const float far = camera.zfar.value_or(default_far);
    if (camera.perspective) {
        result.projection = glm::perspective(camera.yfov, ratio, camera.znear, far);
        result.yfov = camera.yfov;
    } else {
        result.projection =
            glm::ortho(-camera.xmag, camera.xmag, -camera.ymag, camera.ymag, camera.znear, far);
        result.yfov = 0.0f;
    }
    return result;
}

}  // namespace luxel::renderer
