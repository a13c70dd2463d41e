// tinyobjloader's implementation, compiled with the fuzz build's instrumentation so that the OBJ
// harness gets coverage feedback from the parser it drives (fuzz/CMakeLists.txt). Only the fuzz
// build uses it; everything else links Debian's libtinyobjloader.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
