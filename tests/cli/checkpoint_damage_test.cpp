// --checkpoint files that are damaged (a flipped bit in any field, a truncation, a huge tile count
// behind a header made right again) are refused with exit 2 and one "damaged checkpoint" line,
// the output untouched; a periodic write that fails warns once and the render completes.
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>

#include <chrono>
#include <cstdlib>
#include <thread>

#include "cli/run_luz.h"

namespace luz::test {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

class CheckpointDamage : public TempDirTest {};

#if defined(__SANITIZE_ADDRESS__)
constexpr double kRefusalSeconds = 10;  // a sanitizer build starts slowly
#else
constexpr double kRefusalSeconds = 2;
#endif

// About 3 s on two threads of an idle machine (the default size).
std::vector<std::string> render_args(const std::string& checkpoint,
                                     const std::string& width = "1280",
                                     const std::string& height = "960") {
    return {"render", "demo:whitted", "--width", width,          "--height",  height,
            "--aa",   "grid",         "-o",      "out.png",      "--samples", "9",
            "-q",     "--stats",      "s.json",  "--checkpoint", checkpoint};
}

/// Starts luz with `args` in `cwd`, standard error into `err`; returns its pid.
pid_t start_luz(const std::vector<std::string>& args, const fs::path& cwd, const fs::path& err) {
    std::string binary = LUZ_BINARY;
    std::vector<char*> argv{binary.data()};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const pid_t pid = fork();
    if (pid == 0) {
        if (chdir(cwd.c_str()) != 0) _exit(126);
        const int fd = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(fd, STDERR_FILENO);
        freopen("/dev/null", "w", stdout);
        execv(binary.c_str(), argv.data());
        _exit(127);
    }
    return pid;
}

int wait_for(pid_t pid) {
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/// A checkpoint of an interrupted render (render.ckpt in `dir`): its bytes. Interrupted once its
/// periodic writes (every 0.1 s here) hold several tiles, however fast the build.
std::string interrupted_checkpoint(const fs::path& dir) {
    setenv("LUZ_CHECKPOINT_SECONDS", "0.1", 1);
    const pid_t pid = start_luz(render_args("render.ckpt"), dir, dir / "err.txt");
    unsetenv("LUZ_CHECKPOINT_SECONDS");
    const auto deadline = Clock::now() + std::chrono::seconds(60);
    const auto size = [&] {  // 0 until the first write
        std::error_code ec;
        const auto n = fs::file_size(dir / "render.ckpt", ec);
        return ec ? 0 : n;
    };
    int status = -1;  // until it ends by itself (it should not)
    while (size() < 16384 && Clock::now() < deadline && status == -1) {
        int st = 0;
        if (waitpid(pid, &st, WNOHANG) == pid)
            status = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    if (status == -1) {
        kill(pid, SIGINT);
        status = wait_for(pid);
    }
    EXPECT_EQ(status, 130) << read_file(dir / "err.txt");
    fs::remove(dir / "err.txt");
    return read_file(dir / "render.ckpt");
}

uint64_t get64(const std::string& b, size_t at) {
    uint64_t v = 0;
    for (int k = 0; k < 8; ++k) v |= uint64_t(static_cast<unsigned char>(b[at + k])) << (8 * k);
    return v;
}

void put64(std::string& b, size_t at, uint64_t v) {
    for (int k = 0; k < 8; ++k) b[at + k] = static_cast<char>((v >> (8 * k)) & 0xff);
}

/// Runs the render with `bytes` as its checkpoint and an older out.png: exit 2, one line that
/// begins "render.ckpt: --checkpoint: damaged checkpoint (", out.png and the file as they were.
void expect_refused(const fs::path& dir, const std::string& bytes, const std::string& what) {
    fs::remove(dir / "render.ckpt");  // a new file: truncating one makes ext4 write it to disk
    write_file(dir / "render.ckpt", bytes);
    write_file(dir / "out.png", "the previous picture");
    const RunResult r = run_luz(render_args("render.ckpt"), dir);
    EXPECT_EQ(r.status, 2) << what << ": " << r.err;
    EXPECT_EQ(r.err.rfind("render.ckpt: --checkpoint: damaged checkpoint (", 0), 0u)
        << what << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << what << ": " << r.err;
    EXPECT_EQ(read_file(dir / "out.png"), "the previous picture") << what;
    EXPECT_EQ(read_file(dir / "render.ckpt"), bytes) << what << ": left as it was";
    EXPECT_EQ(list_dir(dir), (std::set<std::string>{"out.png", "render.ckpt"})) << what;
}

// One bit of every field (the header's five, a tile's three and its bytes, the end's three) and
// truncations at each boundary. Byte 1051, bit 6 once gave a pixel of 1.19e38 and exit 0.
TEST_F(CheckpointDamage, AFlippedBitOrATruncationAnywhereIsRefused) {
    const std::string saved = interrupted_checkpoint(dir_);
    ASSERT_GT(saved.size(), 2000u);
    const size_t size1 = get64(saved, 48), tile2 = 64 + size1, end = saved.size() - 24;
    ASSERT_LT(tile2 + 24, end) << "at least two tiles";
    const std::vector<std::pair<size_t, int>> bits = {{1, 6},          {10, 0},
                                                      {17, 3},         {25, 5},
                                                      {33, 1},  // header
                                                      {40, 0},         {45, 7},
                                                      {49, 2},         {54, 6},
                                                      {57, 4},  // tile 1
                                                      {64, 0},         {64 + size1 / 2, 3},
                                                      {tile2 - 1, 7},  {1051, 6},  // its bytes
                                                      {tile2 + 2, 1},  {tile2 + 9, 0},
                                                      {tile2 + 20, 5},  // tile 2
                                                      {end, 0},        {end + 7, 7},
                                                      {end + 8, 0},    {end + 17, 2},
                                                      {end + 23, 1}};
    for (const auto& [byte, bit] : bits) {
        std::string bytes = saved;
        bytes[byte] = static_cast<char>(bytes[byte] ^ (1 << bit));
        expect_refused(dir_, bytes,
                       "bit " + std::to_string(bit) + " of byte " + std::to_string(byte));
    }
    for (size_t size : {size_t{0}, size_t{5}, size_t{8}, size_t{39}, size_t{40}, size_t{63},
                        tile2 - 1, tile2, tile2 + 24, end, saved.size() - 1}) {
        expect_refused(dir_, saved.substr(0, size), std::to_string(size) + " bytes");
    }
}

// A tile count made huge behind a header checksum made right again is compared with the
// render's own count before anything is allocated: once bit 27 cost 5.3 GB and 13.6 s, bit 31
// ended in std::bad_alloc (exit 1). Under a 3 GB address-space limit, in well under 2 s, and
// no run of luz here peaks above 1 GiB.
TEST_F(CheckpointDamage, AHugeTileCountIsRefusedWithoutAllocating) {
    const std::string saved = interrupted_checkpoint(dir_);
    ASSERT_GT(saved.size(), 40u);
    rlimit old{};
    getrlimit(RLIMIT_AS, &old);
#if !defined(__SANITIZE_ADDRESS__)  // AddressSanitizer reserves terabytes of address space
    rlimit limited = old;
    limited.rlim_cur = 3ull << 30;
    ASSERT_EQ(setrlimit(RLIMIT_AS, &limited), 0);  // inherited by luz
#endif
    for (int bit : {27, 31}) {
        std::string bytes = saved;
        const uint64_t count = get64(saved, 24) | (uint64_t{1} << bit);
        put64(bytes, 24, count);
        put64(bytes, 32, crc32(0, reinterpret_cast<const Bytef*>(bytes.data()), 32));
        const auto start = Clock::now();
        expect_refused(dir_, bytes, "count bit " + std::to_string(bit));
        const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
        EXPECT_LT(seconds, kRefusalSeconds) << "bit " << bit;
        RecordProperty("seconds_bit_" + std::to_string(bit), std::to_string(seconds));
    }
    setrlimit(RLIMIT_AS, &old);
    rusage children{};
    getrusage(RUSAGE_CHILDREN, &children);
    EXPECT_LT(children.ru_maxrss, 1024 * 1024) << "KiB at the peak of a luz run";
}

// The periodic write fails (its folder replaced by a file mid-render: chmod would not stop
// root): one warning, and the render completes with its output; the checkpoint is not there.
// Written every 0.05 s, a quarter of the picture (about 0.3 s) still has several writes to try.
TEST_F(CheckpointDamage, AFailedPeriodicWriteWarnsOnceAndTheRenderCompletes) {
    fs::create_directory(dir_ / "sub");
    // Beside the folder, named after it: /tmp/e.txt was shared by concurrent runs of the test.
    const fs::path err_path = dir_.parent_path() / (dir_.filename().string() + ".err");
    setenv("LUZ_CHECKPOINT_SECONDS", "0.05", 1);
    const pid_t pid = start_luz(render_args("sub/render.ckpt", "640", "480"), dir_, err_path);
    unsetenv("LUZ_CHECKPOINT_SECONDS");
    const auto deadline = Clock::now() + std::chrono::seconds(30);
    while (!fs::exists(dir_ / "sub/render.ckpt") && Clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    const bool saved = fs::exists(dir_ / "sub/render.ckpt");
    fs::rename(dir_ / "sub", dir_ / "old");
    write_file(dir_ / "sub", "a file where the folder was");
    const int status = wait_for(pid);
    const std::string err = read_file(err_path);
    fs::remove(err_path);
    ASSERT_TRUE(saved) << "no periodic write within 30 s: " << err;
    EXPECT_EQ(status, 0) << err;
    EXPECT_EQ(err,
              "luz: warning: sub/render.ckpt: cannot write: Not a directory (--checkpoint not "
              "saved; the render goes on, trying again every 0.05 s)\n");
    EXPECT_TRUE(fs::exists(dir_ / "out.png"));
    EXPECT_TRUE(fs::exists(dir_ / "s.json"));
}

}  // namespace
}  // namespace luz::test
