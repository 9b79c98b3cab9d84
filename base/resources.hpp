#pragma once
// The resources every long command budgets: memory and disk.
//
// Memory: commands estimate what a request needs before they start (points of a window, pixels
// of an image, states of a search) and refuse what cannot fit with exit 2 and a message naming
// the limit and how to raise it, instead of running for seconds and ending in std::bad_alloc
// or the kernel's OOM killer. The limit is TILEKIT_MEMORY (bytes, or with a K, M, G or T
// suffix) when set, else half of the memory this process can have: the machine's physical
// memory, or the cgroup's memory.max (a Slurm job, a container) when that is lower.
//
// Time: the Deadline of base/run_control.hpp.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace tilekit {

std::uint64_t memory_limit();

// Throws InputError "WHAT needs about X GiB of memory, more than the limit of Y GiB (half of
// this machine's memory; set TILEKIT_MEMORY=... to raise it)" when `bytes` exceeds it.
void require_memory(double bytes, std::string_view what);

// Throws InputError "WHAT needs about X GiB on disk, more than the Y GiB free in DIR" when
// `bytes` exceed the space free to this user in the folder that will hold `path` (a file
// streamed to disk, where memory no longer bounds it). Nothing is checked where the folder
// cannot be asked (it is then the write that fails, with the same exit code).
void require_disk(const std::string& path, double bytes, std::string_view what);

// Asks the kernel to back [p, p + bytes) with huge pages (Linux transparent huge pages in
// "madvise" mode): a fresh output buffer of hundreds of megabytes then takes a few hundred page
// faults instead of one per 4 KiB, which is most of the cost of writing it once. Only advice:
// does nothing below 8 MiB, on other systems, or where the kernel declines.
void advise_huge_pages(void* p, std::size_t bytes);

}  // namespace tilekit
