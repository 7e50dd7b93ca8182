// Tests for core/uniform_grid: STUB
