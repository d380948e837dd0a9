// write_image is atomic (docs/CLI.md): a failed write leaves no file behind and never touches an
// existing one; a successful write replaces the file and leaves no temporary file.

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <random>

#include "image/atomic_file.h"
#include "image/image_io.h"
#include "temp_dir.h"

namespace luz {
namespace {

using test::put_file;
using test::slurp;
using test::TempDir;
using Names = std::vector<std::string>;

const Image small(3, 2, Rgb{0.25f, 0.5f, 0.75f});

/// write_image(path, img) throws ImageError with exactly `message`.
void expect_write_error(const std::string& path, const Image& img, const std::string& message) {
    try {
        write_image(path, img);
        ADD_FAILURE() << "no error writing " << path;
    } catch (const ImageError& e) {
        EXPECT_EQ(std::string(e.what()), message);
    }
}

class AtomicWrite : public ::testing::TestWithParam<std::string> {
  protected:
    std::string name(const std::string& stem) const { return stem + "." + GetParam(); }
};

TEST_P(AtomicWrite, LeavesOnlyTheFileAfterSuccess) {
    TempDir dir;
    write_image(dir / name("out"), small);
    EXPECT_EQ(dir.entries(), Names{name("out")});
    EXPECT_GT(std::filesystem::file_size(dir / name("out")), 0u);
}

TEST_P(AtomicWrite, ReplacesAnExistingFile) {
    TempDir dir;
    put_file(dir / name("out"), "old content");
    write_image(dir / name("out"), small);
    EXPECT_NE(slurp(dir / name("out")), "old content");
    EXPECT_EQ(read_image(dir / name("out")).width, 3);
    EXPECT_EQ(dir.entries(), Names{name("out")});
}

TEST_P(AtomicWrite, MissingDirectoryThrowsAndLeavesNothing) {
    TempDir dir;
    const std::string path = dir / ("missing/" + name("x"));
    expect_write_error(path, small, path + ": cannot write: No such file or directory");
    EXPECT_FALSE(std::filesystem::exists(dir / "missing"));
    EXPECT_EQ(dir.entries(), Names{});
}

TEST_P(AtomicWrite, ParentIsARegularFile) {
    TempDir dir;
    put_file(dir / "file", "keep me");
    const std::string path = dir / ("file/" + name("x"));
    expect_write_error(path, small, path + ": cannot write: Not a directory");
    EXPECT_EQ(slurp(dir / "file"), "keep me");
    EXPECT_EQ(dir.entries(), Names{"file"});
}

TEST_P(AtomicWrite, FailedRenameKeepsTheTargetAndRemovesTheTemporary) {
    TempDir dir;
    // The target is a non-empty directory: the temporary file is written, the rename fails.
    std::filesystem::create_directory(dir / name("out"));
    put_file(dir / (name("out") + "/inside"), "keep me");
    EXPECT_THROW(write_image(dir / name("out"), small), ImageError);
    EXPECT_EQ(dir.entries(), Names{name("out")});
    EXPECT_EQ(slurp(dir / (name("out") + "/inside")), "keep me");
}

/// Limits the size of files this process may write (write() then fails with EFBIG).
class FileSizeLimit {
  public:
    explicit FileSizeLimit(rlim_t bytes) {
        old_handler_ = std::signal(SIGXFSZ, SIG_IGN);
        ::getrlimit(RLIMIT_FSIZE, &old_);
        rlimit limit = old_;
        limit.rlim_cur = bytes;
        ::setrlimit(RLIMIT_FSIZE, &limit);
    }
    ~FileSizeLimit() {
        ::setrlimit(RLIMIT_FSIZE, &old_);
        std::signal(SIGXFSZ, old_handler_);
    }

  private:
    rlimit old_{};
    void (*old_handler_)(int) = nullptr;
};

TEST_P(AtomicWrite, FailureWhileWritingKeepsTheExistingFile) {
    // The disk "fills up" in the middle of the file: a writer that truncated the target first
    // would destroy it.
    TempDir dir;
    put_file(dir / name("out"), "old content");
    Image noisy(64, 64);  // random values, so that no format compresses it below the limit
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (Rgb& p : noisy.pixels) p = Rgb{u(rng), u(rng), u(rng)};
    try {
        FileSizeLimit limit(1000);
        write_image(dir / name("out"), noisy);
        ADD_FAILURE() << "no error";
    } catch (const ImageError& e) {
        EXPECT_EQ(std::string(e.what()), dir / name("out") + ": cannot write: File too large");
    }
    EXPECT_EQ(slurp(dir / name("out")), "old content");
    EXPECT_EQ(dir.entries(), Names{name("out")});
}

TEST_P(AtomicWrite, EmptyImageThrowsAndKeepsTheExistingFile) {
    TempDir dir;
    put_file(dir / name("out"), "old content");
    for (const Image& empty : {Image(), Image(0, 5), Image(5, 0)}) {
        EXPECT_THROW(write_image(dir / name("out"), empty), ImageError);
    }
    EXPECT_EQ(slurp(dir / name("out")), "old content");
    EXPECT_EQ(dir.entries(), Names{name("out")});
    EXPECT_THROW(write_image(dir / name("new"), Image()), ImageError);
    EXPECT_EQ(dir.entries(), Names{name("out")});
}

TEST_P(AtomicWrite, InconsistentImageThrows) {
    TempDir dir;
    Image bad(4, 4);
    bad.pixels.resize(10);
    EXPECT_THROW(write_image(dir / name("out"), bad), ImageError);
    EXPECT_EQ(dir.entries(), Names{});
}

TEST_P(AtomicWrite, NewFileGetsTheUsualPermissions) {
    // A temporary file made by mkstemp would be 0600: the result must be 0666 less the umask.
    TempDir dir;
    const mode_t old = ::umask(022);
    write_image(dir / name("out"), small);
    ::umask(old);
    struct stat st {};
    ASSERT_EQ(::stat((dir / name("out")).c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0644u);
}

TEST_P(AtomicWrite, RelativePathInTheCurrentDirectory) {
    TempDir dir;
    const auto cwd = std::filesystem::current_path();
    std::filesystem::current_path(dir.path());
    write_image(name("here"), small);
    std::filesystem::current_path(cwd);
    EXPECT_EQ(dir.entries(), Names{name("here")});
}

INSTANTIATE_TEST_SUITE_P(Formats, AtomicWrite, ::testing::Values("png", "ppm", "pfm", "exr"));

// A file given in pieces (a checkpoint: numbers and each tile's bytes) is written without
// first being joined: more pieces than one writev() takes, empty ones among them.
TEST(PendingFile, PiecesAreWrittenInOrder) {
    TempDir dir;
    std::vector<std::string> parts;
    std::string joined;
    std::mt19937 rng(11);
    for (int k = 0; k < 3000; ++k) {
        std::string part(rng() % 5 == 0 ? 0 : rng() % 700, '\0');
        for (char& c : part) c = static_cast<char>(rng());
        joined += part;
        parts.push_back(std::move(part));
    }
    const std::vector<std::string_view> pieces(parts.begin(), parts.end());
    PendingFile file(dir / "c.ckpt", pieces);
    EXPECT_EQ(dir.entries().size(), 1u);  // the temporary file, until committed
    file.commit();
    EXPECT_EQ(dir.entries(), Names{"c.ckpt"});
    EXPECT_EQ(slurp(dir / "c.ckpt"), joined);
}

TEST(PendingFile, PiecesCutByAFullDiskKeepTheExistingFile) {
    TempDir dir;
    put_file(dir / "c.ckpt", "old content");
    const std::string part(300, 'x');
    try {
        FileSizeLimit limit(1000);  // the fourth piece is written in part, then no more
        PendingFile file(dir / "c.ckpt", std::vector<std::string_view>(10, part));
        ADD_FAILURE() << "no error";
    } catch (const FileError& e) {
        EXPECT_EQ(std::string(e.what()), dir / "c.ckpt" + ": cannot write: File too large");
    }
    EXPECT_EQ(slurp(dir / "c.ckpt"), "old content");
    EXPECT_EQ(dir.entries(), Names{"c.ckpt"});
}

// A write cut by SIGKILL leaves its temporary file; the next user of the path removes those of
// processes that no longer run, and leaves those of running ones and every other file.
TEST(PendingFile, StaleTemporariesOfDeadProcessesAreRemoved) {
    TempDir dir;
    const pid_t dead = fork();
    if (dead == 0) _exit(0);
    ASSERT_GT(dead, 0);
    ASSERT_EQ(waitpid(dead, nullptr, 0), dead);
    const std::string d = std::to_string(dead), alive = std::to_string(getpid());
    const Names kept = {".c.ckpt.tmp." + alive + ".0123456789abcdef",  // a running process's
                        ".c.ckpt.tmp." + d + ".0123",                  // not a name we make
                        ".c.ckpt.tmp.x" + d + ".0123456789abcdef",
                        ".d.ckpt.tmp." + d + ".0123456789abcdef",  // another file's
                        "c.ckpt"};
    for (const std::string& name : kept) put_file(dir / name, "x");
    put_file(dir / (".c.ckpt.tmp." + d + ".0123456789abcdef"), "cut short");
    EXPECT_EQ(remove_stale_temporaries(dir / "c.ckpt"), 1u);
    Names left = dir.entries();
    Names want = kept;
    std::sort(left.begin(), left.end());
    std::sort(want.begin(), want.end());
    EXPECT_EQ(left, want);
    EXPECT_EQ(remove_stale_temporaries(dir / "missing/c.ckpt"), 0u);  // no folder: nothing
}

TEST(WriteImage, UnknownExtensionNamesFileAndFormats) {
    TempDir dir;
    put_file(dir / "x.jpg", "old content");
    const std::string path = dir / "x.jpg";
    expect_write_error(path, small,
                       path +
                           ": unknown image format (supported extensions: .png, .ppm, .pfm, "
                           ".exr)");
    EXPECT_EQ(slurp(path), "old content");
    EXPECT_EQ(dir.entries(), Names{"x.jpg"});
}

TEST(WriteImage, NoExtension) {
    TempDir dir;
    EXPECT_THROW(write_image(dir / "render", small), ImageError);
    EXPECT_EQ(dir.entries(), Names{});
}

TEST(WriteImage, ManyWritesToOneDirectoryLeaveNoTemporaries) {
    TempDir dir;
    for (int i = 0; i < 20; ++i) write_image(dir / "same.png", Image(2, 2, Rgb{i / 20.0f}));
    EXPECT_EQ(dir.entries(), Names{"same.png"});
    EXPECT_EQ(read_image(dir / "same.png").at(1, 1), Rgb{242 / 255.0f});  // the last: 0.95
}

TEST(WriteImage, VeryLongFileName) {
    // The temporary name adds a prefix and suffix; it must still fit within NAME_MAX.
    TempDir dir;
    const std::string long_name = std::string(240, 'a') + ".png";
    write_image(dir / long_name, small);
    EXPECT_EQ(dir.entries(), Names{long_name});
}

}  // namespace
}  // namespace luz
