// libFuzzer target: bytes → a --checkpoint file read back (parse_checkpoint), once with its
// checksums checked and once without (reaching the checks behind them). Damage must end in
// InputError (exit 2 in `luz`); anything else — a crash, a sanitizer report, another exception,
// an allocation out of proportion to the input — is a bug.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "render/checkpoint_file.h"
#include "scene/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    // The key the file says it has (bytes 16-23), so that the fuzzer gets past it.
    uint64_t key = 0;
    for (size_t k = 0; k < 8 && 16 + k < size; ++k) key |= uint64_t{data[16 + k]} << (8 * k);
    for (const bool verify : {true, false}) {
        try {
            const luz::CheckpointContents c =
                luz::parse_checkpoint(bytes, key, "fuzz.ckpt", verify);
            for (const luz::CheckpointTile& t : c.tiles) {
                if (t.index >= c.count || t.offset + t.size > size) __builtin_trap();
            }
        } catch (const luz::InputError&) {
            // damaged or not a checkpoint, reported with the file: the expected outcome
        }
    }
    return 0;
}
