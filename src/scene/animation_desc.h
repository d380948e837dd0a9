// AnimationDesc is a public type (include/luz/animation_desc.h).
#pragma once

#include "luz/animation_desc.h"
