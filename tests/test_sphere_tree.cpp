// Tests for core/sphere_tree: STUB
