#version 450 core
// Routes each photon's point to its page's layer of the caustic light maps: gl_Layer is set
// here because a vertex shader may not set it in core GL 4.5.

layout(points) in;
layout(points, max_vertices = 1) out;

flat in vec3 v_irradiance[];
flat in int v_layer[];

flat out vec3 g_irradiance;

void main() {
    if (v_layer[0] < 0) {
        return;
    }
    gl_Layer = v_layer[0];
    gl_Position = gl_in[0].gl_Position;
    g_irradiance = v_irradiance[0];
    EmitVertex();
    EndPrimitive();
}
