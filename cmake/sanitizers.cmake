# ACCEL_SANITIZE=ON instruments every target with ASan + UBSan (one CI configuration).
if(ACCEL_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()

# ACCEL_FUZZ=ON builds tests/fuzz's libFuzzer targets. The core is compiled with the
# fuzzer's coverage counters (core/CMakeLists.txt), the targets link libFuzzer's main.
if(ACCEL_FUZZ AND NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "ACCEL_FUZZ needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang")
endif()
