#include "habuffer/gl/compute_inserter.h"

#include <epoxy/gl.h>

#include <algorithm>

#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/glsl_sources.h"

namespace habuffer::gl {

ComputeInserter::ComputeInserter(GlHaBuffer& buffer)
    : buffer_(buffer),
      program_(ShaderProgram::compute(buffer.module_source(ShaderStage::Compute) + kInsertStreamCompute,
                                      "insert compute shader")) {}

ComputeInserter::~ComputeInserter() {
  if (stream_ != 0) glDeleteBuffers(1, &stream_);
}

void ComputeInserter::upload(std::span<const Fragment> fragments) {
  const Extent screen = buffer_.config().screen;
  for (std::size_t i = 0; i < fragments.size(); ++i)
    if (fragments[i].x >= screen.x || fragments[i].y >= screen.y)
      throw GlError("fragment " + std::to_string(i) + " at (" + std::to_string(fragments[i].x) + ", " +
                    std::to_string(fragments[i].y) + ") lies outside screen " + screen.str());
  if (fragments.size() > UINT32_MAX) throw GlError("the compute entry takes at most 2^32 - 1 fragments per stream");
  if (stream_ != 0) glDeleteBuffers(1, &stream_);
  glCreateBuffers(1, &stream_);
  glNamedBufferData(stream_, static_cast<GLsizeiptr>(std::max<std::size_t>(fragments.size_bytes(), 16)),
                    fragments.data(), GL_STATIC_DRAW);
  count_ = fragments.size();
}

void ComputeInserter::dispatch() const {
  glUseProgram(program_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, buffer_.bindings().stream, stream_);
  program_.set("ha_stream_count", static_cast<unsigned>(count_));
  const auto groups = static_cast<GLuint>(std::clamp<std::size_t>((count_ + 63) / 64, 1, 65535));
  glDispatchCompute(groups, 1, 1);
}

FrameReport ComputeInserter::insert(std::span<const Fragment> fragments) {
  upload(fragments);
  const FrameReport report = buffer_.frame([&] { dispatch(); });
  if (report.counters.fragments != fragments.size())
    throw GlError("the GPU counted " + std::to_string(report.counters.fragments) + " insert calls for " +
                  std::to_string(fragments.size()) + " fragments");
  return report;
}

}  // namespace habuffer::gl
