#include "gpu_triangles.h"

#include <epoxy/gl.h>

#include <utility>

namespace habuffer {

GpuTriangles::GpuTriangles(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices)
    : vertices_(positions.size() * sizeof(glm::vec3), positions.data()),
      elements_(indices.size() * 4, indices.data()),
      count_(static_cast<std::int32_t>(indices.size())) {
  glCreateVertexArrays(1, &array_);
  glVertexArrayVertexBuffer(array_, 0, vertices_.id(), 0, sizeof(glm::vec3));
  glVertexArrayElementBuffer(array_, elements_.id());
  glEnableVertexArrayAttrib(array_, 0);
  glVertexArrayAttribFormat(array_, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(array_, 0, 0);
}

GpuTriangles::~GpuTriangles() { glDeleteVertexArrays(1, &array_); }  // 0 (moved from) is ignored

GpuTriangles::GpuTriangles(GpuTriangles&& o) noexcept
    : vertices_(std::move(o.vertices_)), elements_(std::move(o.elements_)), array_(o.array_), count_(o.count_) {
  o.array_ = 0;
}

void GpuTriangles::draw() const {
  glBindVertexArray(array_);
  glDrawElements(GL_TRIANGLES, count_, GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
}

std::uint64_t count_samples(const std::function<void()>& draw) {
  GLuint query = 0;
  glCreateQueries(GL_SAMPLES_PASSED, 1, &query);
  glBeginQuery(GL_SAMPLES_PASSED, query);
  draw();
  glEndQuery(GL_SAMPLES_PASSED);
  GLuint64 samples = 0;
  glGetQueryObjectui64v(query, GL_QUERY_RESULT, &samples);
  glDeleteQueries(1, &query);
  return samples;
}

}  // namespace habuffer
