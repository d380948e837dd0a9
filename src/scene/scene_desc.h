// SceneDesc is a public type (include/luz/scene_desc.h); the parts only the layers use: the
// mesh data, the shape key table.
#pragma once

#include "luz/scene_desc.h"
#include "luz/scene_text.h"  // SceneText
#include "math/transform.h"
#include "scene/mesh_data.h"
#include "scene/shape_desc.h"
