// luz's public API: everything a front end (the `luz` command, the viewer, the Python module,
// the MPI driver) includes. Build once, then render with any settings:
//
//     luz::SceneDesc desc = luz::load_scene("demo:primitives", {});
//     luz::Scene scene = luz::build(desc);
//     luz::Frame frame = luz::render(scene, desc);
//     luz::write_frame(frame, "primitives.png", desc.image.encoding);
#pragma once

#include "luz/animation.h"
#include "luz/output.h"
#include "luz/render.h"
#include "luz/scene.h"
