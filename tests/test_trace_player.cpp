// STUB: tests for core/trace_player and core/heatmap
