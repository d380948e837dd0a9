// The `luz` command. Under mpirun (Open MPI sets OMPI_COMM_WORLD_SIZE), `luz render` becomes
// `luz-mpi render` from the same folder (docs/DISTRIBUTED.md), so that this binary never links MPI
// and starts as fast as ever.
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include "app/cli_main.h"

namespace {

/// Under mpirun with `render`: replaces this process by luz-mpi (returns only when it cannot).
void become_luz_mpi_under_mpirun(int argc, char** argv) {
    if (!std::getenv("OMPI_COMM_WORLD_SIZE") || argc < 2 || std::strcmp(argv[1], "render") != 0)
        return;
    std::error_code ec;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) {  // never render N copies of the whole image
        luz::print_error_line("luz: under mpirun, but cannot find luz-mpi: /proc/self/exe: " +
                              ec.message());
        std::exit(1);
    }
    const std::string mpi = (self.parent_path() / "luz-mpi").string();
    if (::access(mpi.c_str(), X_OK) != 0) {
        const char* size = std::getenv("OMPI_COMM_WORLD_SIZE");
        if (std::strcmp(size, "1") == 0) return;  // one process: render as usual
        const char* rank = std::getenv("OMPI_COMM_WORLD_RANK");
        if (!rank || std::strcmp(rank, "0") == 0) {
            luz::print_error_line("luz: under mpirun, but luz was built without MPI (no " + mpi +
                                  "; install libopenmpi-dev and rebuild)");
        }
        std::exit(1);
    }
    argv[0] = const_cast<char*>(mpi.c_str());
    ::execv(mpi.c_str(), argv);
    luz::print_error_line("luz: cannot run " + mpi + ": " + std::strerror(errno));
    std::exit(1);  // never render N copies of the whole image
}

}  // namespace

int main(int argc, char** argv) {
    become_luz_mpi_under_mpirun(argc, argv);
    return luz::luz_main(argc, argv, nullptr);
}
