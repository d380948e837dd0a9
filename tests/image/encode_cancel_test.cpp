// The encoders stop with Cancelled once the calling thread's cancel flag is set (scene/cancel.h),
// within a band of rows: Ctrl-C during the encoding of a large image answers at once instead of
// after seconds; with the flag clear they give the very same bytes.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <random>
#include <thread>

#include "image/image_io.h"
#include "scene/cancel.h"

namespace luz {
namespace {

const char* const kFormats[] = {"a.png", "a.ppm", "a.pfm", "a.exr"};

/// Noise: no encoder finds a shortcut through it.
Image noise(int w, int h) {
    Image img(w, h);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (Rgb& p : img.pixels) p = Rgb{u(rng), u(rng), u(rng)};
    return img;
}

TEST(EncodeCancel, EveryFormatStopsWhenTheFlagIsSet) {
    const Image img = noise(300, 200);
    std::atomic<bool> cancel{true};
    const CancelScope scope(&cancel);
    for (const char* path : kFormats) EXPECT_THROW(encode_image(path, img), Cancelled) << path;
    const ExrLayer layer{"depth", &img, true};
    EXPECT_THROW(encode_image_layers("a.exr", img, {layer}), Cancelled);
    PngBands png(img.width, img.height, Encoding::linear);
    EXPECT_THROW(png.add(img, img.height), Cancelled);
}

TEST(EncodeCancel, AClearFlagChangesNoByte) {
    const Image img = noise(300, 200);
    std::atomic<bool> cancel{false};
    for (const char* path : kFormats) {
        const std::string without = encode_image(path, img);
        const CancelScope scope(&cancel);
        EXPECT_EQ(encode_image(path, img), without) << path;
    }
}

TEST(EncodeCancel, AFlagSetByAnotherThreadStopsALargeExrWithinAFewChunks) {
    // 1536² of noise: about a second of ZIP compression; the flag comes 50 ms in.
    const Image img = noise(1536, 1536);
    std::atomic<bool> cancel{false};
    std::chrono::steady_clock::time_point set_at{};
    std::thread setter([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        set_at = std::chrono::steady_clock::now();
        cancel.store(true);
    });
    const CancelScope scope(&cancel);
    EXPECT_THROW(encode_image("a.exr", img), Cancelled);
    const auto stopped = std::chrono::steady_clock::now();
    setter.join();
    EXPECT_LT(std::chrono::duration<double>(stopped - set_at).count(), 0.1);
}

}  // namespace
}  // namespace luz
