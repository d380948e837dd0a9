// Ray: an origin and a direction; points along it are origin + t·direction.
#pragma once

#include "math/vec3.h"

namespace luz {

struct Ray {
    Vec3 origin;
    Vec3 direction;

    constexpr Vec3 at(float t) const { return origin + direction * t; }
};

}  // namespace luz
