// luz-mpi: `luz render` across the processes of `mpirun -np N` (docs/DISTRIBUTED.md). `luz` runs it
// when started by mpirun (app/main.cpp). Rank 0 runs the ordinary command line, reading the
// scene and its files as ever while keeping a copy (a file observer); before its first frame it
// sends them to every other process (scene_bundle.h); each frame's tiles are then shared
// (mpi_tile_share.h) and gathered on rank 0, which alone writes files and draws the progress bar.
// The others load the same scene from what rank 0 sent and follow it frame by frame, silently;
// a process that stops answering ends the run (heartbeat.h).
#include <mpi.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <climits>
#include <csignal>
#include <cstdio>
#include <string>
#include <thread>

#include "app/cli_main.h"
#include "app/cli_options.h"
#include "app/signals.h"
#include "luz/animation.h"
#include "luz/luz.h"
#include "luz/memory.h"
#include "luz/options.h"
#include "mpi/heartbeat.h"
#include "mpi/mpi_tile_share.h"
#include "mpi/scene_bundle.h"
#include "mpi/wire.h"

namespace luz::mpi {
namespace {

/// Rank 0 → all: the bundle (its size, then its bytes).
void broadcast_bundle(const SceneBundle& b) {
    std::string bytes = encode(b);
    uint64_t size = bytes.size();
    MPI_Bcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
    for (uint64_t at = 0; at < size; at += 1u << 30) {
        const int n = static_cast<int>(std::min<uint64_t>(size - at, 1u << 30));
        MPI_Bcast(bytes.data() + at, n, MPI_BYTE, 0, MPI_COMM_WORLD);
    }
}

std::string receive_bundle_bytes() {
    uint64_t size = 0;
    MPI_Bcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
    std::string bytes(size, '\0');
    for (uint64_t at = 0; at < size; at += 1u << 30) {
        const int n = static_cast<int>(std::min<uint64_t>(size - at, 1u << 30));
        MPI_Bcast(bytes.data() + at, n, MPI_BYTE, 0, MPI_COMM_WORLD);
    }
    return bytes;
}

/// The processes' heartbeat (heartbeat.h), or null when LUZ_MPI_TIMEOUT is 0.
Heartbeat* g_heart = nullptr;

/// Rank 0: render(), stopped when a process is lost (the heartbeat); then what is done is kept
/// in the --checkpoint and the run ends with the message naming the process.
Frame render_watched(const Scene& scene, const SceneDesc& desc, RenderOptions options,
                     const EngineHooks& hooks) {
    if (!g_heart) return render(scene, desc, options, hooks);
    options.cancel = g_heart->begin_render(options.cancel);
    Frame frame;
    try {
        frame = render(scene, desc, options, hooks);
    } catch (...) {
        g_heart->end_render();
        throw;
    }
    if (const std::optional<std::string> lost = g_heart->end_render()) {
        if (hooks.checkpoint) hooks.checkpoint->save();
        throw std::runtime_error(*lost);
    }
    return frame;
}

/// One frame with its tiles shared among the processes; `passes` numbers the message tags.
Frame render_shared(const Scene& scene, const SceneDesc& desc, const RenderOptions& options,
                    EngineHooks hooks, int& passes) {
    MpiTileShare share(MPI_COMM_WORLD, passes);
    hooks.share = &share;
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    Frame frame = rank == 0 ? render_watched(scene, desc, options, hooks)
                            : render(scene, desc, options, hooks);
    passes += share.passes() + 1;
    int size = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    frame.stats.processes = size;
    frame.stats.primary_rays_by_process = share.primary_rays_by_process();
    frame.stats.mpi_messages = share.wire().messages;
    frame.stats.mpi_tiles_received = share.wire().tiles;
    frame.stats.mpi_tile_bytes_received = share.wire().tile_bytes;
    frame.stats.mpi_broadcast_bytes = share.wire().broadcast_bytes;
    return frame;
}

int run_rank0(int argc, char** argv) {
    SceneBundle bundle;
    set_file_observer(recorder(bundle));
    bool sent = false;
    int passes = 0;
    FrameRenderer render_frame;
    render_frame.whole = [&](const Scene& scene, const SceneDesc& desc,
                             const RenderOptions& options, const EngineHooks& hooks) {
        if (!sent) {
            // mpirun binds each process to cores (Open MPI: one core each when -np ≤ 2):
            // --threads beyond them share those cores.
            const int cores = render_threads(0);
            if (options.threads > cores) {
                std::fprintf(stderr,
                             "luz: warning: --threads %d, but mpirun bound this process to %d "
                             "core%s (mpirun --bind-to none, or --map-by ...:PE=%d)\n",
                             options.threads, cores, cores == 1 ? "" : "s", options.threads);
            }
            broadcast_bundle(bundle);  // status -1: render
            sent = true;
        }
        return render_shared(scene, desc, options, hooks, passes);
    };
    // A shared render is never rendered in bands: the whole image, then its PNG file.
    render_frame.png = [&](const Scene& scene, const SceneDesc& desc, const RenderOptions& options,
                           Encoding encoding, const EngineHooks& hooks) {
        const Frame frame = render_frame.whole(scene, desc, options, hooks);
        PngFrame png;
        png.stats = frame.stats;
        png.complete = frame.complete;
        if (png.complete) png.png = encode_image("frame.png", frame.image, encoding);
        return png;
    };
    const int status = luz_main(argc, argv, &render_frame);
    if (!sent) {  // stopped before rendering: everyone exits with this status, silently
        bundle.files.clear();
        bundle.status = status;
        broadcast_bundle(bundle);
        return status;
    }
    // Failed or interrupted while the others render: end them all (the message is printed).
    if (status != 0) MPI_Abort(MPI_COMM_WORLD, status);
    return status;
}

/// Set by SIGINT and SIGTERM in the processes other than rank 0: their render stops (it is the
/// render's cancel flag), and nothing else happens (see run_other()).
std::atomic<bool> g_stop{false};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void on_stop_signal(int) { g_stop.store(true); }

/// The frames of `o`, rendered in step with rank 0 until the run ends or a signal stops this
/// process; nothing is written.
void follow_rank0(const RenderArgs& o) {
    const std::vector<Override> overrides = overrides_of(o);
    set_memory_limit(o.max_memory ? *o.max_memory : default_memory_limit());
    const Animation animation = Animation::load(o.scene, overrides);
    const SceneDesc& first = animation.first();
    const FrameRange range = o.frames ? parse_frames(*o.frames, animation) : FrameRange{};
    RenderOptions options;
    options.threads = o.threads;
    options.cancel = &g_stop;
    options.want_aa_mask = !o.aa_mask_file.empty();
    if (!o.aovs.empty()) options.aovs = parse_aov_list(o.aovs, "--aov " + o.aovs);
    if (o.region) options.region = parse_region(*o.region, first.image);
    Scene scene;
    SceneDesc built_from;
    int passes = 0;
    for (int f = range.first; f < range.end && !g_stop.load(); ++f) {
        const SceneDesc desc = f == 0 ? first : animation.frame(f);
        if (!scene || needs_rebuild(built_from, desc)) {
            scene = build(desc);
            built_from = desc;
        }
        render_shared(scene, desc, options, EngineHooks{}, passes);
    }
}

int run_other(int argc, char** argv, int rank, int size) {
    // Interruption is rank 0's to decide: it keeps its --checkpoint, says "interrupted" and
    // ends the run (MPI_Abort), and mpirun then kills the others. mpirun signals every
    // process at once (SIGINT to mpirun, or ending a failed run), and kills them one second
    // later: here a signal only stops the render, silently, so that rank 0 has both cores
    // for keeping what is done, and no process ends before it or prints anything.
    install_stop_handler(on_stop_signal);
    const std::string who = "luz: process " + std::to_string(rank) + " of " + std::to_string(size);
    SceneBundle bundle;
    try {
        bundle = decode_bundle(receive_bundle_bytes());
    } catch (const WireError& e) {
        print_error_line(who + ": cannot read what rank 0 sent: " + e.what());
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
    if (bundle.status != -1) return bundle.status;  // rank 0 has said why
    set_file_source(bundle_source(bundle));
    try {
        CLI::App app{"luz-mpi", "luz"};
        RenderArgs o;
        add_render_options(*app.add_subcommand("render"), o);
        app.require_subcommand(1);
        app.parse(argc, argv);
        follow_rank0(o);
        if (g_stop.load()) {
            // Stopped by a signal: rank 0 ends the run (MPI_Abort) once it has kept what is
            // done. Had only this process been signalled, it ends the run itself, later.
            const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
            while (std::chrono::steady_clock::now() < deadline)
                std::this_thread::sleep_for(std::chrono::milliseconds(20));
            MPI_Abort(MPI_COMM_WORLD, 1);
        }
        return 0;
    } catch (const std::exception& e) {
        // Rank 0 read the same scene without error: what this process got differs.
        print_error_line(who + ": " + e.what());
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
    return 1;
}

}  // namespace
}  // namespace luz::mpi

int main(int argc, char** argv) {
    // Multiple: the heartbeat's thread sends and receives while the others render (their calls
    // stay serialized among themselves, see mpi_tile_share.cpp).
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_MULTIPLE, &provided);
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    if (provided < MPI_THREAD_SERIALIZED) {
        if (rank == 0) luz::print_error_line("luz: this MPI library cannot serve threads");
        MPI_Finalize();
        return 1;
    }
    double timeout = 0;
    try {
        timeout = luz::mpi::heartbeat_timeout();
    } catch (const std::invalid_argument& e) {
        if (rank == 0) luz::print_error_line(std::string("luz: ") + e.what());
        MPI_Finalize();
        return 2;
    }
    if (provided < MPI_THREAD_MULTIPLE && timeout > 0) {
        if (rank == 0) {
            luz::print_error_line(
                "luz: warning: this MPI library has no MPI_THREAD_MULTIPLE: a process that stops "
                "answering is not noticed (LUZ_MPI_TIMEOUT)");
        }
        timeout = 0;
    }
    luz::mpi::Heartbeat heart(MPI_COMM_WORLD, timeout);
    luz::mpi::g_heart = timeout > 0 ? &heart : nullptr;
    const int status =
        rank == 0 ? luz::mpi::run_rank0(argc, argv) : luz::mpi::run_other(argc, argv, rank, size);
    luz::mpi::g_heart = nullptr;
    heart.finish();  // every message received: nothing left for MPI_Finalize
    // This process's part is over. Once one process exits non-zero, mpirun ends the others with
    // SIGTERM (they may still be in MPI_Finalize): that must end them silently, not print
    // "luz: interrupted" after the one message rank 0 printed.
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    MPI_Finalize();
    return status;
}
