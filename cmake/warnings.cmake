# accel_warnings: an INTERFACE target every project target links, so warning flags
# live in one place and never leak into third-party code.
add_library(accel_warnings INTERFACE)
target_compile_options(accel_warnings INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor>)
