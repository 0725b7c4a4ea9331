#include <unistd.h>

#include <iostream>

#include "cli.hpp"

int main(int argc, char** argv) {
    return exemplar::cli::run_cli(argc, argv, std::cout, std::cerr, isatty(STDERR_FILENO) != 0);
}
