#include <malloc.h>
#include <unistd.h>

#include <iostream>

#include "cli.hpp"

int main(int argc, char** argv) {
    // Blocks of 128 KiB and more are mapped and unmapped on their own (glibc's initial mmap
    // threshold, kept fixed). By default glibc raises the threshold to the size of each large
    // block freed, after which images and fields come from the heap, whose freed holes the
    // next level's buffers do not always fit: peak memory 2.2 MiB higher on 0.15 Mpx examples,
    // 22 MiB on stylit (docs/PERFORMANCE.md, "Libraries loaded on first use"). The process is
    // the CLI's, so the policy is set here, never in the library.
    mallopt(M_MMAP_THRESHOLD, 128 * 1024);
    return exemplar::cli::run_cli(argc, argv, std::cout, std::cerr, isatty(STDERR_FILENO) != 0);
}
