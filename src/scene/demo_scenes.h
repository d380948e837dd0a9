// The built-in scenes are public (include/luz/demo_scenes.h); their texts live in scene/.
#pragma once

#include "luz/demo_scenes.h"
