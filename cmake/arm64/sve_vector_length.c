// What the emulated CPU offers, for the log of dev/cross_test_arm64.sh: Highway picks its
// SVE targets from these (SVE_256 needs 256-bit vectors, SVE2_128 SVE2 with 128-bit ones), so
// the log shows that a qemu -cpu option took effect.
#include <asm/hwcap.h>
#include <stdio.h>
#include <sys/auxv.h>
#include <sys/prctl.h>

int main(void) {
  const unsigned long hwcap = getauxval(AT_HWCAP), hwcap2 = getauxval(AT_HWCAP2);
  if (!(hwcap & HWCAP_SVE)) {
    puts("no SVE");
    return 0;
  }
  const int vl = prctl(PR_SVE_GET_VL);  // bytes, with flags in the high bits
  printf("SVE%s, %d-bit vectors\n", (hwcap2 & HWCAP2_SVE2) ? " and SVE2" : " (no SVE2)",
         vl < 0 ? -1 : (vl & PR_SVE_VL_LEN_MASK) * 8);
  return 0;
}
