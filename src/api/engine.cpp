// The engine header's own parts (engine/luz_engine.h): the checkpoint a front end holds, and
// what names a PNG file.
#include "engine/luz_engine.h"

#include "image/image_io.h"
#include "render/checkpoint.h"

namespace luz {

CheckpointFile::CheckpointFile(const std::string& path, const std::string& key)
    : checkpoint_(std::make_unique<Checkpoint>(path, fingerprint(key))) {}

CheckpointFile::~CheckpointFile() = default;

void CheckpointFile::save() { checkpoint_->save(); }

void CheckpointFile::remove() { checkpoint_->remove(); }

bool is_png_path(const std::string& path) {
    ImageFormat format{};
    return format_from_path(path, format) && format == ImageFormat::png;
}

}  // namespace luz
