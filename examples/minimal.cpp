// The smallest luz program: renders demo:primitives to the path given, the very bytes that
// `luz render demo:primitives -o PATH` writes. Build once, render, write.
#include <luz/luz.h>

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: minimal OUT.png\n");
        return 2;
    }
    try {
        const luz::SceneDesc desc = luz::load_scene("demo:primitives", {});
        const luz::Scene scene = luz::build(desc);
        const luz::Frame frame = luz::render(scene, desc);
        luz::write_frame(frame, argv[1], desc.image.encoding);
    } catch (const luz::SceneError& e) {  // bad input: one line naming the file and the place
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "minimal: %s\n", e.what());
        return 1;
    }
    return 0;
}
