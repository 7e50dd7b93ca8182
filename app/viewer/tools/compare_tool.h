#pragma once
// Compare: the same ray through every structure and traversal order. Owns the background
// job, its rows, the ray they were made for and the "Same ray, every structure" window.
// For a student's structure it also runs the ray through the built-in structure of its kind
// and shows the first step where the two differ, and which answer is right (trace_diff.h).
#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "commands.h"
#include "job.h"
#include "student/trace_diff.h"
#include "tool_host.h"
#include "tools/compare_model.h"
#include "tools/tool.h"
#include "view_layout.h"

namespace viz {

/// A structure (and parameters) the user asked to see from the compare table.
struct StructureChoice {
  std::string name;
  std::vector<std::string> params;
};

/// What one comparison found.
struct CompareResult {
  std::vector<CompareRow> rows;
  /// A student structure against the built-in of its kind (`peer`, as `peer_params`).
  std::optional<accel::TraceDifference> builtin;
  std::string peer, peer_params, builtin_error;
};

/// The comparison table and its job.
class CompareTool final : public Tool {
 public:
  // ---- The tool (tool.h)
  const char* name() const override { return "compare"; }
  /// C: compare the debug ray; `host` gives the ray and starts the run.
  std::vector<KeyBinding> keys(ToolHost& host) override;
  void add_verbs(VerbTable& table, ToolHost& host) override;
  void wait() override { job_.wait(); }
  /// A new scene forgets the rows; a new ray runs again while the window is open.
  void on_event(ToolEvent event, ToolHost& host) override;
  void update(ToolHost&, float) override { poll(); }
  /// The table, along the bottom of the view.
  void panels(ToolHost& host) override;
  bool set_panel(const std::string& name, bool on) override;

  /// Starts comparing `ray` over `scene`; `current` keeps its parameters (the traversal
  /// varied); `shown`, the structure built for `current`, is compared with the built-in of
  /// its kind when it is a student's. Synchronous in script mode.
  void start(std::shared_ptr<const accel::Scene> scene, const accel::Ray& ray, const StructureRequest& current,
             BuiltPtr shown, bool synchronous);
  /// Takes the finished rows (per frame).
  void poll();
  /// Forgets the rows (a new scene).
  void clear() { result_ = CompareResult{}; }
  /// The rows of the last finished comparison.
  const std::vector<CompareRow>& rows() const { return result_.rows; }
  /// The step of the current (student's) trace the user asked to go to, once.
  std::optional<size_t> take_seek() { return std::exchange(seek_, std::nullopt); }
  /// Prints the rows as the `compare` script command does.
  void print_rows() const;

  /// Whether the window is shown.
  bool open() const { return open_; }
  /// Shows or hides the window.
  void set_open(bool open) { open_ = open; }
  /// The window; `built` marks the current row, `ray` tells whether the rows are stale.
  /// Returns the structure whose "show" button was pressed.
  std::optional<StructureChoice> panel(const PanelPlace& place, const BuiltStructure* built, const accel::Ray& ray);

 private:
  void builtin_lines();  // the student-against-built-in lines above the table

  Job<CompareResult> job_;
  std::shared_ptr<std::atomic<int>> progress_;
  CompareResult result_;
  std::optional<size_t> seek_;
  accel::Ray ray_;  // the ray of the rows
  bool open_ = false;
};

}  // namespace viz
