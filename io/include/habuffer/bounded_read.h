/// @file
/// Whole input files read into memory within bounds: the one reader of the
/// binary loaders (spatial hash tables, voxel grids). Only a regular file or
/// a pipe is read; a regular file's size is checked against the format's
/// largest and the machine's memory before anything is allocated, and a pipe
/// is stopped at the limit, so a device (/dev/zero), a directory or a huge
/// file is one clear error instead of "out of memory" or
/// "basic_filebuf::underflow".
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace habuffer {

/// The bytes of `path`, a regular file or a pipe (a FIFO, /dev/stdin), read
/// whole. Throws DataError naming the path, and `what` ("spatial hash
/// table", "voxel grid") where it says what the file should be, for: a
/// missing or unreadable file; a directory; a device or socket (never read:
/// /dev/zero would not end); a regular file of more than `max_bytes` or
/// more than this machine's memory (refused from its size, nothing read);
/// a pipe that gives more than `max_bytes` or half the machine's memory
/// (stopped there); a read error.
std::string read_file_bounded(const std::string& path, std::string_view what, std::uint64_t max_bytes);

}  // namespace habuffer
