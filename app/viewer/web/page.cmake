# The web page (included by app/viewer/CMakeLists.txt under emscripten): accelviz.js,
# accelviz.wasm and accelviz.data (the bundled files) next to our own accelviz.html, in the
# build folder's root, which any static file server can serve as it is.
#
# -sASYNCIFY: the main loop waits for the browser's next animation frame in the middle of
#   main() (browser_web.cpp), and background tasks are fibers; both unwind the stack.
# One thread (no SharedArrayBuffer, so no special HTTP headers); memory grows as scenes do.
set_target_properties(accelviz PROPERTIES
  SUFFIX ".js"
  RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR})

# The files the page opens, at the paths the native viewer finds them under the repository
# root (/app stands in for it: shaders/, scenes/, and ../shared/scenes/ as /shared/scenes).
set(bundle
  "${PROJECT_SOURCE_DIR}/shaders@/app/shaders"
  "${PROJECT_SOURCE_DIR}/scenes@/app/scenes")
# The bench's results, for the speed-against-error chart (the lecture playlist opens one).
file(GLOB bench_results CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/bench/*.json)
foreach(result ${bench_results})
  cmake_path(GET result FILENAME name)
  list(APPEND bundle "${result}@/app/bench/${name}")
endforeach()
# The small meshes of ../shared, when it is there: the lecture's presets and the test's bunny.
set(ACCEL_WEB_SHARED_SCENES "${PROJECT_SOURCE_DIR}/../shared/scenes" CACHE PATH
    "Folder of the shared meshes bundled into the page (skipped when absent)")
set(ACCEL_WEB_SHARED_MESHES bunny_lowres.obj bunny.obj teapot.obj dragon_res4.obj cornell_box.obj spot.obj
    CACHE STRING "Shared meshes bundled into the page")
foreach(mesh ${ACCEL_WEB_SHARED_MESHES})
  if(EXISTS "${ACCEL_WEB_SHARED_SCENES}/${mesh}")
    cmake_path(SET mesh_path NORMALIZE "${ACCEL_WEB_SHARED_SCENES}/${mesh}")
    list(APPEND bundle "${mesh_path}@/shared/scenes/${mesh}")
  endif()
endforeach()
# The viewer's fonts (main.cpp looks for DejaVu where Debian puts it; ImGui's own otherwise).
foreach(font DejaVuSans.ttf DejaVuSansMono.ttf)
  set(font_path "/usr/share/fonts/truetype/dejavu/${font}")
  if(EXISTS ${font_path})
    list(APPEND bundle "${font_path}@${font_path}")
  endif()
endforeach()

set(preload)
foreach(entry ${bundle})
  list(APPEND preload "SHELL:--preload-file ${entry}")
endforeach()

target_link_options(accelviz PRIVATE
  -sASYNCIFY
  -sALLOW_MEMORY_GROWTH=1
  -sMAXIMUM_MEMORY=4GB
  -sTOTAL_STACK=8MB
  -sFORCE_FILESYSTEM=1
  -sENVIRONMENT=web
  -sINVOKE_RUN=0
  "-sEXPORTED_RUNTIME_METHODS=['FS','callMain']"
  ${preload})
# Relink when a bundled folder changes (the data file is made by the link).
file(GLOB_RECURSE bundled_files CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/shaders/* ${PROJECT_SOURCE_DIR}/scenes/*)
list(APPEND bundled_files ${bench_results})
set_property(TARGET accelviz APPEND PROPERTY LINK_DEPENDS ${bundled_files})

# Our page (emscripten 3.1.6 cannot minify an HTML output of its own) and its script.
configure_file(${CMAKE_CURRENT_SOURCE_DIR}/web/accelviz.html ${CMAKE_BINARY_DIR}/accelviz.html COPYONLY)
configure_file(${CMAKE_CURRENT_SOURCE_DIR}/web/page.js ${CMAKE_BINARY_DIR}/page.js COPYONLY)
