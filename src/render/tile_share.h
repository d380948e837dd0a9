// TileShare is the interface a render asks of a share of its tiles (src/engine/tile_share.h,
// beside the engine header the MPI front end implements it through).
#pragma once

#include "engine/tile_share.h"
