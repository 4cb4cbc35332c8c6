/// @file
/// What the OpenImageIO files of habuffer::render share (image_files.cpp,
/// heatmap.cpp): one atomic writer, so an interrupted run never leaves a
/// half-written image. Private to the render library.
#pragma once

#include <string>

#include <OpenImageIO/imagebuf.h>

namespace habuffer {

/// Writes `buf` to `path` through an AtomicFile (habuffer/atomic_file.h): the
/// file appears whole or not at all; missing parent directories are created.
/// Throws ImageError naming the file and the reason.
void write_atomically(const std::string& path, const OIIO::ImageBuf& buf);

}  // namespace habuffer
