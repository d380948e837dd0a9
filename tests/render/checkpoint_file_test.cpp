// The --checkpoint file (render/checkpoint.h, checkpoint_file.h): what is saved reads back;
// every flipped bit and every truncation is refused as damaged; a huge tile count allocates
// nothing; a write that fails warns once and the render goes on; old versions are named.
#include "render/checkpoint_file.h"

#include <sys/resource.h>
#include <zlib.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include "image/temp_dir.h"
#include "render/checkpoint.h"
#include "scene/input_error.h"

namespace luz {
namespace {

using test::put_file;
using test::slurp;
using test::TempDir;

constexpr uint64_t kKey = 0x1234567890abcdefull;

/// Saves a checkpoint of 5 items of which 0, 2 and 3 are finished; returns its bytes.
std::string small_checkpoint(const std::string& path) {
    Checkpoint c(path, kKey);
    c.start(5);
    for (size_t i : {3, 0, 2}) {
        std::string bytes(40 + 7 * i, '\0');
        for (size_t k = 0; k < bytes.size(); ++k) bytes[k] = static_cast<char>(i * 31 + k);
        EXPECT_EQ(c.finish(i, bytes), "");
    }
    c.save();
    return slurp(path);
}

/// The message of the InputError reading `path` throws (in the constructor or in start(5)), or
/// "" when it reads.
std::string refusal(const std::string& path, size_t items = 5) {
    try {
        Checkpoint c(path, kKey);
        c.start(items);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

/// Replaces the file at `path` (a new file: truncating one makes ext4 write it to disk).
void replace_file(const std::string& path, const std::string& bytes) {
    std::filesystem::remove(path);
    put_file(path, bytes);
}

void put64(std::string& bytes, size_t at, uint64_t v) {
    for (int k = 0; k < 8; ++k) bytes[at + k] = static_cast<char>((v >> (8 * k)) & 0xff);
}

/// The header's checksum made right again after an edit (as a careful forger would).
void reseal_header(std::string& bytes) {
    put64(bytes, 32, crc32(0, reinterpret_cast<const Bytef*>(bytes.data()), 32));
}

TEST(CheckpointFile, WhatIsSavedReadsBack) {
    TempDir dir;
    const std::string path = dir / "c.ckpt";
    const std::string saved = small_checkpoint(path);
    Checkpoint c(path, kKey);
    c.start(5);
    EXPECT_EQ(c.finished(), 3u);
    for (size_t i = 0; i < 5; ++i) EXPECT_EQ(c.done(i), i == 0 || i == 2 || i == 3) << i;
    EXPECT_EQ(c.data(3).size(), 61u);
    EXPECT_EQ(static_cast<unsigned char>(c.data(3)[1]), 94u);
    c.save();  // the same tiles, the same bytes
    EXPECT_EQ(slurp(path), saved);
}

TEST(CheckpointFile, EveryFlippedBitAndEveryTruncationIsRefusedAsDamaged) {
    TempDir dir;
    const std::string path = dir / "c.ckpt";
    const std::string saved = small_checkpoint(path);
    ASSERT_EQ(saved.size(), 40u + 3 * 24 + (40 + 40 + 14 + 40 + 21) + 24);
    const std::string prefix = path + ": --checkpoint: damaged checkpoint (";
    for (size_t bit = 0; bit < 8 * saved.size(); ++bit) {
        std::string bytes = saved;
        bytes[bit / 8] = static_cast<char>(bytes[bit / 8] ^ (1 << (bit % 8)));
        replace_file(path, bytes);
        const std::string message = refusal(path);
        ASSERT_EQ(message.rfind(prefix, 0), 0u) << "bit " << bit << ": " << message;
        EXPECT_EQ(slurp(path), bytes) << "left as it was";
    }
    for (size_t size = 0; size < saved.size(); ++size) {
        replace_file(path, saved.substr(0, size));
        const std::string message = refusal(path);
        ASSERT_EQ(message.rfind(prefix, 0), 0u) << size << " bytes: " << message;
    }
    put_file(path, saved + "x");
    EXPECT_EQ(refusal(path), prefix + "bytes after its end)");
    put_file(path, saved);
    EXPECT_EQ(refusal(path), "");
}

// A count damaged behind a header made right again (a bit of 27, 31 or 63) is refused by the
// render's own count before any memory is given to it: once 5.3 GB and 13.6 s, or bad_alloc.
TEST(CheckpointFile, AHugeTileCountAllocatesNothing) {
    TempDir dir;
    const std::string path = dir / "c.ckpt";
    const std::string saved = small_checkpoint(path);
    rusage before{};
    getrusage(RUSAGE_SELF, &before);
    const auto start = std::chrono::steady_clock::now();
    for (int bit : {27, 31, 40, 63}) {
        std::string bytes = saved;
        put64(bytes, 24, 5 | (uint64_t{1} << bit));
        reseal_header(bytes);
        put_file(path, bytes);
        EXPECT_EQ(refusal(path), path + ": --checkpoint: damaged checkpoint (it holds " +
                                     std::to_string(5 | (uint64_t{1} << bit)) +
                                     " tiles, this render has 5)");
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    rusage after{};
    getrusage(RUSAGE_SELF, &after);
    EXPECT_LT(seconds, 1.0);
    EXPECT_LT(after.ru_maxrss - before.ru_maxrss, 64 * 1024) << "KiB more at the peak";
}

// A tile numbered past the render's tiles is refused even when every checksum is right.
TEST(CheckpointFile, CountsAndIndicesAreCheckedBehindRightChecksums) {
    const std::string name = "x.ckpt";
    std::string heads;
    const std::string tile = "0123456789";
    const auto file_of = [&](uint64_t count, std::vector<CheckpointTileRef> tiles) {
        std::string bytes;
        for (std::string_view piece : checkpoint_pieces(kKey, count, tiles, heads)) bytes += piece;
        return bytes;
    };
    EXPECT_NO_THROW(parse_checkpoint(file_of(4, {{3, tile_checksum(3, tile), tile}}), kKey, name));
    try {
        parse_checkpoint(file_of(4, {{9, tile_checksum(9, tile), tile}}), kKey, name);
        ADD_FAILURE() << "index 9 of 4 read";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(),
                     "x.ckpt: --checkpoint: damaged checkpoint (the tile at byte 40 is number 9, "
                     "of 4)");
    }
    try {
        const CheckpointTileRef t{1, tile_checksum(1, tile), tile};
        parse_checkpoint(file_of(4, {t, t}), kKey, name);
        ADD_FAILURE() << "a tile twice read";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "x.ckpt: --checkpoint: damaged checkpoint (tile 1 twice)");
    }
}

TEST(CheckpointFile, OtherVersionsAndOtherFilesAreNamed) {
    TempDir dir;
    const std::string path = dir / "c.ckpt";
    std::string bytes = small_checkpoint(path);
    put64(bytes, 8, 1);  // version 1 had no checksum
    put_file(path, bytes);
    EXPECT_EQ(refusal(path), path +
                                 ": --checkpoint: checkpoint of version 1, this luz writes 2 "
                                 "(render again without it, or remove the file)");
    put64(bytes, 8, 3);
    reseal_header(bytes);
    put_file(path, bytes);
    EXPECT_EQ(refusal(path), path +
                                 ": --checkpoint: checkpoint of version 3, this luz writes 2 "
                                 "(render again without it, or remove the file)");
    put_file(path, "P6\n1 1\n255\nabc");
    EXPECT_EQ(refusal(path), path + ": --checkpoint: not a luz checkpoint");
    std::filesystem::remove(path);
    std::filesystem::create_directory(path);
    EXPECT_EQ(refusal(path), path + ": --checkpoint: not a regular file");
}

// A write that fails while rendering (here: its folder replaced by a file, which stops root
// too) is reported once, and the render goes on; the next write is tried an interval later.
TEST(CheckpointFile, AFailedWriteWarnsOnceAndTheRenderGoesOn) {
    TempDir dir;
    std::filesystem::create_directory(dir / "sub");
    const std::string path = dir / "sub/c.ckpt";
    setenv("LUZ_CHECKPOINT_SECONDS", "0.001", 1);
    Checkpoint c(path, kKey);
    unsetenv("LUZ_CHECKPOINT_SECONDS");
    EXPECT_EQ(Checkpoint::interval(), 10.0);
    c.start(50);
    std::filesystem::remove_all(dir / "sub");
    put_file(dir / "sub", "in the way");
    int warnings = 0;
    for (size_t i = 0; i < 50; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
        const std::string w = c.finish(i, std::string(100, 'x'));
        if (w.empty()) continue;
        ++warnings;
        EXPECT_EQ(w, path +
                         ": cannot write: Not a directory (--checkpoint not saved; the render "
                         "goes on, trying again every 0.001 s)");
    }
    EXPECT_EQ(warnings, 1);
    EXPECT_EQ(c.finished(), 50u);
    std::filesystem::remove(dir / "sub");
    std::filesystem::create_directory(dir / "sub");
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    EXPECT_EQ(c.finish(0, "again"), "");  // written again once it can be
    EXPECT_TRUE(std::filesystem::exists(path));
}

/// The checkpoint files of tests/corpus/checkpoints (the fuzzer's seeds) and those with which
/// scripts/fuzz.sh found bugs (tests/corpus/fuzz/checkpoint), read as
/// fuzz/fuzz_checkpoint_loader.cpp reads them: each reads or throws InputError, with and without
/// its checksums checked.
TEST(CheckpointFile, CorpusFilesReadOrThrowInputError) {
    const std::filesystem::path corpus = std::filesystem::path(LUZ_SOURCE_DIR) / "tests/corpus";
    int files = 0, read = 0;
    for (const char* folder : {"checkpoints", "fuzz/checkpoint"}) {
        if (!std::filesystem::is_directory(corpus / folder)) continue;
        for (const auto& e : std::filesystem::directory_iterator(corpus / folder)) {
            const std::string bytes = slurp(e.path().string());
            uint64_t key = 0;
            for (size_t k = 0; k < 8 && 16 + k < bytes.size(); ++k)
                key |= uint64_t(static_cast<unsigned char>(bytes[16 + k])) << (8 * k);
            ++files;
            for (const bool verify : {true, false}) {
                try {
                    const CheckpointContents c = parse_checkpoint(bytes, key, "fuzz.ckpt", verify);
                    for (const CheckpointTile& t : c.tiles) {
                        EXPECT_LT(t.index, c.count) << e.path();
                        EXPECT_LE(t.offset + t.size, bytes.size()) << e.path();
                    }
                    read += verify;
                } catch (const InputError& x) {
                    EXPECT_EQ(std::string(x.what()).rfind("fuzz.ckpt: --checkpoint: ", 0), 0u)
                        << e.path() << ": " << x.what();
                } catch (const std::exception& x) {
                    ADD_FAILURE() << e.path() << ": not an InputError: " << x.what();
                }
            }
        }
    }
    EXPECT_GE(files, 7);
    EXPECT_EQ(read, 4) << "the four whole seeds (written by a Python writer of the format) read";
}

}  // namespace
}  // namespace luz
