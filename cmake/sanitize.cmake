# -DBEARING_SIM_SANITIZE=ON: every target built with AddressSanitizer (and its leak checker)
# and UndefinedBehaviorSanitizer; undefined behaviour stops the program like a memory error.
# For a separate build directory (dev/sanitize_test.sh), not for the running node.
option(BEARING_SIM_SANITIZE "Build with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
if(BEARING_SIM_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()
