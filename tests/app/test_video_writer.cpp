// The recording writer: a GIF and an MP4 of a few synthetic frames, read back with the same
// libraries (giflib's decoder, libavformat's demuxer): the frame count, size, rate and
// that nothing is left behind on errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

#include <unistd.h>

#include <gif_lib.h>

extern "C" {
#include <libavformat/avformat.h>
}

#include "video_writer.h"

namespace viz {
namespace {

namespace fs = std::filesystem;

fs::path out_dir() {
  const fs::path d = fs::temp_directory_path() / ("accel_video_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

/// A moving square on a gradient: frame k differs from k-1.
std::vector<uint8_t> frame(int w, int h, int k) {
  std::vector<uint8_t> px(static_cast<size_t>(w) * h * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t* p = &px[(static_cast<size_t>(y) * w + x) * 4];
      const bool square = x >= 4 * k && x < 4 * k + 10 && y >= 10 && y < 20;
      p[0] = square ? 255 : uint8_t(x * 3);
      p[1] = square ? 220 : uint8_t(y * 4);
      p[2] = square ? 0 : 90;
      p[3] = 255;
    }
  return px;
}

accel::Status record(const std::string& path, int w, int h, int fps, int n) {
  auto writer = VideoWriter::open(path, w, h, fps);
  if (!writer) return writer.error();
  for (int k = 0; k < n; ++k) {
    const auto px = frame(w, h, k);
    if (auto st = writer.value()->add_frame(px.data(), static_cast<size_t>(w) * 4); !st) return st;
  }
  return writer.value()->finish();
}

TEST(VideoWriter, GifHasOneImagePerFrameAndTheDelay) {
  const std::string path = (out_dir() / "clip.gif").string();
  ASSERT_TRUE(record(path, 64, 40, 10, 5).ok());
  int error = 0;
  GifFileType* gif = DGifOpenFileName(path.c_str(), &error);
  ASSERT_NE(gif, nullptr);
  ASSERT_EQ(DGifSlurp(gif), GIF_OK);
  EXPECT_EQ(gif->SWidth, 64);
  EXPECT_EQ(gif->SHeight, 40);
  EXPECT_EQ(gif->ImageCount, 5);
  GraphicsControlBlock gcb{};
  ASSERT_EQ(DGifSavedExtensionToGCB(gif, 0, &gcb), GIF_OK);
  EXPECT_EQ(gcb.DelayTime, 10);  // hundredths of a second at 10 fps
  DGifCloseFile(gif, &error);
  EXPECT_FALSE(fs::exists(path + ".part"));
}

TEST(VideoWriter, Mp4IsH264WithEveryFrame) {
  const std::string path = (out_dir() / "clip.mp4").string();
  ASSERT_TRUE(record(path, 65, 41, 12, 7).ok()) << "odd sides are cropped to even";
  AVFormatContext* in = nullptr;
  ASSERT_EQ(avformat_open_input(&in, path.c_str(), nullptr, nullptr), 0);
  ASSERT_GE(avformat_find_stream_info(in, nullptr), 0);
  ASSERT_EQ(in->nb_streams, 1u);
  const AVCodecParameters* par = in->streams[0]->codecpar;
  EXPECT_EQ(par->codec_id, AV_CODEC_ID_H264);
  EXPECT_EQ(par->width, 64);
  EXPECT_EQ(par->height, 40);
  // The rate: the frames' timestamps are 1/12 s apart.
  EXPECT_EQ(av_q2d(in->streams[0]->r_frame_rate), 12.0);
  // Every frame is shown: none is marked to be discarded (beyond the edit list's end).
  AVPacket* pkt = av_packet_alloc();
  int packets = 0, discarded = 0;
  while (av_read_frame(in, pkt) >= 0) {
    ++packets;
    discarded += (pkt->flags & AV_PKT_FLAG_DISCARD) != 0;
    av_packet_unref(pkt);
  }
  EXPECT_EQ(packets, 7);
  EXPECT_EQ(discarded, 0);
  EXPECT_NEAR(static_cast<double>(in->duration) / AV_TIME_BASE, 7.0 / 12.0, 1e-3) << "7 frames of 1/12 s";
  av_packet_free(&pkt);
  avformat_close_input(&in);
}

TEST(VideoWriter, ErrorsNameThePathAndLeaveNoFile) {
  const fs::path d = out_dir();
  auto bad_ext = VideoWriter::open((d / "clip.avi").string(), 64, 40, 10);
  ASSERT_FALSE(bad_ext.ok());
  EXPECT_NE(bad_ext.error().message.find("clip.avi"), std::string::npos);
  EXPECT_NE(bad_ext.error().message.find(".gif, .mp4"), std::string::npos);
  EXPECT_FALSE(VideoWriter::open((d / "x.gif").string(), 64, 40, 0).ok());
  EXPECT_FALSE(VideoWriter::open((d / "x.gif").string(), 0, 40, 10).ok());
  for (const char* name : {"no/such/dir/clip.gif", "no/such/dir/clip.mp4"}) {
    auto w = VideoWriter::open((d / name).string(), 64, 40, 10);
    ASSERT_FALSE(w.ok()) << name;
    EXPECT_NE(w.error().message.find(name), std::string::npos) << w.error().message;
  }
  {  // Dropped without finish(): no file at all, not even the part.
    const std::string path = (d / "dropped.mp4").string();
    auto w = VideoWriter::open(path, 64, 40, 10);
    ASSERT_TRUE(w.ok());
    const auto px = frame(64, 40, 0);
    ASSERT_TRUE(w.value()->add_frame(px.data(), 64 * 4).ok());
    EXPECT_FALSE(fs::exists(path));
  }
  EXPECT_FALSE(fs::exists(d / "dropped.mp4"));
  EXPECT_FALSE(fs::exists(d / "dropped.mp4.part"));
}

}  // namespace
}  // namespace viz
