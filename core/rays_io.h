#pragma once
// The CLI's file formats (docs/hits.md): rays in, hits out.
#include <atomic>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "geometry.h"
#include "result.h"

namespace accel {

/// Parses one rays-file number: decimal, C99 hex-float ("0x1.8p+3", signed), inf/-inf.
bool parse_ray_number(std::string_view token, float* out);

/// The content lines of a text format (rays, 2D scenes) one at a time, split into tokens at
/// whitespace; blank lines and lines whose first token starts with '#' are skipped.
class TokenLines {
 public:
  TokenLines(const std::string& text, std::string source_name);
  /// Moves to the next content line; false at the end of the text.
  bool next();
  const std::vector<std::string_view>& tokens() const { return tokens_; }
  /// "SOURCE:LINE: what", for the current line.
  Error error(const std::string& what) const;

 private:
  std::istringstream in_;
  std::string source_name_, line_;
  size_t line_no_ = 0;
  std::vector<std::string_view> tokens_;
};

/// The whole text file at `path`, read to its end (a FIFO until its writer closes it).
/// Errors name the path: "PATH: cannot open WHAT for reading" (also for a directory), a
/// read error.
Result<std::string> read_text_file(const std::string& path, const std::string& what);

/// Reads a rays file: `ox oy oz dx dy dz [tmin tmax]` per line, '#' comments and blank lines
/// skipped. Errors name the file and line: wrong field count, malformed or non-finite number,
/// zero direction, NaN interval bounds.
Result<std::vector<Ray>> read_rays(const std::string& path);
/// Same, from text already in memory (`source_name` is used in messages).
Result<std::vector<Ray>> parse_rays(const std::string& text, const std::string& source_name);

/// `v` as a C99 hex float ("0x1.8p+1"), or "inf" / "-inf": what parse_ray_number reads back
/// exactly.
std::string format_ray_number(float v);
/// `ox oy oz dx dy dz` (and ` tmin tmax` with `interval`) in format_ray_number's form: a rays-file
/// line that reads back as exactly `ray` (print-ray, the viewer's state files, check's replays).
std::string format_ray_line(const Ray& ray, bool interval = true);

/// Formats one hit row `ray,prim,t,u,v` (t with %.9g, "inf" on a miss).
std::string format_hit_row(size_t ray_index, const Hit& hit);

/// Writes the hits CSV atomically (write_file_atomic). Error names the path.
Status write_hits_csv(const std::string& path, const std::vector<Hit>& hits,
                      const std::atomic<bool>* cancel = nullptr);

/// Writes `content` to `path` atomically: to a temporary file beside it, renamed over it on
/// success, so a failure (a full disk, `*cancel` set while writing) never leaves a partial
/// file or the temporary one. A symbolic link is followed and stays a link. An existing
/// device, FIFO or socket, and any existing path under /dev/ or /proc/ (/dev/full,
/// /dev/stdout), is written directly (appending): there is no file to replace there. Errors name `path` and the system's reason ("...: write failed: No space left on
/// device"); a cancelled write says "not written (interrupted)".
Status write_file_atomic(const std::string& path, const std::string& content,
                         const std::atomic<bool>* cancel = nullptr);

/// Whether write_file_atomic(path, ...) can create its file there: the same checks, and a
/// temporary file created and removed beside the target, so a command can fail before its
/// work instead of after it. A full disk only shows in the write itself.
Status check_writable(const std::string& path);

}  // namespace accel
