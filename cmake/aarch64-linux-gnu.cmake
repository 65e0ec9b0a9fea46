# CMake toolchain file: cross-compile for aarch64 Linux with Debian's g++-aarch64-linux-gnu.
# Used by dev/cross_test_arm64.sh (the ROS-free core and its kernel tests under qemu-user).
#
# The arm64 libraries (Highway, yaml-cpp, gtest, Eigen's headers) come from a sysroot of
# unpacked Debian packages (BEARING_SIM_ARM64_SYSROOT, default build-arm64/sysroot), not from
# multiarch: libyaml-cpp-dev is not Multi-Arch: same, so installing its arm64 build would
# remove the amd64 one that the ROS build uses. libc and libstdc++ are the cross compiler's
# own (/usr/aarch64-linux-gnu), so the sysroot is only searched, not passed as --sysroot.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
# The cross compiler's implicit directories do not name the multiarch triplet, so CMake would
# not search <prefix>/lib/aarch64-linux-gnu/cmake for the packages' config files.
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)

# Toolchain files are read again for every try_compile: the environment carries the sysroot
# there as well as a cache variable would.
if(NOT BEARING_SIM_ARM64_SYSROOT)
  if(DEFINED ENV{BEARING_SIM_ARM64_SYSROOT})
    set(BEARING_SIM_ARM64_SYSROOT "$ENV{BEARING_SIM_ARM64_SYSROOT}")
  else()
    get_filename_component(BEARING_SIM_ARM64_SYSROOT "${CMAKE_CURRENT_LIST_DIR}/../build-arm64/sysroot" ABSOLUTE)
  endif()
endif()
set(ENV{BEARING_SIM_ARM64_SYSROOT} "${BEARING_SIM_ARM64_SYSROOT}")

set(CMAKE_FIND_ROOT_PATH "${BEARING_SIM_ARM64_SYSROOT}" /usr/aarch64-linux-gnu)
# Programs (cmake, qemu) are the host's; libraries, headers and packages only the target's,
# so that nothing of the amd64 /usr/lib can be picked up by mistake.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# Target binaries run through qemu-user with the cross libc (ctest, gtest_discover_tests, try_run).
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64 -L /usr/aarch64-linux-gnu)
