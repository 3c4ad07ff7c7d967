// Large heap blocks on transparent huge pages, for the programs (faultline-app, the benches).
//
// Debian's kernels give transparent huge pages only to memory marked with madvise, and glibc's
// malloc marks its memory only when the process starts with GLIBC_TUNABLES holding
// glibc.malloc.hugetlb=1. Without it, every frame's columns are faulted in 4 KiB at a time,
// and in a virtual machine a page fault costs several microseconds: scrubbing the demo (205k
// spheres) a frame read from the frame cache took ~40 ms, of which ~5 were reading; 14 ms with
// the tunable (bench_strain --demo-only). The memory and its freeing are malloc's as before.
// Not for the Python module: a library leaves its host process's allocator alone.
#pragma once

namespace faultline::core {

// Adds glibc.malloc.hugetlb=1 to GLIBC_TUNABLES (for this process's children: it takes effect
// at a program's start) unless FAULTLINE_HUGE_PAGES=0, the tunable is set already, the kernel
// has no transparent huge pages in madvise mode (with "always" they are on already), or this is
// a sanitizer build. True when it added it.
bool addMallocHugePagesTunable();

// At the top of main: when addMallocHugePagesTunable() adds the tunable, runs this program
// again (/proc/self/exe, the same argv) so that its malloc reads it. Returns when nothing was
// added, or when the exec fails (the program then runs as it was started).
void restartWithMallocHugePages(char** argv);

} // namespace faultline::core
