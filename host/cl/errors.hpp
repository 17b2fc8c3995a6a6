#pragma once
#include <CL/cl.h>

#include <string>

namespace clpath {

// "CL_OUT_OF_RESOURCES" for -5, and so on: errors are reported by name.
const char* cl_error_name(cl_int code);

// Throws clpath::Error("<what>: <name> (<code>)") unless code is CL_SUCCESS.
void cl_check(cl_int code, const std::string& what);

}  // namespace clpath
