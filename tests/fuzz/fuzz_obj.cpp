// libFuzzer target: OBJ loading and validation (core/obj_loader.cpp through load_scene, as
// the CLI and the viewer load a file), then every structure built on what loaded.
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static accel::fuzz::InputFile file(".obj");
  auto scene = accel::load_scene(file.write(data, size));
  if (!scene) {
    // One line, naming the file: what every front end prints.
    const std::string& message = scene.error().message;
    if (message.empty() || message.find('\n') != std::string::npos) std::abort();
    return 0;
  }
  accel::fuzz::build_and_trace_everything(scene.value());
  return 0;
}
