// Truncated or corrupt OpenEXR files give an ImageError (never a crash, a hang or a line on
// stderr).
#include <OpenEXR/openexr.h>
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <new>
#include <random>
#include <string>
#include <vector>

#include "exr_fixtures.h"
#include "image/image_codecs.h"
#include "image/image_io.h"
#include "temp_dir.h"

namespace luz {
namespace {

using test::awkward_image;
using test::box;
using test::error_of;
using test::make_file;
using test::rgb;
using test::set_data_window;
using test::TestFile;

/// Decoding `bytes` either works or throws ImageError "invalid OpenEXR: ..." (or the codec's
/// own messages).
void expect_clean_failure_or_image(std::string_view bytes, const std::string& what) {
    std::string error;
    try {
        const Image img = decode_exr(bytes);
        EXPECT_GT(img.width, 0) << what;
    } catch (const ImageError& e) {
        error = e.what();
    } catch (const std::bad_alloc&) {  // a data window too large for memory
    }
    if (!error.empty()) {
        EXPECT_TRUE(error.rfind("invalid OpenEXR: ", 0) == 0 || error == "bad data window" ||
                    error == "not an OpenEXR file" || error.rfind("no R, G, B", 0) == 0)
            << what << ": " << error;
    }
}

TEST(ExrCodec, TruncatedFilesFailCleanly) {
    TestFile tiled;
    tiled.storage = EXR_STORAGE_TILED;
    tiled.tile_w = tiled.tile_h = 8;
    tiled.channels = rgb(EXR_PIXEL_HALF);
    const std::string files[] = {encode_exr(awkward_image(9, 40, 4)), make_file(tiled)};
    ASSERT_FALSE(HasFatalFailure());
    for (const std::string& bytes : files) {
        ::testing::internal::CaptureStderr();
        for (size_t keep = 0; keep < bytes.size(); ++keep) {
            const std::string error = error_of(bytes.substr(0, keep));
            if (keep < 4) {
                EXPECT_EQ(error, "not an OpenEXR file") << keep;
            } else {
                EXPECT_EQ(error.rfind("invalid OpenEXR: ", 0), 0u) << keep << ": " << error;
            }
        }
        EXPECT_EQ(::testing::internal::GetCapturedStderr(), "") << "the library printed";
    }
    // A message worth reading: the last chunk is cut short.
    const std::string bytes = encode_exr(Image(8, 8, Rgb{0.5f}));
    EXPECT_NE(error_of(bytes.substr(0, bytes.size() - 1)).find("chunk"), std::string::npos)
        << error_of(bytes.substr(0, bytes.size() - 1));
}

TEST(ExrCodec, AHugeDataWindowInASmallFileIsRefusedBeforeTakingItsMemory) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP()
        << "an address-space limit and AddressSanitizer's shadow memory exclude each other";
#endif
    // A 16 × 16 file whose header then claims 16 × 2^24 pixels (3 GiB of floats): the chunk
    // table such a window needs does not fit in the file, which is the message, not the memory.
    std::string bytes = encode_exr(Image(16, 16, Rgb{0.5f}));
    set_data_window(bytes, 3, 1 << 24);  // y max
    ASSERT_FALSE(HasFatalFailure());
    const auto decode_in_1_gib = [&bytes] {
        rlimit limit{};
        limit.rlim_cur = limit.rlim_max = rlim_t{1} << 30;  // 1 GiB of address space
        setrlimit(RLIMIT_AS, &limit);
        std::fputs(error_of(bytes).c_str(), stderr);
        std::_Exit(0);
    };
    EXPECT_EXIT(decode_in_1_gib(), ::testing::ExitedWithCode(0), "invalid OpenEXR: .*chunk");
}

TEST(ExrCodec, AWideDataWindowInASmallFileIsRefusedByItsFirstChunksSize) {
    // Files of 16 × 16 pixels whose header then claims 2^24 columns: the first chunk would
    // unpack to hundreds of megabytes from a few hundred bytes, more than its compression can
    // give. It is refused by that, before the library takes the memory to unpack it.
    for (exr_compression_t compression :
         {EXR_COMPRESSION_RLE, EXR_COMPRESSION_ZIPS, EXR_COMPRESSION_ZIP, EXR_COMPRESSION_PIZ,
          EXR_COMPRESSION_PXR24, EXR_COMPRESSION_B44}) {
        TestFile file;
        file.compression = compression;
        file.data_window = box(0, 0, 15, 15);
        file.channels = rgb(EXR_PIXEL_HALF);
        std::string bytes = make_file(file);
        ASSERT_FALSE(HasFatalFailure());
        set_data_window(bytes, 2, 1 << 24);  // x max
        ASSERT_FALSE(HasFatalFailure());
        EXPECT_NE(error_of(bytes).find("bytes, too few for its"), std::string::npos)
            << "compression " << compression << ": " << error_of(bytes);
    }
}

TEST(ExrCodec, CorruptFilesFailCleanly) {
    // Every byte of small files of each compression set to a few values: an image or an
    // ImageError, never a crash.
    std::vector<std::string> files = {encode_exr(awkward_image(7, 18, 9))};
    for (exr_compression_t compression :
         {EXR_COMPRESSION_NONE, EXR_COMPRESSION_RLE, EXR_COMPRESSION_ZIPS, EXR_COMPRESSION_PIZ,
          EXR_COMPRESSION_PXR24, EXR_COMPRESSION_B44}) {
        for (exr_storage_t storage : {EXR_STORAGE_SCANLINE, EXR_STORAGE_TILED}) {
            TestFile file;
            file.storage = storage;
            file.compression = compression;
            file.tile_w = file.tile_h = 4;
            file.data_window = box(-1, 2, 6, 9);
            file.channels = rgb(EXR_PIXEL_HALF);
            files.push_back(make_file(file));
            ASSERT_FALSE(HasFatalFailure());
        }
    }
    for (const std::string& bytes : files) {
        ::testing::internal::CaptureStderr();
        for (size_t i = 4; i < bytes.size(); ++i) {
            for (unsigned char v : {0x00, 0x01, 0x7f, 0xff}) {
                std::string bad = bytes;
                if (static_cast<unsigned char>(bad[i]) == v) continue;
                bad[i] = static_cast<char>(v);
                expect_clean_failure_or_image(bad, "byte " + std::to_string(i));
            }
        }
        EXPECT_EQ(::testing::internal::GetCapturedStderr(), "") << "the library printed";
    }
}

}  // namespace
}  // namespace luz
