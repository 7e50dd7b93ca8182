// Tests for core/kd_tree: STUB
