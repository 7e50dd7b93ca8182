#include "tools/recorder.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <vector>

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include "browser.h"
#include "paths.h"
#include "screenshot.h"
#include "tool_host.h"
#include "tools/build_player.h"
#include "tools/ray_debugger.h"
#include "tools/recorder_verbs.h"

namespace viz {
namespace {

constexpr double kNoticeSeconds = 4.0;

double clock_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

accel::Status Recorder::start(const std::string& path, const RecordOptions& options) {
  if (recording()) return accel::make_error("record: already recording to " + (writer_ ? writer_->path() : pending_->path) +
                                            " (record stop first)");
  if (auto format = video_format_of(path); !format) return accel::make_error("record: " + format.error().message);
  if (options.fps < VideoWriter::kMinFps || options.fps > VideoWriter::kMaxFps)
    return accel::make_error("record: fps=" + std::to_string(options.fps) + " is out of range (" +
                             std::to_string(VideoWriter::kMinFps) + ".." + std::to_string(VideoWriter::kMaxFps) + ")");
  // The file itself is created with the first frame, when its size is known; check now that
  // it can be, so a bad path fails here rather than at the first step.
  const std::filesystem::path dir = std::filesystem::absolute(path).parent_path();
  if (!std::filesystem::is_directory(dir))
    return accel::make_error("record: " + path + ": the directory " + dir.string() + " does not exist");
  pending_ = Pending{path, options};
  options_ = options;
  path_field_ = path;
  due_ = true;
  set_notice("recording " + path);
  return {};
}

accel::Status Recorder::stop() {
  if (pending_) {  // nothing was drawn since start
    const std::string path = pending_->path;
    pending_.reset();
    set_notice("record: nothing recorded to " + path);
    return accel::make_error("record stop: no frame was recorded to " + path);
  }
  if (!writer_) return accel::make_error("record stop: not recording");
  std::unique_ptr<VideoWriter> w = std::move(writer_);
  const size_t frames = w->frames();
  const std::string path = w->path();
  if (auto st = w->finish(); !st) {
    set_notice(st.error().message);
    return st;
  }
  const std::string written = std::filesystem::absolute(path).string();
  set_notice("wrote " + written + " (" + std::to_string(frames) + " frames)");
  browser::offer_download(written);  // the page: the browser saves it as a download
  return {};
}

bool Recorder::wants_capture(bool with_ui) const {
  if (with_ui && screenshot_due_) return true;
  return recording() && due_ && options_.ui == with_ui;
}

void Recorder::capture(bool with_ui, glm::ivec4 view, glm::ivec2 framebuffer) {
  if (!wants_capture(with_ui) || framebuffer.x <= 0 || framebuffer.y <= 0) return;
  if (with_ui && screenshot_due_) {
    screenshot_due_ = false;
    // The pictures folder, made on the first F12 (paths.h says which one).
    const std::filesystem::path dir = std::filesystem::absolute(pictures_dir());
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) {
      set_notice("screenshot: cannot create the folder " + dir.string() + ": " + ec.message());
    } else {
      std::filesystem::path file;
      for (;; ++next_screenshot_) {
        char name[32];
        std::snprintf(name, sizeof name, "accelviz_%04d.png", next_screenshot_);
        file = dir / name;
        if (!std::filesystem::exists(file)) break;
      }
      const std::string path = file.string();
      if (auto st = save_framebuffer_png(path, framebuffer.x, framebuffer.y); !st) set_notice(st.error().message);
      else {
        set_notice("screenshot: wrote " + path);
        browser::offer_download(path);  // the page: the browser saves it as a download
      }
    }
  }
  if (!recording() || !due_ || options_.ui != with_ui) return;
  due_ = false;
  const glm::ivec4 r = with_ui ? glm::ivec4(0, 0, framebuffer.x, framebuffer.y) : view;
  if (r.z <= 0 || r.w <= 0) return;
  std::vector<uint8_t> px = read_back_buffer(r, framebuffer.y, 4);
  for (size_t i = 3; i < px.size(); i += 4) px[i] = 255;  // the framebuffer's alpha is not the picture's
  if (pending_) {
    const int w = options_.width > 0 ? options_.width : r.z, h = options_.height > 0 ? options_.height : r.w;
    auto opened = VideoWriter::open(pending_->path, w, h, options_.fps);
    pending_.reset();
    if (!opened) {
      set_notice("record: " + opened.error().message);
      return;
    }
    writer_ = std::move(opened.value());
  }
  if (r.z != writer_->width() || r.w != writer_->height()) {
    // A resized window or an explicit size: every frame has the video's size.
    px = resize_rgba(px, r.z, r.w, writer_->width(), writer_->height());
    if (px.empty()) return;
  }
  if (auto st = writer_->add_frame(px.data(), static_cast<size_t>(writer_->width()) * 4); !st) {
    writer_.reset();  // the writer removed its partial file
    set_notice("record: " + st.error().message);
  }
}

bool Recorder::settings_section() {
  const float em = ImGui::GetFontSize();
  bool pressed = false;
  ImGui::SetNextItemWidth(14.0f * em);
  ImGui::BeginDisabled(recording());
  ImGui::InputText("file (.gif, .mp4)", &path_field_);
  ImGui::SetNextItemWidth(8.0f * em);
  ImGui::SliderInt("steps per second", &options_.fps, VideoWriter::kMinFps, VideoWriter::kMaxFps);
  ImGui::Checkbox("with the panels", &options_.ui);
  ImGui::EndDisabled();
  if (ImGui::Button(recording() ? "Stop recording (R)" : "Record (R)")) pressed = true;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("one frame per step of the animation: play it (space, or P for the construction)");
  ImGui::TextDisabled("F12: screenshot to the pictures folder");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s/accelviz_NNNN.png", std::filesystem::absolute(pictures_dir()).c_str());
  if (const std::string n = notice(); !n.empty()) ImGui::TextWrapped("%s", n.c_str());
  return pressed;
}

void Recorder::set_notice(std::string text) {
  notice_ = std::move(text);
  notice_until_ = clock_seconds() + kNoticeSeconds;
}

std::string Recorder::notice() const {
  if (writer_)
    return "recording " + writer_->path() + ": " + std::to_string(writer_->frames()) + " frames (R stops)";
  if (pending_) return "recording " + pending_->path + ": waiting for the first frame";
  return clock_seconds() < notice_until_ ? notice_ : std::string();
}

// ---------------------------------------------------------------------------------------
// Script verbs (tools/recorder_verbs.h)

void Recorder::add_verbs(VerbTable& table, ToolHost& host) {
  ToolVerbs<Recorder> verbs(table, *this, host);
  recorder_verbs(verbs);
}

// ---------------------------------------------------------------------------------------
// The tool's keys and frame

std::vector<KeyBinding> Recorder::keys(ToolHost&) {
  return {
      // The notice says what happened.
      {GLFW_KEY_R, "R", "start / stop recording a GIF or MP4",
       [this](const KeyPress&) {
         (void)toggle();
         return true;
       }},
      {GLFW_KEY_F12, "F12", "screenshot: writes a numbered accelviz_NNNN.png into the pictures folder and says where",
       [this](const KeyPress&) {
         request_screenshot();
         return true;
       }},
  };
}

accel::Status Recorder::toggle() { return recording() ? stop() : start(path_field_, options_); }

void Recorder::update(ToolHost& host, float) {
  const StepSeen seen{host.ray().player().step(), host.build().player().step(), host.build().active()};
  if (seen == step_seen_) return;
  step_seen_ = seen;
  step_changed();
}

void Recorder::section(ToolHost&, PanelSection section) {
  if (section != PanelSection::Own || !ImGui::CollapsingHeader("Recording")) return;
  if (settings_section()) (void)toggle();  // the section shows the result
}

void Recorder::window_title(std::string& title, const ToolHost&) const {
  if (recording()) title += " - recording (R stops)";
}

}  // namespace viz
