// Exit status 0 if this machine runs x86-64-v3 code: AVX, AVX2, BMI1, BMI2,
// F16C, FMA, LZCNT and MOVBE, with the OS saving the AVX registers. CMake
// runs it once at configure time (HGRID_ARCH=auto); it is not part of the library.
#include <cpuid.h>

int main() {
  unsigned a = 0, b = 0, c = 0, d = 0;
  if (!__get_cpuid(1, &a, &b, &c, &d)) return 1;
  const bool fma = (c >> 12) & 1, movbe = (c >> 22) & 1, popcnt = (c >> 23) & 1, osxsave = (c >> 27) & 1,
             avx = (c >> 28) & 1, f16c = (c >> 29) & 1;
  if (!(fma && movbe && popcnt && osxsave && avx && f16c)) return 1;
  unsigned xcr0 = 0, xcr0_hi = 0;
  __asm__("xgetbv" : "=a"(xcr0), "=d"(xcr0_hi) : "c"(0));
  if ((xcr0 & 6) != 6) return 1;  // SSE and AVX state enabled by the OS
  if (!__get_cpuid_count(7, 0, &a, &b, &c, &d)) return 1;
  const bool bmi1 = (b >> 3) & 1, avx2 = (b >> 5) & 1, bmi2 = (b >> 8) & 1;
  if (!(bmi1 && avx2 && bmi2)) return 1;
  if (!__get_cpuid(0x80000001, &a, &b, &c, &d)) return 1;
  return ((c >> 5) & 1) ? 0 : 1;  // LZCNT
}
