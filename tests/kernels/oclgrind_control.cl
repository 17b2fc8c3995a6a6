/* The controls of the Oclgrind checks (tests/kernels/oclgrind_tests.cmake):
 * kernels with the bugs the checks look for, which Oclgrind must report, or
 * the checks that find nothing in the real kernels prove nothing. Never
 * launched outside the simulator. */
#ifndef CLP_OCLGRIND_CONTROL_CL
#define CLP_OCLGRIND_CONTROL_CL

#include "common.h"

kernel void control_write_past_end(global uint* out, uint count) {
    uint i = get_global_id(0);
    if (i > count) return; /* the bug: should be i >= count */
    out[i] = i;
}

/* Stores a value that was never set when count is small. */
kernel void control_store_uninitialised(global uint* out, uint count) {
    uint i = get_global_id(0);
    if (i >= count) return;
    uint v;
    if (count > 1000u) v = i; /* the bug: no value otherwise */
    out[i] = v;
}

#endif
