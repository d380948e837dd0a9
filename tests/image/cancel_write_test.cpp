// Writing a file stops with Cancelled once the calling thread's cancel flag is set
// (scene/cancel.h), between writes of at most 64 MiB, and leaves no temporary file: an 800 MB
// image being written answers Ctrl-C at once.
#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <string>

#include "image/atomic_file.h"
#include "image/temp_dir.h"
#include "scene/cancel.h"

namespace luz {
namespace {

using test::TempDir;

TEST(CancelWrite, AWriteStopsAndLeavesNothing) {
    const TempDir dir;
    const std::string path = (dir.path() / "big.pfm").string();
    const std::string bytes(3 << 20, 'x');
    std::atomic<bool> cancel{true};
    {
        const CancelScope scope(&cancel);
        EXPECT_THROW(PendingFile(path, bytes), Cancelled);
    }
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
    cancel = false;
    const CancelScope scope(&cancel);
    PendingFile(path, bytes).commit();
    EXPECT_EQ(std::filesystem::file_size(path), bytes.size());
}

}  // namespace
}  // namespace luz
