// tinyobjloader compiled from its header with the fuzzers' instrumentation (Debian ships it
// prebuilt as libtinyobjloader.so, which the fuzzer could not see into).
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
