/// @file
/// Text from files and command lines quoted in error messages: short and
/// printable whatever the input (binary, control bytes, NULs, megabyte lines),
/// so an error message never floods or corrupts a terminal.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace habuffer {

/// At most `max_bytes` bytes of `text`, control and non-ASCII bytes escaped as
/// \xNN (a backslash as \\), and, when cut, "..." and the full length:
/// abc... (1048577 bytes). Printable short text comes back unchanged.
std::string printable(std::string_view text, std::size_t max_bytes = 200);

/// printable() of a field or line between single quotes, 40 bytes by default.
std::string excerpt(std::string_view text, std::size_t max_bytes = 40);

/// An error message as one short line for a terminal: runs of whitespace
/// (newlines, tabs, padding) become one space, the ends are trimmed, a line
/// with any other control byte is printable() whole, and a line beyond
/// `max_bytes` is cut ("... (N bytes)"). Quotes made by excerpt() stay as
/// they are. What the CLI and the viewer print for any exception.
std::string error_line(std::string_view what, std::size_t max_bytes = 600);

/// A std::filesystem error with its paths as excerpts (80 bytes each): the
/// operation and the system's reason, then the paths, never a 300-byte name
/// quoted whole: "cannot create directories: File name too long ('a/aaa...'
/// (312 bytes))".
std::string filesystem_message(const std::filesystem::filesystem_error& e);

}  // namespace habuffer
