// The renderer's wide BVH, Bvh8: WideBvh<8>'s collapse compiled once (wide_bvh_collapse.h).
#include "geometry/wide_bvh_collapse.h"

namespace luz {

template class WideBvh<8>;

}  // namespace luz
