# ACCEL_SANITIZE=ON instruments every target with ASan + UBSan (one CI configuration).
if(ACCEL_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()
