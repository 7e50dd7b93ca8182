#pragma once
// The status notices at the top of the 3D view: a build under way, the construction being
// recorded, the heat map being traced, the recorder's last word. They read the tools that
// have something to say; the playlist's title is the playlist's own overlay.
#include "tools/tool.h"

namespace viz {

class StatusOverlay final : public Tool {
 public:
  const char* name() const override { return "status"; }
  void overlay(ToolHost& host) override;
};

}  // namespace viz
