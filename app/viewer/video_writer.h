#pragma once
// GL-free: writes the frames of a recording (RGBA8, top row first) to an animated GIF
// (giflib, a palette per frame from its median-cut quantizer) or an MP4 with H.264 video
// (FFmpeg's libavformat / libavcodec with libx264, libswscale for RGB -> YUV 4:2:0; not in
// the web page, which records GIFs only). No hand-written encoder. The output appears only
// when finish() succeeds: frames go to "PATH.part", renamed at the end and removed on
// failure or when the writer is dropped, so a failed or abandoned recording never leaves a
// half-written file.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "result.h"

namespace viz {

enum class VideoFormat { Gif, Mp4 };

/// The format of `path` by its extension (.gif, .mp4; case-insensitive), or an error naming
/// the path and the valid extensions.
accel::Result<VideoFormat> video_format_of(const std::string& path);

/// `src` (w x h RGBA) resampled to `out_w` x `out_h` with an area filter (frames shrink
/// well): libswscale's natively, stb_image_resize's box filter in the page; empty when
/// that fails.
std::vector<uint8_t> resize_rgba(const std::vector<uint8_t>& src, int w, int h, int out_w, int out_h);

class VideoWriter {
 public:
  /// Starts a recording of `width` x `height` frames at `fps` frames per second. Errors
  /// name the path (an unknown extension, a size or rate out of range, a file that cannot
  /// be created, an encoder that cannot be opened).
  static accel::Result<std::unique_ptr<VideoWriter>> open(const std::string& path, int width, int height, int fps);
  virtual ~VideoWriter() = default;

  /// Appends one frame: `width` x `height` RGBA8 pixels, rows `stride` bytes apart, the top
  /// row first.
  virtual accel::Status add_frame(const uint8_t* rgba, size_t stride) = 0;
  /// Ends the file and moves it into place. After an error the partial file is removed.
  virtual accel::Status finish() = 0;

  const std::string& path() const { return path_; }
  int width() const { return width_; }
  int height() const { return height_; }
  int fps() const { return fps_; }
  size_t frames() const { return frames_; }

  static constexpr int kMinFps = 1, kMaxFps = 60;
  static constexpr int kMaxSide = 8192;

 protected:
  VideoWriter(std::string path, int width, int height, int fps)
      : path_(std::move(path)), width_(width), height_(height), fps_(fps) {}
  std::string part_path() const { return path_ + ".part"; }
  std::string path_;
  int width_, height_, fps_;
  size_t frames_ = 0;
};

}  // namespace viz
