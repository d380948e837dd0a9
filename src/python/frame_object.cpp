// luz.Frame's views, statistics and files.
#include "python/frame_object.h"

#include "luz/options.h"
#include "luz/stats_json.h"
#include "python/interruptible.h"
#include "python/json_convert.h"

namespace luz::python {

namespace py = pybind11;

py::array image_view(const Image& image, bool scalar, py::handle owner) {
    const py::ssize_t h = image.height, w = image.width;
    constexpr py::ssize_t pixel = sizeof(Rgb), channel = sizeof(float);
    static_assert(sizeof(Rgb) == 3 * sizeof(float), "Image pixels are three packed floats");
    // The data pointer is the image's own; numpy holds `owner`, not a copy.
    auto* data = const_cast<float*>(image.pixels.empty() ? nullptr : &image.pixels[0].x);
    if (scalar) return py::array_t<float>({h, w}, {w * pixel, pixel}, data, owner);
    return py::array_t<float>({h, w, py::ssize_t{3}}, {w * pixel, pixel, channel}, data, owner);
}

py::dict frame_stats(const FrameObject& f) {
    return to_python(nlohmann::ordered_json::parse(stats_json(f.frame.stats, f.scene->desc)));
}

void save_frame(const FrameObject& f, const std::string& path) {
    check_output_path(path, "path");
    // Ctrl-C stops the encoding of a large image (and its temporary files go)
    run_interruptibly([&](const std::atomic<bool>&) {
        write_frame_files(f.frame, path, f.scene->desc.image.encoding);
    });
}

py::bytes frame_png(const FrameObject& f) {
    std::string bytes;
    run_interruptibly([&](const std::atomic<bool>&) {
        bytes = encode_frame(f.frame, "frame.png", f.scene->desc.image.encoding);
    });
    return py::bytes(bytes);
}

}  // namespace luz::python
