#pragma once
// Recording for slides: the frames the animation shows -- one per traversal or construction
// step -- written to an animated GIF or an MP4 (video_writer.h), the whole window or the 3D
// view alone; and F12's numbered PNG screenshots in the pictures folder. App tells it when a step changed and
// calls capture() after drawing the 3D view (before the panels) and after the panels, so a
// recording without the UI holds the scene only.
#include <memory>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "commands.h"
#include "result.h"
#include "tools/tool.h"
#include "video_writer.h"

namespace viz {

struct RecordOptions {
  int fps = 4;        ///< frames (steps) per second of the video
  bool ui = true;     ///< the whole window with its panels; false: the 3D view only
  int width = 0;      ///< output size; 0: the captured size
  int height = 0;
};

class Recorder final : public Tool {
 public:
  // ---- The tool (tool.h)
  const char* name() const override { return "recording"; }
  /// R starts and stops a recording; F12 takes a screenshot.
  std::vector<KeyBinding> keys(ToolHost& host) override;
  /// record, record stop.
  void add_verbs(VerbTable& table, ToolHost& host) override;
  /// A new step of the animation (traversal or construction) is a new frame of a recording.
  void update(ToolHost& host, float dt) override;
  /// Own: the "Recording" section.
  void section(ToolHost& host, PanelSection section) override;
  /// " - recording (R stops)" while one runs.
  void window_title(std::string& title, const ToolHost& host) const override;

  /// Starts a recording with the section's path and options, or stops the one running.
  accel::Status toggle();
  /// Starts recording to `path` (.gif or .mp4). The first frame is the next one drawn.
  /// Errors name the path: an unknown extension, a bad fps, a recording already running.
  accel::Status start(const std::string& path, const RecordOptions& options);
  /// Finishes the file; "wrote PATH (N frames)" or the error naming the path.
  accel::Status stop();
  bool recording() const { return writer_ != nullptr || pending_.has_value(); }
  /// The animation moved to another step: the next frame drawn is recorded.
  void step_changed() { due_ = true; }

  /// F12: the next finished frame goes to the next free accelviz_NNNN.png in the pictures
  /// folder (paths.h: pictures_dir(), made when missing; the notice says where).
  void request_screenshot() { screenshot_due_ = true; }
  /// Whether capture() has work for this frame (skips the read-back otherwise).
  bool wants_capture(bool with_ui) const;
  /// Reads the current back buffer: with_ui = false right after the 3D view was drawn
  /// (`view` is its rectangle, x, y from the top-left, framebuffer pixels), true after the
  /// panels (`framebuffer` is the whole size). Records or saves what is due.
  void capture(bool with_ui, glm::ivec4 view, glm::ivec2 framebuffer);

  /// The main panel's "Recording" section; true when Record / Stop was pressed (the
  /// caller starts or stops with the section's path and options).
  bool settings_section();
  const std::string& path_field() const { return path_field_; }
  const RecordOptions& options() const { return options_; }
  /// One line for the status overlay: the running recording, or the last result (a file
  /// written, an error) for a few seconds; empty when there is nothing to say.
  std::string notice() const;
  /// Whether a recording with the panels runs (its frames must not show the notice).
  bool recording_ui() const { return recording() && options_.ui; }

 private:
  /// The animation's step at the last frame: a new one is recorded.
  struct StepSeen {
    size_t trace = ~size_t(0), build = ~size_t(0);
    bool build_mode = false;
    bool operator==(const StepSeen&) const = default;
  } step_seen_;

  struct Pending {
    std::string path;
    RecordOptions options;
  };
  std::optional<Pending> pending_;        // started, the first frame not yet captured
  std::unique_ptr<VideoWriter> writer_;
  RecordOptions options_;
  bool due_ = false;
  bool screenshot_due_ = false;
  std::string path_field_ = "accelviz.gif";
  void set_notice(std::string text);
  std::string notice_;
  double notice_until_ = 0.0;  // seconds on the steady clock
  int next_screenshot_ = 1;
};

}  // namespace viz
