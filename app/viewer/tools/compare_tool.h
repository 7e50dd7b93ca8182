#pragma once
// Compare: the same ray through every structure and traversal order. Owns the background
// job, its rows, the ray they were made for and the "Same ray, every structure" window.
#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "view_layout.h"
#include "workbench.h"

namespace viz {

/// A structure (and parameters) the user asked to see from the compare table.
struct StructureChoice {
  std::string name;
  std::vector<std::string> params;
};

/// The comparison table and its job.
class CompareTool {
 public:
  /// Starts comparing `ray` over `scene`; `current` keeps its parameters (the traversal
  /// varied). Synchronous in script mode.
  void start(std::shared_ptr<const accel::Scene> scene, const accel::Ray& ray, const StructureRequest& current,
             bool synchronous);
  /// Takes the finished rows (per frame).
  void poll();
  /// Forgets the rows (a new scene).
  void clear() { rows_.clear(); }
  /// The rows of the last finished comparison.
  const std::vector<CompareRow>& rows() const { return rows_; }
  /// Prints the rows as the `compare` script command does.
  void print_rows() const;
  /// Waits for the job.
  void wait() { job_.wait(); }

  /// Whether the window is shown.
  bool open() const { return open_; }
  /// Shows or hides the window.
  void set_open(bool open) { open_ = open; }
  /// The window; `built` marks the current row, `ray` tells whether the rows are stale.
  /// Returns the structure whose "show" button was pressed.
  std::optional<StructureChoice> panel(const PanelPlace& place, const BuiltStructure* built, const accel::Ray& ray);

 private:
  Job<std::vector<CompareRow>> job_;
  std::shared_ptr<std::atomic<int>> progress_;
  std::vector<CompareRow> rows_;
  accel::Ray ray_;  // the ray of the rows
  bool open_ = false;
};

}  // namespace viz
