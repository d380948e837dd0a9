// Bvh4 (bvh_reference.h): WideBvh<4>'s collapse, compiled for the tests only.
#include "bvh_reference.h"

#include "geometry/wide_bvh_collapse.h"

namespace luz {

template class WideBvh<4>;

}  // namespace luz
