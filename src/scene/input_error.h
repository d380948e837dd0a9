// InputError (SceneError) is public: include/luz/errors.h.
#pragma once

#include "luz/errors.h"
