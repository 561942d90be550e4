// Caps on what a file may declare, checked before anything is allocated. Each has a
// documented default and an environment variable for a user with a genuinely large file
// (README, "Limits on input files"). On the ground floor because the JSON reader of
// util/text.hpp needs them too; in namespace io, beside the readers that enforce the rest.
#pragma once

#include <cstddef>
#include <string>

namespace pathlet::io {

// Largest uncompressed/compressed size ratio a zlib or deflate stream may claim. Deflate
// cannot exceed ~1032:1, so the default refuses only impossible headers (decompression
// bombs, corrupt sizes). PATHLET_MAX_INFLATE_RATIO (>= 1) lowers or raises it.
double max_inflate_ratio();

// Deepest nesting of arrays/objects accepted in a JSON file (graphs, camera paths,
// experiments). Deeper input is refused with its file before it is walked recursively.
// PATHLET_MAX_JSON_DEPTH (>= 8) changes it; default 128.
int max_json_depth();

// Largest JSON input file (graphs, camera paths, experiments, viewer scripts) read into
// memory: PATHLET_MAX_JSON_BYTES (>= 4096) changes it; default 64 MiB. Such files are kilobytes.
size_t max_json_bytes();

// Largest coordinate magnitude a point may have and still be kept (default 1e15 data units):
// a finite outlier beyond it would overflow the bounding box to inf. PATHLET_MAX_COORDINATE.
double max_coordinate();

// Deepest [ / { nesting in JSON text (strings and // /* */ comments skipped), and the byte
// offset where it first exceeds `limit` (or npos). Cheap, iterative: run it before parsing,
// because walking, copying or printing a deeper value recurses and can overflow the stack.
struct JsonDepth {
    int depth = 0;
    size_t first_too_deep = size_t(-1);
};
JsonDepth json_nesting_depth(const std::string& text, int limit);

}  // namespace pathlet::io
