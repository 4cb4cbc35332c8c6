/// @file
/// The interchange files of SPEC 10 and of the CLI: fragment streams, offsets,
/// per-pixel lists, table and max-age dumps: what the CLI reads and writes and
/// what other implementations compare against bit for bit.
#pragma once

#include <span>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "habuffer/csv.h"
#include "habuffer/fragment.h"
#include "habuffer/techniques/ha/ha_buffer.h"
#include "habuffer/offset_sequence.h"

namespace habuffer {

/// Header x,y,depth,rgba. Throws DataError naming file, line and field for
/// bad syntax or a pixel outside `screen`.
std::vector<Fragment> read_fragments(const std::string& path, Extent screen);
/// read_fragments from an open reader (tests, fuzzers; `in`'s name in the errors).
std::vector<Fragment> parse_fragments(CsvReader& in, Extent screen);
/// Writes `fragments` in read_fragments' format, whole or not at all; throws DataError.
void write_fragments(const std::string& path, std::span<const Fragment> fragments);

/// Header ox,oy, one row per age from age 1.
/// Throws DataError naming file, line and field.
std::vector<glm::uvec2> read_offset_rows(const std::string& path);
/// read_offset_rows from an open reader.
std::vector<glm::uvec2> parse_offset_rows(CsvReader& in);
/// read_offset_rows, validated for `table` and `count` ages (OffsetSequence::
/// from_list); errors are DataError naming the file.
OffsetSequence read_offsets(const std::string& path, Extent table, std::uint32_t count);
/// Writes one row per age of `offsets` in read_offset_rows' format; throws DataError.
void write_offsets(const std::string& path, const OffsetSequence& offsets);

/// Header x,y,rank,code,rgba: every pixel's list, pixels row-major. A
/// multisampled buffer adds a last column, coverage (the record's mask), and
/// its code is the depth code alone (the code field shifted right by S).
void write_lists(const std::string& path, const FragmentBuffer& buffer);
/// Header slot,record: non-empty slots ascending, record in 0x hex (16 or 8 digits).
void write_table(const std::string& path, const HaBuffer& buffer);
/// Header cx,cy,max_age: every cell, row-major.
void write_max_age(const std::string& path, const HaBuffer& buffer);

}  // namespace habuffer
