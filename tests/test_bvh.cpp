// Tests for core/bvh: STUB
