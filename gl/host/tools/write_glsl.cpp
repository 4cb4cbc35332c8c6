// Writes the GLSL files a host's file-based shader pipeline includes
// (habuffer::gl::host_glsl_files) under the directory given, for install.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>

#include "habuffer/gl/host_glsl_files.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: habuffer_write_glsl OUTPUT_DIR\n");
    return 2;
  }
  try {
    const std::filesystem::path root = argv[1];
    for (const habuffer::gl::GlslFile& f : habuffer::gl::host_glsl_files()) {
      const std::filesystem::path path = root / f.path;
      std::filesystem::create_directories(path.parent_path());
      std::ofstream out(path, std::ios::binary);
      out << f.text;
      if (!out) throw std::runtime_error("cannot write " + path.string());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "habuffer_write_glsl: %s\n", e.what());
    return 1;
  }
  return 0;
}
