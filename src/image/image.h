// Image is a public type (include/luz/image.h): the layers use it from there.
#pragma once

#include "luz/image.h"
