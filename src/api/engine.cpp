// The engine header's own parts (engine/luz_engine.h): the checkpoint a front end holds, the
// outputs it writes together, and what names a PNG file.
#include "engine/luz_engine.h"
#include "image/atomic_file.h"
#include "image/image_io.h"
#include "render/checkpoint.h"

namespace luz {

CheckpointFile::CheckpointFile(const std::string& path, const std::string& key)
    : checkpoint_(std::make_unique<Checkpoint>(path, fingerprint(key))) {}

CheckpointFile::~CheckpointFile() = default;

void CheckpointFile::save() { checkpoint_->save(); }

void CheckpointFile::remove() { checkpoint_->remove(); }

struct PendingOutputs::Files {
    std::vector<std::unique_ptr<PendingFile>> files;
};

PendingOutputs::PendingOutputs() : files_(std::make_unique<Files>()) {}

PendingOutputs::~PendingOutputs() = default;

void PendingOutputs::add(const std::string& path, std::string bytes) {
    files_->files.push_back(std::make_unique<PendingFile>(path, std::move(bytes)));
}

void PendingOutputs::commit(const std::atomic<bool>* cancel) {
    std::vector<PendingFile*> all;
    for (auto& f : files_->files) all.push_back(f.get());
    commit_together(all, cancel);
}

bool is_png_path(const std::string& path) {
    ImageFormat format{};
    return format_from_path(path, format) && format == ImageFormat::png;
}

}  // namespace luz
