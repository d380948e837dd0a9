// What writing an output does to what is at its path: a regular file is replaced keeping its
// mode, a symlink is written through, a device, FIFO or descriptor is written as a stream and
// never replaced, a folder is refused; files committed together fail together.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <filesystem>
#include <thread>

#include "fifo_reader.h"
#include "image/atomic_file.h"
#include "temp_dir.h"

namespace luz {
namespace {

using test::put_file;
using test::slurp;
using test::TempDir;
using Names = std::vector<std::string>;
namespace fs = std::filesystem;

mode_t mode_of(const std::string& path) {
    struct stat st {};
    return ::lstat(path.c_str(), &st) == 0 ? st.st_mode : 0;
}

/// Everything that comes out of the read end `fd` until it is closed.
std::string drain(int fd) {
    std::string got;
    char buffer[4096];
    for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) > 0;) got.append(buffer, n);
    return got;
}

TEST(OutputKinds, SymlinkIsWrittenThroughToItsTarget) {
    TempDir dir;
    fs::create_directory(dir / "store");
    put_file(dir / "store/real.png", "old");
    fs::create_symlink("store/real.png", dir / "link.png");
    write_file_atomically(dir / "link.png", "new");
    EXPECT_TRUE(fs::is_symlink(dir / "link.png"));
    EXPECT_EQ(slurp(dir / "store/real.png"), "new");
    EXPECT_EQ(dir.entries(), (Names{"link.png", "store"}));
    EXPECT_EQ(dir.entries("store"), Names{"real.png"});  // the temporary file went there
}

TEST(OutputKinds, RelativeSymlinkChainAndDanglingLinkCreateTheirTarget) {
    TempDir dir;
    fs::create_directory(dir / "a");
    fs::create_symlink("../b.png", dir / "a/one.png");  // a/one.png → b.png → c.png (none yet)
    fs::create_symlink("c.png", dir / "b.png");
    write_file_atomically(dir / "a/one.png", "made");
    EXPECT_TRUE(fs::is_symlink(dir / "a/one.png"));
    EXPECT_TRUE(fs::is_symlink(dir / "b.png"));
    EXPECT_EQ(slurp(dir / "c.png"), "made");
}

TEST(OutputKinds, SymlinkLoopIsRefusedAndChangesNothing) {
    TempDir dir;
    fs::create_symlink("y.png", dir / "x.png");
    fs::create_symlink("x.png", dir / "y.png");
    try {
        write_file_atomically(dir / "x.png", "bytes");
        ADD_FAILURE() << "no error";
    } catch (const FileError& e) {
        EXPECT_EQ(std::string(e.what()),
                  dir / "x.png" + ": cannot write: Too many levels of symbolic links");
    }
    EXPECT_EQ(dir.entries(), (Names{"x.png", "y.png"}));
}

TEST(OutputKinds, ReplacedFileKeepsItsMode) {
    TempDir dir;
    for (const mode_t mode : {0600u, 0640u, 0755u}) {
        put_file(dir / "out.png", "old");
        ASSERT_EQ(::chmod((dir / "out.png").c_str(), mode), 0);
        write_file_atomically(dir / "out.png", "new");
        EXPECT_EQ(mode_of(dir / "out.png") & 07777, mode);
        EXPECT_EQ(slurp(dir / "out.png"), "new");
    }
}

// Replacing is atomic, so the path gets a new inode: other hard links keep the old version
// (as with mv, rsync or an editor's safe save); docs/CLI.md#output-paths says so.
TEST(OutputKinds, HardLinkedFileIsReplacedAndTheOtherNameKeepsTheOldVersion) {
    TempDir dir;
    put_file(dir / "out.png", "old");
    fs::create_hard_link(dir / "out.png", dir / "other.png");
    write_file_atomically(dir / "out.png", "new");
    EXPECT_EQ(slurp(dir / "out.png"), "new");
    EXPECT_EQ(slurp(dir / "other.png"), "old");
}

TEST(OutputKinds, FolderIsRefusedBeforeAnythingIsWritten) {
    TempDir dir;
    fs::create_directory(dir / "out.png");
    fs::create_symlink("out.png", dir / "link.png");
    for (const char* name : {"out.png", "link.png"}) {
        try {
            PendingFile file(dir / name, std::string("bytes"));
            ADD_FAILURE() << "no error for " << name;
        } catch (const FileError& e) {
            EXPECT_EQ(std::string(e.what()), dir / name + ": cannot write: is a folder");
        }
    }
    EXPECT_EQ(dir.entries(), (Names{"link.png", "out.png"}));
    EXPECT_EQ(dir.entries("out.png"), Names{});
}

// As root (CI, containers) a device node is as easy to replace as a file: /dev/null became a
// JSON file. A twin of /dev/null made here must stay a device.
TEST(OutputKinds, DeviceIsWrittenToAndNeverReplaced) {
    TempDir dir;
    if (::mknod((dir / "null.png").c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0)
        GTEST_SKIP() << "cannot make a device node here (not root)";
    write_file_atomically(dir / "null.png", "bytes");
    EXPECT_TRUE(S_ISCHR(mode_of(dir / "null.png")));
    EXPECT_EQ(dir.entries(), Names{"null.png"});
}

TEST(OutputKinds, FifoIsStreamedToItsReaderAndStays) {
    TempDir dir;
    ASSERT_EQ(::mkfifo((dir / "out.png").c_str(), 0600), 0);
    FifoReader reader(dir / "out.png");
    const std::string bytes(300000, 'x');  // more than a pipe holds
    write_file_atomically(dir / "out.png", bytes);
    EXPECT_EQ(reader.finish(), bytes);
    EXPECT_TRUE(S_ISFIFO(mode_of(dir / "out.png")));
    EXPECT_EQ(dir.entries(), Names{"out.png"});
}

TEST(OutputKinds, FifoWithoutReaderWaitsUntilCancelled) {
    TempDir dir;
    ASSERT_EQ(::mkfifo((dir / "out.png").c_str(), 0600), 0);
    std::atomic<bool> cancel{false};
    PendingFile file(dir / "out.png", std::string("bytes"));
    EXPECT_TRUE(file.is_stream());
    std::thread stop([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
        cancel.store(true);
    });
    const auto start = std::chrono::steady_clock::now();
    EXPECT_THROW(file.commit(&cancel), WriteCancelled);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stop.join();
    EXPECT_LT(seconds, 1.0);
    EXPECT_TRUE(S_ISFIFO(mode_of(dir / "out.png")));
}

// /dev/stdout, /dev/fd/N and >(cmd) name a descriptor: its pipe gets the bytes, nothing is
// renamed onto /proc.
TEST(OutputKinds, DescriptorPathWritesToTheDescriptor) {
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    std::string got;
    std::thread reader([&] { got = drain(fds[0]); });
    for (const std::string prefix : {"/dev/fd/", "/proc/self/fd/"})
        write_file_atomically(prefix + std::to_string(fds[1]), "[" + prefix + "]");
    ::close(fds[1]);
    reader.join();
    ::close(fds[0]);
    EXPECT_EQ(got, "[/dev/fd/][/proc/self/fd/]");
}

// A reader gone away is an error for that output, not a SIGPIPE that ends the process.
TEST(OutputKinds, PipeWithoutReaderIsAnErrorNotASignal) {
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    ::close(fds[0]);
    const std::string path = "/dev/fd/" + std::to_string(fds[1]);
    try {
        write_file_atomically(path, "bytes");
        ADD_FAILURE() << "no error";
    } catch (const FileError& e) {
        EXPECT_EQ(std::string(e.what()), path + ": cannot write: Broken pipe");
    }
    ::close(fds[1]);
}

// Streams are written before any file is renamed: a pipe without a reader leaves the files as
// they were. (Tests never name /dev/full or /dev/stdout themselves: a regression would
// replace the machine's.)
TEST(OutputKinds, StreamThatFailsLeavesTheFilesCommittedWithIt) {
    TempDir dir;
    put_file(dir / "a.png", "old");
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    ::close(fds[0]);
    {
        PendingFile image(dir / "a.png", std::string("new"));
        PendingFile stats("/dev/fd/" + std::to_string(fds[1]), std::string("{}"));
        EXPECT_THROW(commit_together({&image, &stats}), FileError);
    }
    ::close(fds[1]);
    EXPECT_EQ(slurp(dir / "a.png"), "old");
    EXPECT_EQ(dir.entries(), Names{"a.png"});
}

}  // namespace
}  // namespace luz
