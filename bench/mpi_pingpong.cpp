// The costs docs/SCALING.md's model starts from, on this machine: the round trip of a request
// (8 bytes) answered by a reply, of a tile-sized message (3 KiB), and rank 0's receive
// bandwidth for large messages. Run: mpirun -np 2 build/native/bench/mpi_pingpong
#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <vector>

namespace {

/// Median seconds of a round trip of `bytes` each way, over `reps` trips (after a warm-up).
double round_trip(int rank, int bytes, int reps) {
    std::vector<char> buf(static_cast<size_t>(std::max(bytes, 1)));
    std::vector<double> t;
    for (int r = 0; r < reps + 10; ++r) {
        MPI_Barrier(MPI_COMM_WORLD);
        const double t0 = MPI_Wtime();
        if (rank == 0) {
            MPI_Send(buf.data(), bytes, MPI_BYTE, 1, 1, MPI_COMM_WORLD);
            MPI_Recv(buf.data(), bytes, MPI_BYTE, 1, 2, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        } else if (rank == 1) {
            MPI_Recv(buf.data(), bytes, MPI_BYTE, 0, 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
            MPI_Send(buf.data(), bytes, MPI_BYTE, 0, 2, MPI_COMM_WORLD);
        }
        if (r >= 10) t.push_back(MPI_Wtime() - t0);
    }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    MPI_Init(&argc, &argv);
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    if (size < 2) {
        if (rank == 0) std::fprintf(stderr, "mpi_pingpong: run with mpirun -np 2\n");
        MPI_Finalize();
        return 1;
    }
    const double small = round_trip(rank, 8, 2000);
    const double tile = round_trip(rank, 3200, 2000);
    // Bandwidth: 64 MiB sent 1 → 0 in 1 MiB messages.
    const int chunk = 1 << 20, chunks = 64;
    std::vector<char> buf(chunk);
    MPI_Barrier(MPI_COMM_WORLD);
    const double t0 = MPI_Wtime();
    for (int i = 0; i < chunks; ++i) {
        if (rank == 1) MPI_Send(buf.data(), chunk, MPI_BYTE, 0, 3, MPI_COMM_WORLD);
        if (rank == 0)
            MPI_Recv(buf.data(), chunk, MPI_BYTE, 1, 3, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    }
    MPI_Barrier(MPI_COMM_WORLD);
    const double seconds = MPI_Wtime() - t0;
    if (rank == 0) {
        std::printf("round_trip_8B_us      %.2f\n", small * 1e6);
        std::printf("round_trip_3200B_us   %.2f\n", tile * 1e6);
        std::printf("bandwidth_GBps        %.2f\n", double(chunk) * chunks / seconds / 1e9);
    }
    MPI_Finalize();
    return 0;
}
