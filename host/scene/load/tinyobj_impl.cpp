// tinyobjloader's implementation, compiled from Debian's header into clpath
// itself rather than linked from libtinyobjloader.so: a build copied to a
// machine without that library then needs nothing more, and
// the fuzzers compile the parser with their instrumentation.
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wall"
#pragma GCC diagnostic ignored "-Wextra"
#endif
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
