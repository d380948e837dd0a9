// Outputs that would destroy each other or an input: two names for one file (the same inode,
// or the same resolved path where nothing is yet), refused before any work.
#include <algorithm>
#include <utility>

#include "engine/luz_engine.h"
#include "image/output_target.h"
#include "scene/text_files.h"

namespace luz {

void check_distinct_files(const std::vector<NamedFile>& files) {
    // Sorted by identity, so that a render of 10 000 frames with every term is checked in
    // n log n; the first pair of each identity is reported, in the order given.
    std::vector<std::pair<FileIdentity, size_t>> ids;
    ids.reserve(files.size());
    for (size_t k = 0; k < files.size(); ++k) ids.emplace_back(file_identity(files[k].path), k);
    std::sort(ids.begin(), ids.end());
    size_t first_bad = files.size(), other_bad = 0;
    for (size_t run = 0; run < ids.size();) {
        size_t end = run + 1;
        while (end < ids.size() && ids[end].first == ids[run].first) ++end;
        // within a run, indices ascend: the first member and the first output after it (or,
        // when the first is an output, the second member)
        if (end - run > 1) {
            const size_t lo = ids[run].second;
            size_t hi = files.size();
            for (size_t b = run + 1; b < end && hi == files.size(); ++b)
                if (files[lo].output || files[ids[b].second].output) hi = ids[b].second;
            if (hi != files.size() && (lo < first_bad || (lo == first_bad && hi < other_bad))) {
                first_bad = lo;
                other_bad = hi;
            }
        }
        run = end;
    }
    if (first_bad == files.size()) return;
    const NamedFile& a = files[first_bad];
    const NamedFile& b = files[other_bad];
    std::string message = a.path + ": " + a.origin + " and " + b.origin + " name the same file";
    if (b.path != a.path) message += " (" + b.path + ")";
    throw SceneError(message);
}

InputFileRecorder::InputFileRecorder() : previous_(file_observer()) {
    set_file_observer([this](const std::string& path, const std::string& text) {
        {
            const std::lock_guard<std::mutex> lock(mutex_);
            files_.push_back(path);
        }
        if (previous_) previous_(path, text);
    });
}

InputFileRecorder::~InputFileRecorder() { set_file_observer(previous_); }

}  // namespace luz
