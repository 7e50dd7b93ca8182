#pragma once
// The CLI's file formats (docs/hits.md): rays in, hits out.
#include <string>
#include <vector>

#include "geometry.h"
#include "result.h"

namespace accel {

/// Parses one rays-file number: decimal, C99 hex-float ("0x1.8p+3", signed), inf/-inf.
bool parse_ray_number(std::string_view token, float* out);

/// Reads a rays file: `ox oy oz dx dy dz [tmin tmax]` per line, '#' comments and blank lines
/// skipped. Errors name the file and line: wrong field count, malformed or non-finite number,
/// zero direction, NaN interval bounds.
Result<std::vector<Ray>> read_rays(const std::string& path);
/// Same, from text already in memory (`source_name` is used in messages).
Result<std::vector<Ray>> parse_rays(const std::string& text, const std::string& source_name);

/// Formats one hit row `ray,prim,t,u,v` (t with %.9g, "inf" on a miss).
std::string format_hit_row(size_t ray_index, const Hit& hit);

/// Writes the hits CSV atomically: to a temporary file beside `path`, renamed on success,
/// so a failure never leaves a half-written file. Error names the path.
Status write_hits_csv(const std::string& path, const std::vector<Hit>& hits);

/// Writes `content` to `path` atomically (temporary file + rename).
Status write_file_atomic(const std::string& path, const std::string& content);

}  // namespace accel
