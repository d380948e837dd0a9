// RenderStats is a public type (include/luz/stats.h): the layers use it from there.
#pragma once

#include "luz/stats.h"
