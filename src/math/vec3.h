// Vec3 and Rgb are public types (include/luz/vec3.h): the layers use them from there.
#pragma once

#include "luz/vec3.h"
