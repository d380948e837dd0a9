// The material presets are public (include/luz/presets.h); their values live in scene/presets.cpp.
#pragma once

#include "luz/presets.h"
