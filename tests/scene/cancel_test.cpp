// Loads stop with Cancelled once the calling thread's cancel flag is set (scene/cancel.h): the
// OBJ's checking pass and tinyobjloader's read, and the scene's objects, look at it, so that a
// long load answers Ctrl-C; a scope holds its thread's flag only, and restores the one before.
#include "scene/cancel.h"

#include <gtest/gtest.h>

#include <string>
#include <thread>

#include "scene/obj_loader.h"
#include "scene/scene_loader.h"

namespace luz {
namespace {

TEST(Cancel, AScopeHoldsItsThreadsFlagAndRestoresThePreviousOne) {
    std::atomic<bool> set{true}, clear{false};
    EXPECT_EQ(cancel_flag(), nullptr);
    EXPECT_NO_THROW(check_cancel());
    {
        const CancelScope outer(&clear);
        EXPECT_NO_THROW(check_cancel());
        {
            const CancelScope inner(&set);
            EXPECT_THROW(check_cancel(), Cancelled);
            std::thread other([] { EXPECT_NO_THROW(check_cancel()); });  // not its flag
            other.join();
        }
        EXPECT_EQ(cancel_flag(), &clear);
    }
    EXPECT_EQ(cancel_flag(), nullptr);
}

/// A triangle referenced by `faces` faces.
std::string obj_of(int faces) {
    std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (int i = 0; i < faces; ++i) text += "f 1 2 3\n";
    return text;
}

MeshData parse_cancel_obj(const std::string& text) {
    std::vector<std::string> warnings;
    const TextReader none = [](const std::string&, std::string& reason) {
        reason = "none";
        return std::optional<std::string>();
    };
    return parse_obj(text, "m.obj", false, none, warnings);
}

TEST(Cancel, AnObjLoadStops) {
    std::atomic<bool> cancel{false};
    const CancelScope scope(&cancel);
    EXPECT_EQ(parse_cancel_obj(obj_of(100)).triangle_count(), 100u);
    cancel = true;
    EXPECT_THROW(parse_cancel_obj(obj_of(100)), Cancelled);    // tinyobjloader reads nothing more
    EXPECT_THROW(parse_cancel_obj(obj_of(70000)), Cancelled);  // the checking pass stops on its way
}

TEST(Cancel, ASceneLoadStopsAtItsObjects) {
    const std::string scene = R"({"objects": [{"type": "sphere"}, {"type": "sphere"}]})";
    std::atomic<bool> cancel{false};
    const CancelScope scope(&cancel);
    EXPECT_EQ(parse_scene(scene, "s.json", "").objects.size(), 2u);
    cancel = true;
    EXPECT_THROW(parse_scene(scene, "s.json", ""), Cancelled);
}

}  // namespace
}  // namespace luz
