#include "gpu_meshes.h"

#include <epoxy/gl.h>

#include <glm/gtc/type_ptr.hpp>

#include "habuffer/gl/gl_buffer.h"

namespace habuffer::view {

GpuMeshes::GpuMeshes(const Scene& scene) {
  for (const habuffer::Mesh& m : scene.meshes) {
    Mesh g{0, 0, 0, static_cast<std::int32_t>(m.indices.size()), m.colour, m.opacity, m.opaque()};
    g.vertices = gl::create_buffer(m.positions.size() * sizeof(glm::vec3), m.positions.data());
    g.indices = gl::create_buffer(m.indices.size() * sizeof(std::uint32_t), m.indices.data());
    glCreateVertexArrays(1, &g.vertex_array);
    glVertexArrayVertexBuffer(g.vertex_array, 0, g.vertices, 0, sizeof(glm::vec3));
    glVertexArrayElementBuffer(g.vertex_array, g.indices);
    glEnableVertexArrayAttrib(g.vertex_array, 0);
    glVertexArrayAttribFormat(g.vertex_array, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(g.vertex_array, 0, 0);
    meshes_.push_back(g);
  }
}

GpuMeshes::~GpuMeshes() {
  for (Mesh& g : meshes_) {
    glDeleteVertexArrays(1, &g.vertex_array);
    gl::delete_buffer(g.vertices);
    gl::delete_buffer(g.indices);
  }
}

void GpuMeshes::draw(const gl::ShaderProgram& program, const Camera& camera, bool opaque) const {
  const GLuint id = program.id();
  glUseProgram(id);
  glProgramUniformMatrix4fv(id, glGetUniformLocation(id, "r_view"), 1, GL_FALSE, glm::value_ptr(camera.view));
  glProgramUniformMatrix4fv(id, glGetUniformLocation(id, "r_projection"), 1, GL_FALSE, glm::value_ptr(camera.projection));
  program.set("r_near", camera.near_plane);
  program.set("r_far", camera.far_plane);
  for (const Mesh& g : meshes_) {
    if (g.opaque != opaque) continue;
    program.set("r_colour", g.colour.x, g.colour.y, g.colour.z);
    program.set("r_opacity", g.opacity);
    glBindVertexArray(g.vertex_array);
    glDrawElements(GL_TRIANGLES, g.count, GL_UNSIGNED_INT, nullptr);
  }
  glBindVertexArray(0);
  glUseProgram(0);
}

}  // namespace habuffer::view
