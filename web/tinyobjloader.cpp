// tinyobjloader's implementation for the web build (natively it is Debian's libtinyobjloader).
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
