/* The control of the Oclgrind checks (tests/kernels/oclgrind_tests.cmake):
 * a kernel that writes one element past the end of its buffer. Oclgrind must
 * report it, or the checks that find nothing in the real kernels prove
 * nothing. Never launched outside the simulator. */
#ifndef CLP_OCLGRIND_CONTROL_CL
#define CLP_OCLGRIND_CONTROL_CL

#include "common.h"

kernel void control_write_past_end(global uint* out, uint count) {
    uint i = get_global_id(0);
    if (i > count) return; /* the bug: should be i >= count */
    out[i] = i;
}

#endif
