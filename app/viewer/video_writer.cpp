#include "video_writer.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <vector>

// The web page has giflib (compiled from Debian's source package) but not FFmpeg
// (ACCEL_WITH_MP4=0): an MP4 is then refused in one line, and frames are resized with
// stb_image_resize (stb's, as the native viewer's screenshots are written with stb).
#ifndef ACCEL_WITH_MP4
#define ACCEL_WITH_MP4 1
#endif
#include <gif_lib.h>

#if ACCEL_WITH_MP4
extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}
#else
#define STB_IMAGE_RESIZE_IMPLEMENTATION
#define STBIR_DEFAULT_FILTER_DOWNSAMPLE STBIR_FILTER_BOX  // an area filter, as swscale's SWS_AREA
#include <stb/stb_image_resize.h>
#endif

namespace viz {
namespace {

std::string extension_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

void remove_quietly(const std::string& path) {
  std::error_code ec;
  std::filesystem::remove(path, ec);
}

accel::Status move_into_place(const std::string& from, const std::string& to) {
  std::error_code ec;
  std::filesystem::rename(from, to, ec);
  if (ec) {
    remove_quietly(from);
    return accel::make_error(to + ": cannot write the file (" + ec.message() + ")");
  }
  return {};
}

// ---------------------------------------------------------------------------------------
// GIF: one image per frame with its own 256-colour palette (GifQuantizeBuffer, median cut),
// the frame delay in a graphics control block, looping forever (NETSCAPE2.0).

class GifWriter final : public VideoWriter {
 public:
  GifWriter(std::string path, int w, int h, int fps) : VideoWriter(std::move(path), w, h, fps) {}
  ~GifWriter() override { abandon(); }

  accel::Status start() {
    int error = 0;
    gif_ = EGifOpenFileName(part_path().c_str(), false, &error);
    if (!gif_) return fail("cannot create the file (" + std::string(GifErrorString(error)) + ")");
    EGifSetGifVersion(gif_, true);  // GIF89a: delays and looping
    if (EGifPutScreenDesc(gif_, width_, height_, 8, 0, nullptr) == GIF_ERROR) return fail_gif();
    // Loop forever: the NETSCAPE2.0 application extension, sub-block {1, count lo, count hi}.
    const unsigned char app[] = "NETSCAPE2.0";
    const unsigned char loop[] = {1, 0, 0};
    if (EGifPutExtensionLeader(gif_, APPLICATION_EXT_FUNC_CODE) == GIF_ERROR ||
        EGifPutExtensionBlock(gif_, 11, app) == GIF_ERROR || EGifPutExtensionBlock(gif_, 3, loop) == GIF_ERROR ||
        EGifPutExtensionTrailer(gif_) == GIF_ERROR)
      return fail_gif();
    return {};
  }

  accel::Status add_frame(const uint8_t* rgba, size_t stride) override {
    if (!gif_) return accel::make_error(path_ + ": the recording has ended");
    const size_t n = static_cast<size_t>(width_) * static_cast<size_t>(height_);
    std::vector<GifByteType> r(n), g(n), b(n), index(n);
    for (int y = 0; y < height_; ++y) {
      const uint8_t* row = rgba + static_cast<size_t>(y) * stride;
      for (int x = 0; x < width_; ++x) {
        const size_t i = static_cast<size_t>(y) * static_cast<size_t>(width_) + static_cast<size_t>(x);
        r[i] = row[4 * x];
        g[i] = row[4 * x + 1];
        b[i] = row[4 * x + 2];
      }
    }
    int colours = 256;
    std::vector<GifColorType> palette(256);
    if (GifQuantizeBuffer(static_cast<unsigned>(width_), static_cast<unsigned>(height_), &colours, r.data(), g.data(),
                          b.data(), index.data(), palette.data()) == GIF_ERROR)
      return fail("cannot quantize frame " + std::to_string(frames_));
    ColorMapObject* map = GifMakeMapObject(256, palette.data());
    if (!map) return fail("out of memory");
    // Delays are in hundredths of a second: 1/fps rounded, at least 2 (viewers clamp less).
    GraphicsControlBlock gcb{};
    gcb.DisposalMode = DISPOSE_DO_NOT;
    gcb.DelayTime = std::max(2, (100 + fps_ / 2) / fps_);
    gcb.TransparentColor = NO_TRANSPARENT_COLOR;
    GifByteType ext[4];
    const size_t ext_len = EGifGCBToExtension(&gcb, ext);
    bool ok = EGifPutExtension(gif_, GRAPHICS_EXT_FUNC_CODE, static_cast<int>(ext_len), ext) != GIF_ERROR &&
              EGifPutImageDesc(gif_, 0, 0, width_, height_, false, map) != GIF_ERROR;
    GifFreeMapObject(map);
    for (int y = 0; ok && y < height_; ++y)
      ok = EGifPutLine(gif_, index.data() + static_cast<size_t>(y) * static_cast<size_t>(width_), width_) != GIF_ERROR;
    if (!ok) return fail_gif();
    ++frames_;
    return {};
  }

  accel::Status finish() override {
    if (!gif_) return accel::make_error(path_ + ": the recording has ended");
    int error = 0;
    const int closed = EGifCloseFile(gif_, &error);
    gif_ = nullptr;
    if (closed == GIF_ERROR) return fail("cannot finish the file (" + std::string(GifErrorString(error)) + ")");
    // giflib creates its file readable by the owner only; a slide's GIF is for sharing.
    std::error_code ec;
    std::filesystem::permissions(part_path(),
                                 std::filesystem::perms::owner_read | std::filesystem::perms::owner_write |
                                     std::filesystem::perms::group_read | std::filesystem::perms::others_read,
                                 ec);
    return move_into_place(part_path(), path_);
  }

 private:
  accel::Status fail(const std::string& what) {
    abandon();
    return accel::make_error(path_ + ": " + what);
  }
  accel::Status fail_gif() { return fail(std::string("GIF error: ") + GifErrorString(gif_ ? gif_->Error : 0)); }
  void abandon() {
    if (gif_) {
      int error = 0;
      EGifCloseFile(gif_, &error);
      gif_ = nullptr;
      remove_quietly(part_path());
    }
  }
  GifFileType* gif_ = nullptr;
};

#if ACCEL_WITH_MP4
// ---------------------------------------------------------------------------------------
// MP4: H.264 (libx264 through libavcodec), YUV 4:2:0, one frame per 1/fps.

std::string av_message(int code) {
  char buf[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, buf, sizeof buf);
  return buf;
}

class Mp4Writer final : public VideoWriter {
 public:
  // YUV 4:2:0 needs even sides: an odd last row or column is dropped.
  Mp4Writer(std::string path, int w, int h, int fps) : VideoWriter(std::move(path), w, h, fps) {}
  ~Mp4Writer() override { abandon(); }

  accel::Status start() {
    av_log_set_level(AV_LOG_ERROR);  // x264's statistics are not the viewer's business
    const int ew = width_ & ~1, eh = height_ & ~1;
    if (ew < 2 || eh < 2) return accel::make_error(path_ + ": an MP4 needs frames of at least 2x2 pixels");
    int rc = avformat_alloc_output_context2(&format_, nullptr, "mp4", part_path().c_str());
    if (rc < 0 || !format_) return fail("cannot set up the MP4 container (" + av_message(rc) + ")");
    const AVCodec* codec = avcodec_find_encoder(AV_CODEC_ID_H264);
    if (!codec) return fail("no H.264 encoder in this FFmpeg (libavcodec without libx264)");
    stream_ = avformat_new_stream(format_, nullptr);
    codec_ = avcodec_alloc_context3(codec);
    if (!stream_ || !codec_) return fail("out of memory");
    codec_->width = ew;
    codec_->height = eh;
    codec_->time_base = AVRational{1, fps_};
    codec_->framerate = AVRational{fps_, 1};
    codec_->pix_fmt = AV_PIX_FMT_YUV420P;
    codec_->gop_size = 2 * fps_;
    codec_->max_b_frames = 0;  // slides step frame by frame: no reordering delay
    if (format_->oformat->flags & AVFMT_GLOBALHEADER) codec_->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    // Crisp lines on slides: a quality-based rate (CRF 18) rather than a bit rate.
    av_opt_set(codec_->priv_data, "preset", "medium", 0);
    av_opt_set(codec_->priv_data, "crf", "18", 0);
    if ((rc = avcodec_open2(codec_, codec, nullptr)) < 0) return fail("cannot open the H.264 encoder (" + av_message(rc) + ")");
    if ((rc = avcodec_parameters_from_context(stream_->codecpar, codec_)) < 0) return fail(av_message(rc));
    stream_->time_base = codec_->time_base;
    if ((rc = avio_open(&format_->pb, part_path().c_str(), AVIO_FLAG_WRITE)) < 0)
      return fail("cannot create the file (" + av_message(rc) + ")");
    if ((rc = avformat_write_header(format_, nullptr)) < 0) return fail("cannot write the MP4 header (" + av_message(rc) + ")");
    frame_ = av_frame_alloc();
    packet_ = av_packet_alloc();
    if (!frame_ || !packet_) return fail("out of memory");
    frame_->format = codec_->pix_fmt;
    frame_->width = ew;
    frame_->height = eh;
    if ((rc = av_frame_get_buffer(frame_, 0)) < 0) return fail(av_message(rc));
    scaler_ = sws_getContext(ew, eh, AV_PIX_FMT_RGBA, ew, eh, AV_PIX_FMT_YUV420P, SWS_BICUBIC, nullptr, nullptr, nullptr);
    if (!scaler_) return fail("cannot set up the RGB -> YUV conversion");
    return {};
  }

  accel::Status add_frame(const uint8_t* rgba, size_t stride) override {
    if (!format_) return accel::make_error(path_ + ": the recording has ended");
    int rc = av_frame_make_writable(frame_);
    if (rc < 0) return fail(av_message(rc));
    const uint8_t* src[1] = {rgba};
    const int src_stride[1] = {static_cast<int>(stride)};
    sws_scale(scaler_, src, src_stride, 0, frame_->height, frame_->data, frame_->linesize);
    frame_->pts = static_cast<int64_t>(frames_);
    if (auto st = encode(frame_); !st) return st;
    ++frames_;
    return {};
  }

  accel::Status finish() override {
    if (!format_) return accel::make_error(path_ + ": the recording has ended");
    if (auto st = encode(nullptr); !st) return st;  // flush the delayed (B-) frames
    const int rc = av_write_trailer(format_);
    close();
    if (rc < 0) {
      remove_quietly(part_path());
      return accel::make_error(path_ + ": cannot finish the MP4 (" + av_message(rc) + ")");
    }
    return move_into_place(part_path(), path_);
  }

 private:
  accel::Status encode(AVFrame* frame) {
    int rc = avcodec_send_frame(codec_, frame);
    if (rc < 0) return fail("cannot encode frame " + std::to_string(frames_) + " (" + av_message(rc) + ")");
    while ((rc = avcodec_receive_packet(codec_, packet_)) >= 0) {
      // Each frame lasts one tick of 1/fps: without a duration the MP4's edit list would end
      // at the last frame's start and players would drop that frame.
      if (packet_->duration <= 0) packet_->duration = 1;
      av_packet_rescale_ts(packet_, codec_->time_base, stream_->time_base);
      packet_->stream_index = stream_->index;
      rc = av_interleaved_write_frame(format_, packet_);
      av_packet_unref(packet_);
      if (rc < 0) return fail("cannot write (" + av_message(rc) + ")");
    }
    if (rc != AVERROR(EAGAIN) && rc != AVERROR_EOF) return fail("encoder error (" + av_message(rc) + ")");
    return {};
  }
  accel::Status fail(const std::string& what) {
    abandon();
    return accel::make_error(path_ + ": " + what);
  }
  void close() {
    sws_freeContext(scaler_);
    scaler_ = nullptr;
    av_packet_free(&packet_);
    av_frame_free(&frame_);
    avcodec_free_context(&codec_);
    if (format_) {
      if (format_->pb) avio_closep(&format_->pb);
      avformat_free_context(format_);
      format_ = nullptr;
    }
  }
  void abandon() {
    if (!format_) return;
    close();
    remove_quietly(part_path());
  }
  AVFormatContext* format_ = nullptr;
  AVStream* stream_ = nullptr;
  AVCodecContext* codec_ = nullptr;
  AVFrame* frame_ = nullptr;
  AVPacket* packet_ = nullptr;
  SwsContext* scaler_ = nullptr;
};

#endif  // ACCEL_WITH_MP4

}  // namespace

std::vector<uint8_t> resize_rgba(const std::vector<uint8_t>& src, int w, int h, int out_w, int out_h) {
  std::vector<uint8_t> out(static_cast<size_t>(out_w) * static_cast<size_t>(out_h) * 4);
#if ACCEL_WITH_MP4
  SwsContext* ctx = sws_getContext(w, h, AV_PIX_FMT_RGBA, out_w, out_h, AV_PIX_FMT_RGBA, SWS_AREA, nullptr, nullptr, nullptr);
  if (!ctx) return {};
  const uint8_t* in_planes[1] = {src.data()};
  const int in_stride[1] = {w * 4};
  uint8_t* out_planes[1] = {out.data()};
  const int out_stride[1] = {out_w * 4};
  sws_scale(ctx, in_planes, in_stride, 0, h, out_planes, out_stride);
  sws_freeContext(ctx);
#else
  if (!stbir_resize_uint8(src.data(), w, h, w * 4, out.data(), out_w, out_h, out_w * 4, 4)) return {};
#endif
  return out;
}

accel::Result<VideoFormat> video_format_of(const std::string& path) {
  const std::string ext = extension_of(path);
  if (ext == ".gif") return VideoFormat::Gif;
  if (ext == ".mp4") return VideoFormat::Mp4;
  return accel::make_error(path + ": unknown recording format '" + ext + "' (valid: .gif, .mp4)");
}

accel::Result<std::unique_ptr<VideoWriter>> VideoWriter::open(const std::string& path, int width, int height,
                                                              int fps) {
  auto format = video_format_of(path);
  if (!format) return format.error();
  if (width < 1 || height < 1 || width > kMaxSide || height > kMaxSide)
    return accel::make_error(path + ": frame size " + std::to_string(width) + "x" + std::to_string(height) +
                             " is out of range (1.." + std::to_string(kMaxSide) + ")");
  if (fps < kMinFps || fps > kMaxFps)
    return accel::make_error(path + ": fps=" + std::to_string(fps) + " is out of range (" + std::to_string(kMinFps) +
                             ".." + std::to_string(kMaxFps) + ")");
  if (format.value() == VideoFormat::Gif) {
    auto w = std::make_unique<GifWriter>(path, width, height, fps);
    if (auto st = w->start(); !st) return st.error();
    return std::unique_ptr<VideoWriter>(std::move(w));
  }
#if ACCEL_WITH_MP4
  auto w = std::make_unique<Mp4Writer>(path, width, height, fps);
  if (auto st = w->start(); !st) return st.error();
  return std::unique_ptr<VideoWriter>(std::move(w));
#else
  return accel::make_error(path + ": MP4 recording needs FFmpeg, which the web page does not have; record a .gif");
#endif
}

}  // namespace viz
