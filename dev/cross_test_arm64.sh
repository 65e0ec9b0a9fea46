#!/usr/bin/env bash
# Cross-compiles the ROS-free core library and its SIMD kernel tests for aarch64 and runs them
# under qemu-user, once per emulated CPU, so that Highway's NEON, SVE, SVE2, SVE_256 and
# SVE2_128 kernels are checked against the scalar loops (test_contact_kernel forces the
# dispatcher onto every target the emulated CPU runs). Nothing here touches build/.
#
#   dev/cross_test_arm64.sh [--all] [--tests "test_a test_b"] [--cpus "cpu1 cpu2"] [--jobs N]
#                               [--no-install]
#
#   --all         also every other suite of test/core, under the first CPU configuration only
#                 (NEON): qemu emulates SVE some 15 times slower than NEON, so the whole core
#                 suite would take half an hour or more per SVE configuration
#   --tests       the suites of test/core to run under every CPU (names without .cpp)
#   --cpus        qemu-aarch64 -cpu values (default: the list in CPUS below)
#   --jobs        parallel compile jobs (default 2)
#   --no-install  fail instead of installing missing Debian packages
#
# Output: build-arm64/ (sysroot of unpacked arm64 packages, build tree, per-CPU logs and gtest
# XML); the last line is "N passed, N failed" over all gtest cases and configurations; the exit
# status is non-zero when any failed or a binary crashed.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OUT=$ROOT/build-arm64
SYSROOT=$OUT/sysroot
BUILD=$OUT/build
RESULTS=$OUT/results

# Run under every CPU: the suite that tests the kernels against the scalar loops on every
# compiled target (contact sums, race spall windows, waviness sums and coefficients, the Adams
# step's small products), and two fast ones that reach the same kernels through the model's
# waviness and spalls (~20 s per SVE configuration; test_exponential_integrator, which runs
# the small products through the integrator, takes well over 10 min there: --all runs it on NEON).
TESTS="test_contact_kernel test_imperfections test_row_imperfections"
# One configuration per kind of Arm vector unit that Highway distinguishes:
#   max,sve=off        NEON only (Cortex-A72/A76, Neoverse N1, Graviton 2)
#   max,sve128=on      SVE2 with 128-bit vectors: Highway's SVE2_128 (Neoverse N2/V2, Graviton 4)
#   max,sve256=on      256-bit vectors: Highway's SVE_256 (Neoverse V1, Graviton 3)
#   a64fx              SVE without SVE2, 512 bits: Highway's SVE target chosen
#   max                SVE2 at qemu-user's default 512 bits: the generic SVE2 target
#   max,sve-default-vector-length=256
#                      SVE2 at 2048 bits, the architecture's maximum (32 doubles per vector:
#                      HWY_MAX_BYTES buffers, masked tails and blocks wider than every matrix)
# Every configuration also runs each lesser target it supports (NEON included).
CPUS="max,sve=off max,sve128=on max,sve256=on a64fx max max,sve-default-vector-length=256"
JOBS=2
INSTALL=1
ALL=0

while [ $# -gt 0 ]; do
  case $1 in
    --all) ALL=1 ;;
    --tests) TESTS=$2; shift ;;
    --cpus) CPUS=$2; shift ;;
    --jobs) JOBS=$2; shift ;;
    --no-install) INSTALL=0 ;;
    -h|--help) sed -n '2,20p' "$0"; exit 0 ;;
    *) echo "unknown argument: $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done

seconds() { date +%s; }
T_START=$(seconds)

# --- 1. Host tools: the cross compiler, qemu-user, cmake, ninja (all Debian bookworm packages).
need_packages=()
command -v aarch64-linux-gnu-g++ >/dev/null || need_packages+=(g++-aarch64-linux-gnu)
command -v aarch64-linux-gnu-gcc >/dev/null || need_packages+=(gcc-aarch64-linux-gnu)
command -v qemu-aarch64 >/dev/null || need_packages+=(qemu-user)
command -v cmake >/dev/null || need_packages+=(cmake)
command -v ninja >/dev/null || need_packages+=(ninja-build)
apt_updated=0
if [ ${#need_packages[@]} -gt 0 ]; then
  if [ $INSTALL = 0 ]; then
    echo "missing Debian packages: ${need_packages[*]}" >&2
    exit 1
  fi
  echo "== installing ${need_packages[*]}"
  apt-get update -qq
  apt_updated=1
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${need_packages[@]}"
fi

# --- 2. The arm64 libraries, unpacked into a sysroot under build-arm64/ rather than installed
# through multiarch: libyaml-cpp-dev is not Multi-Arch: same, and installing its arm64 build
# would remove the amd64 one (and the ROS build with it). Highway at the version of the
# amd64 package that the x86 build uses, so that both builds compile the same kernels.
ARM64_PACKAGES="libhwy-dev libhwy1 libyaml-cpp-dev libyaml-cpp0.7 libgtest-dev libeigen3-dev"
if ! dpkg --print-foreign-architectures | grep -qx arm64; then
  if [ $INSTALL = 0 ]; then
    echo "arm64 is not a dpkg foreign architecture (dpkg --add-architecture arm64)" >&2
    exit 1
  fi
  # Only so that apt can download arm64 packages: nothing is installed for arm64.
  echo "== dpkg --add-architecture arm64"
  dpkg --add-architecture arm64
  apt_updated=0
fi
wanted=""
for package in $ARM64_PACKAGES; do
  arch=arm64
  [ "$package" = libeigen3-dev ] && arch=all  # header-only
  version=$(apt-cache policy "$package:$arch" 2>/dev/null | awk '/Candidate:/ {print $2}')
  if { [ -z "$version" ] || [ "$version" = "(none)" ]; } && [ $apt_updated = 0 ]; then
    apt-get update -qq
    apt_updated=1
    version=$(apt-cache policy "$package:$arch" | awk '/Candidate:/ {print $2}')
  fi
  if [ -z "$version" ] || [ "$version" = "(none)" ]; then
    echo "no $package:$arch in the apt sources" >&2
    exit 1
  fi
  [ "$package" = libhwy-dev ] && hwy_version=$version
  wanted="$wanted$package:$arch=$version"$'\n'
done
installed_hwy=$(dpkg-query -W -f='${Version}' libhwy-dev 2>/dev/null || true)
if [ -n "$installed_hwy" ] && [ "$installed_hwy" != "$hwy_version" ]; then
  echo "note: amd64 libhwy-dev is $installed_hwy, the arm64 one $hwy_version"
fi
# Unpacked again only when the package versions change (the stamp lists them).
# ($(...) drops the trailing newline on both sides.)
if [ "$(cat "$SYSROOT/.packages" 2>/dev/null)" != "$(printf '%s' "$wanted")" ]; then
  echo "== unpacking arm64 packages into $SYSROOT"
  rm -rf "$SYSROOT" "$OUT/debs"
  mkdir -p "$SYSROOT" "$OUT/debs"
  # The download runs as root into build-arm64/ (apt's _apt user may not write there).
  (cd "$OUT/debs" && apt-get download -qq -o APT::Sandbox::User=root $(printf '%s' "$wanted" | tr '\n' ' '))
  for deb in "$OUT"/debs/*.deb; do dpkg -x "$deb" "$SYSROOT"; done
  printf '%s' "$wanted" >"$SYSROOT/.packages"
fi
T_INSTALLED=$(seconds)

# --- 3. Configure and build the core and the chosen suites (cmake/arm64/CMakeLists.txt takes
# the core's sources from the main CMakeLists.txt).
ALL_TESTS=$(cd "$ROOT/test/core" && ls test_*.cpp | grep -vx test_support.cpp | sed 's/\.cpp$//' | tr '\n' ' ')
BUILD_TESTS=$TESTS
[ $ALL = 1 ] && BUILD_TESTS=$ALL_TESTS
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
cmake -S "$ROOT/cmake/arm64" -B "$BUILD" "${generator[@]}" \
  -DCMAKE_TOOLCHAIN_FILE="$ROOT/cmake/aarch64-linux-gnu.cmake" \
  -DBEARING_SIM_ARM64_SYSROOT="$SYSROOT" \
  -DBEARING_SIM_CROSS_TESTS="$(echo $BUILD_TESTS | tr ' ' ';')" >"$OUT/configure.log" ||
  { cat "$OUT/configure.log"; exit 1; }
cmake --build "$BUILD" -j "$JOBS"
T_BUILT=$(seconds)

# --- 4. Run every suite under each emulated CPU. -L: the cross compiler's libc and libstdc++;
# libhwy and libyaml-cpp come from the sysroot through the binaries' build RPATH.
echo "== per emulated CPU (qemu-aarch64 -cpu ...)"
passed_total=0
failed_total=0
rm -rf "$RESULTS"
first_cpu=1
for cpu in $CPUS; do
  suites=$TESTS
  [ $ALL = 1 ] && [ $first_cpu = 1 ] && suites=$ALL_TESTS
  first_cpu=0
  dir=$RESULTS/$(echo "$cpu" | tr ',=' '__')
  mkdir -p "$dir"
  qemu=(qemu-aarch64 -L /usr/aarch64-linux-gnu -cpu "$cpu")
  # An unknown -cpu value stops qemu at once: counted as a failure, not a silent skip.
  if ! unit=$("${qemu[@]}" "$BUILD/sve_vector_length" 2>&1); then
    echo "-cpu $cpu: qemu-aarch64 failed: $unit"
    failed_total=$((failed_total + 1))
    continue
  fi
  passed=0
  failed=0
  failed_names=""
  t0=$(seconds)
  for name in $suites; do
    log=$dir/$name.log
    status=0
    # From the source tree, as catkin runs them (config/ is read relative to it).
    (cd "$ROOT" && "${qemu[@]}" "$BUILD/bearing_sim_$name" --gtest_output="xml:$dir/$name.xml") >"$log" 2>&1 ||
      status=$?
    p=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) tests\{0,1\}\..*/\1/p' "$log" | tail -1)
    f=$(sed -n 's/^\[  FAILED  \] \([0-9]*\) tests\{0,1\}, listed below:.*/\1/p' "$log" | tail -1)
    p=${p:-0}
    f=${f:-0}
    # A crash (signal, SIGILL of an instruction qemu lacks) prints no summary: one failure.
    if [ $status -ne 0 ] && [ "$f" = 0 ]; then f=1; fi
    passed=$((passed + p))
    failed=$((failed + f))
    [ "$f" != 0 ] && failed_names="$failed_names $name"
  done
  # What the dispatcher ran on, from the kernel test's own lines.
  targets=""
  chosen=""
  if [ -f "$dir/test_contact_kernel.log" ]; then
    targets=$(sed -n 's/^\[ TARGET   \] \(.*\)/\1/p' "$dir/test_contact_kernel.log" | awk '!seen[$0]++' | tr '\n' ' ')
    chosen=$(sed -n 's/.*SIMD target: \(.*\)/\1/p' "$dir/test_contact_kernel.log" | head -1)
    compiled=$(sed -n 's/^\[ \(TARGET   \] \|SKIPPED  \] SIMD target \)\([A-Z0-9_]*\).*/\2/p' "$dir/test_contact_kernel.log" |
      awk '!seen[$0]++' | tr '\n' ' ')
  fi
  line="-cpu $cpu: $unit; targets tested: ${targets:-?}(dispatcher's choice: ${chosen:-?}); $(echo $suites | wc -w) suites: $passed passed, $failed failed ($(($(seconds) - t0)) s)"
  [ -n "$failed_names" ] && line="$line; failed:$failed_names (logs in $dir)"
  echo "$line"
  passed_total=$((passed_total + passed))
  failed_total=$((failed_total + failed))
done
T_TESTED=$(seconds)

echo "== compiled Highway targets: ${compiled:-?}"
echo "== suites under every CPU: $TESTS"
[ $ALL = 1 ] && echo "== every suite of test/core under -cpu ${CPUS%% *}"
echo "== time: install/sysroot $((T_INSTALLED - T_START)) s, configure+build $((T_BUILT - T_INSTALLED)) s, tests $((T_TESTED - T_BUILT)) s"
echo "$passed_total passed, $failed_total failed"
[ "$failed_total" = 0 ]
