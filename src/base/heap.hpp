// How a process keeps the memory it frees, for programs that build and drop
// large arrays over and over (a grid per Monte Carlo sample, a model's tables
// per packing).
#pragma once

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace hgrid {

/// Largest block glibc still takes from its heaps rather than mmap() (its
/// own upper bound for this setting on 64-bit systems; larger blocks are
/// mapped and returned on free as before).
inline constexpr int kHeapBlockMax = 32 << 20;

/// Keeps freed memory in the process instead of giving it back to the kernel
/// at once. glibc's malloc maps blocks above a threshold that starts at
/// 128 KiB and trims a heap whose free top exceeds another; either way the
/// next allocation of the same size touches fresh pages, and each first touch
/// is a page fault in which the kernel zeroes the page. A program that builds
/// a grid of 10^5 spheres every other Monte Carlo sweep faults millions of
/// times (measured in docs/record/PERFORMANCE.md, round 34). After this call blocks
/// up to kHeapBlockMax come from the heaps and the heaps are not trimmed, so
/// the process keeps its peak footprint until it exits. A no-op without
/// glibc. Call it once, at the start of a program, before its threads start.
inline void keep_freed_memory() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, kHeapBlockMax);
  mallopt(M_TRIM_THRESHOLD, 0x7fffffff);  // the largest value mallopt() takes: never trim
#endif
}

}  // namespace hgrid
