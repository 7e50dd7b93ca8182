#pragma once
// STUB: replaced by the viewer helper (TracePlayer: time -> step of a recorded trace).
