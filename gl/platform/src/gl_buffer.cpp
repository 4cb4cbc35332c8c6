#include "habuffer/gl/gl_buffer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <string>
#include <utility>

#include "habuffer/gl/gl_error.h"
#include "pixel_store.h"

namespace habuffer::gl {

unsigned create_buffer(std::uint64_t bytes, const void* data) {
  const std::uint64_t size = std::max<std::uint64_t>((bytes + 3) / 4 * 4, 4);  // whole words, as zero_buffer clears
  GLuint b = 0;
  glCreateBuffers(1, &b);
  // Immutable storage with no client-access flags: the driver keeps it in
  // device memory (with GL_DYNAMIC_DRAW data stores, the NVIDIA driver moved
  // buffers we read back, the HA table among them, to host memory: "Buffer
  // performance warning ... copied/moved from VIDEO memory to HOST memory").
  // Sub-data updates (the parameter block) need GL_DYNAMIC_STORAGE_BIT.
  // The data go in separately: the store may be up to 3 bytes longer than they are.
  glNamedBufferStorage(b, static_cast<GLsizeiptr>(size), nullptr, GL_DYNAMIC_STORAGE_BIT);
  GLint64 got = 0;
  glGetNamedBufferParameteri64v(b, GL_BUFFER_SIZE, &got);
  if (static_cast<std::uint64_t>(got) != size) {
    glDeleteBuffers(1, &b);
    throw GlError("OpenGL could not allocate a buffer of " + std::to_string(size) + " bytes");
  }
  // GL leaves a new store's contents undefined: zeros, so a read-back never
  // sees another allocation's bytes (the NVIDIA driver hands them out; a
  // node pool's unused links read back as links beyond the pool).
  if (data == nullptr || bytes < size) zero_buffer(b);
  if (data != nullptr && bytes > 0) glNamedBufferSubData(b, 0, static_cast<GLsizeiptr>(bytes), data);
  return b;
}

void zero_buffer(unsigned buffer) {
  const NeutralUnpack unpack;  // the clear value is read through the host's unpack state
  const GLuint z = 0;
  glClearNamedBufferData(buffer, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &z);
}

std::vector<std::uint32_t> read_words(unsigned buffer, std::uint64_t words) {
  std::vector<std::uint32_t> out(words);
  if (words > 0) glGetNamedBufferSubData(buffer, 0, static_cast<GLsizeiptr>(words * 4), out.data());
  return out;
}

void delete_buffer(unsigned& buffer) {
  if (buffer != 0) glDeleteBuffers(1, &buffer);
  buffer = 0;
}

GlStorage::GlStorage(std::uint64_t bytes, const void* data)
    : id_(create_buffer(bytes, data)), bytes_(std::max<std::uint64_t>((bytes + 3) / 4 * 4, 4)) {}

GlStorage::~GlStorage() { release(); }

void GlStorage::release() {
  if (id_ != 0 && made_on_.current()) delete_buffer(id_);
  id_ = 0;
}

GlStorage::GlStorage(GlStorage&& other) noexcept
    : id_(std::exchange(other.id_, 0u)), bytes_(std::exchange(other.bytes_, 0)), made_on_(other.made_on_) {}

GlStorage& GlStorage::operator=(GlStorage&& other) noexcept {
  if (this != &other) {
    release();
    id_ = std::exchange(other.id_, 0u);
    bytes_ = std::exchange(other.bytes_, 0);
    made_on_ = other.made_on_;
  }
  return *this;
}

void GlStorage::zero() const {
  if (id_ != 0) zero_buffer(id_);
}

std::vector<std::uint32_t> GlStorage::read_words(std::uint64_t words) const { return gl::read_words(id_, words); }

void GlStorage::read_into(void* out, std::uint64_t bytes) const {
  if (bytes > 0) glGetNamedBufferSubData(id_, 0, static_cast<GLsizeiptr>(bytes), out);
}

void GlStorage::bind_storage(unsigned point) const {
  if (id_ != 0) bind_at(GL_SHADER_STORAGE_BUFFER, point, id_);
}

GlTexture::GlTexture(unsigned format, Extent size, std::uint32_t texel_bytes) : bytes_(size.area() * texel_bytes) {
  glCreateTextures(GL_TEXTURE_2D, 1, &id_);
  glTextureStorage2D(id_, 1, format, static_cast<GLsizei>(size.x), static_cast<GLsizei>(size.y));
}

GlTexture::~GlTexture() { release(); }

void GlTexture::release() {
  if (id_ != 0 && made_on_.current()) glDeleteTextures(1, &id_);
  id_ = 0;
}

GlTexture::GlTexture(GlTexture&& other) noexcept
    : id_(std::exchange(other.id_, 0u)), bytes_(std::exchange(other.bytes_, 0)), made_on_(other.made_on_) {}

GlTexture& GlTexture::operator=(GlTexture&& other) noexcept {
  if (this != &other) {
    release();
    id_ = std::exchange(other.id_, 0u);
    bytes_ = std::exchange(other.bytes_, 0);
    made_on_ = other.made_on_;
  }
  return *this;
}

void bind_at(unsigned target, unsigned point, unsigned buffer) { glBindBuffersBase(target, point, 1, &buffer); }

}  // namespace habuffer::gl
