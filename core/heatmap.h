#pragma once
// STUB: replaced by the viewer helper (per-pixel traversal cost image, computed in parallel).
