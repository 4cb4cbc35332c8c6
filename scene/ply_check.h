/// @file
/// Checks what a PLY file's header promises against what the file holds,
/// before assimp reads it: assimp trusts the header, so a truncated file
/// (a header promising 1000 vertices over 3) aborts the process inside one
/// of its assertions, and a 136-byte file claiming 4e9 vertices allocates
/// tens of gigabytes. Refused here with the element and the sizes instead.
/// Private to the scene library (mesh_loader.cpp, the fuzz target).
#pragma once

#include <istream>
#include <string>

namespace habuffer {

/// Whether `path` starts with the PLY magic line.
bool is_ply_file(const std::string& path);

/// Throws SceneError naming the file, the element and the sizes when the
/// header is malformed, or when the data after it cannot hold the elements it
/// declares: binary, fewer bytes than the rows need at the least (lists
/// empty); ASCII, fewer non-empty lines than rows.
void check_ply_file(const std::string& path);
/// The same over a stream (positioned at the file's start) named `path` in
/// messages: tests and the fuzz target.
void check_ply_stream(std::istream& in, const std::string& path);

}  // namespace habuffer
