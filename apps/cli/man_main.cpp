// Writes the manual pages of `exemplar` (cli.hpp: man_pages) into a folder, one NAME.1 file per
// page: the build runs it, `cmake --install` installs the pages.
#include <cstdio>
#include <fstream>
#include <string>

#include "cli.hpp"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: exemplar_man OUT_FOLDER\n");
        return 2;
    }
    for (const auto& [name, page] : exemplar::cli::man_pages()) {
        const std::string file = std::string(argv[1]) + "/" + name + ".1";
        std::ofstream out(file);
        out << page;
        if (!out) {
            std::fprintf(stderr, "exemplar_man: cannot write %s\n", file.c_str());
            return 1;
        }
    }
    return 0;
}
