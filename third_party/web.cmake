# The web build's libraries (emscripten; scripts/build_web.sh configures it). Nothing here is
# copied into the repository or downloaded from elsewhere:
#  * glm, nlohmann-json, stb, tinyobjloader and CLI11 are header files of the host's Debian packages,
#    reached through a folder of links in the build tree (the host's /usr/include itself would
#    bring glibc's headers into emscripten's sysroot);
#  * Dear ImGui is compiled from Debian's source package (apt-get source imgui, fetched by
#    build_web.sh into ACCEL_IMGUI_SOURCE_DIR), with its GLFW and OpenGL3 backends;
#  * giflib likewise (apt-get source giflib, into ACCEL_GIF_SOURCE_DIR): the page records
#    GIFs with the writer the native viewer uses;
#  * GLFW is emscripten's own (-sUSE_GLFW=3), OpenGL ES 3.0 is WebGL2.
set(ACCEL_HOST_INCLUDE_DIR "/usr/include" CACHE PATH "Where the host's Debian headers are (glm, nlohmann, stb, tiny_obj_loader.h, CLI)")
set(ACCEL_IMGUI_SOURCE_DIR "" CACHE PATH "Dear ImGui's unpacked Debian source package (imgui.cpp, backends/)")
set(ACCEL_GIF_SOURCE_DIR "" CACHE PATH "giflib's unpacked Debian source package (egif_lib.c, quantize.c, ...)")

set(host_links ${CMAKE_CURRENT_BINARY_DIR}/host-include)
file(MAKE_DIRECTORY ${host_links})
foreach(entry glm nlohmann stb tiny_obj_loader.h CLI)
  if(NOT EXISTS ${ACCEL_HOST_INCLUDE_DIR}/${entry})
    message(FATAL_ERROR "web build: ${ACCEL_HOST_INCLUDE_DIR}/${entry} is missing (scripts/deps.sh installs it)")
  endif()
  file(CREATE_LINK ${ACCEL_HOST_INCLUDE_DIR}/${entry} ${host_links}/${entry} SYMBOLIC)
endforeach()

add_library(glm::glm INTERFACE IMPORTED GLOBAL)
target_include_directories(glm::glm SYSTEM INTERFACE ${host_links})
add_library(nlohmann_json::nlohmann_json INTERFACE IMPORTED GLOBAL)
target_include_directories(nlohmann_json::nlohmann_json SYSTEM INTERFACE ${host_links})
add_library(PkgConfig::STB INTERFACE IMPORTED GLOBAL)
target_include_directories(PkgConfig::STB SYSTEM INTERFACE ${host_links})
add_library(CLI11::CLI11 INTERFACE IMPORTED GLOBAL)
target_include_directories(CLI11::CLI11 SYSTEM INTERFACE ${host_links})

# tinyobjloader is one header whose implementation a single unit switches on.
add_library(tinyobjloader_web STATIC ${CMAKE_CURRENT_SOURCE_DIR}/tinyobjloader_impl.cpp)
target_include_directories(tinyobjloader_web SYSTEM PUBLIC ${host_links})
target_compile_definitions(tinyobjloader_web PUBLIC TINYOBJLOADER_USE_DOUBLE)
add_library(tinyobjloader::tinyobjloader_double ALIAS tinyobjloader_web)

# GLFW and WebGL2 come with emscripten: link options only.
add_library(glfw INTERFACE)
target_link_options(glfw INTERFACE -sUSE_GLFW=3 -sMIN_WEBGL_VERSION=2 -sMAX_WEBGL_VERSION=2)

if(NOT EXISTS ${ACCEL_IMGUI_SOURCE_DIR}/imgui.cpp OR NOT EXISTS ${ACCEL_IMGUI_SOURCE_DIR}/backends/imgui_impl_glfw.cpp)
  message(FATAL_ERROR "web build: ACCEL_IMGUI_SOURCE_DIR='${ACCEL_IMGUI_SOURCE_DIR}' holds no ImGui sources "
                      "(scripts/build_web.sh fetches them with apt-get source imgui)")
endif()
add_library(imgui_web STATIC
  ${ACCEL_IMGUI_SOURCE_DIR}/imgui.cpp
  ${ACCEL_IMGUI_SOURCE_DIR}/imgui_draw.cpp
  ${ACCEL_IMGUI_SOURCE_DIR}/imgui_tables.cpp
  ${ACCEL_IMGUI_SOURCE_DIR}/imgui_widgets.cpp
  ${ACCEL_IMGUI_SOURCE_DIR}/backends/imgui_impl_glfw.cpp
  ${ACCEL_IMGUI_SOURCE_DIR}/backends/imgui_impl_opengl3.cpp
  ${ACCEL_IMGUI_SOURCE_DIR}/misc/cpp/imgui_stdlib.cpp)
target_include_directories(imgui_web SYSTEM PUBLIC
  ${ACCEL_IMGUI_SOURCE_DIR} ${ACCEL_IMGUI_SOURCE_DIR}/backends ${ACCEL_IMGUI_SOURCE_DIR}/misc/cpp)
target_link_libraries(imgui_web PUBLIC glfw)
add_library(imgui::imgui ALIAS imgui_web)

# giflib: the library files of its Makefile (SOURCES), not its tools.
if(NOT EXISTS ${ACCEL_GIF_SOURCE_DIR}/egif_lib.c OR NOT EXISTS ${ACCEL_GIF_SOURCE_DIR}/quantize.c)
  message(FATAL_ERROR "web build: ACCEL_GIF_SOURCE_DIR='${ACCEL_GIF_SOURCE_DIR}' holds no giflib sources "
                      "(scripts/build_web.sh fetches them with apt-get source giflib)")
endif()
add_library(gif_web STATIC
  ${ACCEL_GIF_SOURCE_DIR}/dgif_lib.c
  ${ACCEL_GIF_SOURCE_DIR}/egif_lib.c
  ${ACCEL_GIF_SOURCE_DIR}/gifalloc.c
  ${ACCEL_GIF_SOURCE_DIR}/gif_err.c
  ${ACCEL_GIF_SOURCE_DIR}/gif_font.c
  ${ACCEL_GIF_SOURCE_DIR}/gif_hash.c
  ${ACCEL_GIF_SOURCE_DIR}/openbsd-reallocarray.c
  ${ACCEL_GIF_SOURCE_DIR}/quantize.c)
target_include_directories(gif_web SYSTEM PUBLIC ${ACCEL_GIF_SOURCE_DIR})
add_library(GIF::GIF ALIAS gif_web)
