/// @file
/// Text from files and command lines quoted in error messages: short and
/// printable whatever the input (binary, control bytes, NULs, megabyte lines),
/// so an error message never floods or corrupts a terminal.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace habuffer {

/// At most `max_bytes` bytes of `text`, control and non-ASCII bytes escaped as
/// \xNN (a backslash as \\), and, when cut, "..." and the full length:
/// abc... (1048577 bytes). Printable short text comes back unchanged.
std::string printable(std::string_view text, std::size_t max_bytes = 200);

/// printable() of a field or line between single quotes, 40 bytes by default.
std::string excerpt(std::string_view text, std::size_t max_bytes = 40);

}  // namespace habuffer
