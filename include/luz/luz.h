// luz's public API, the core a library user needs: load and build a scene, render it into a
// Frame, write the frame. Build once, then render with any settings:
//
//     luz::SceneDesc desc = luz::load_scene("demo:primitives", {});
//     luz::Scene scene = luz::build(desc);
//     luz::Frame frame = luz::render(scene, desc);
//     luz::write_frame(frame, "primitives.png", desc.image.encoding);
//
// What only some front ends need has a header of its own, not included here (docs/LIBRARY.md).
#pragma once

#include "luz/output.h"
#include "luz/render.h"
#include "luz/scene.h"
