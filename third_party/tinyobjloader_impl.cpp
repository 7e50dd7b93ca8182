// tinyobjloader's implementation for the web build: Debian ships it as one header, which
// natively comes precompiled in libtinyobjloader; here a single unit compiles it.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
