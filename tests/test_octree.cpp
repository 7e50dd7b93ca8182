// Tests for core/octree: STUB
