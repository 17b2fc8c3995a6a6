/* What every kernel file needs: the layouts shared with the host, and the
 * loads that turn their float[3] fields into float3 (shared structs hold no
 * float3, see shared_structs.h). */
#ifndef CLP_COMMON_H
#define CLP_COMMON_H

#include "shared_structs.h"

inline float3 load3(const float* p) { return (float3)(p[0], p[1], p[2]); }
inline float3 load3g(global const float* p) { return (float3)(p[0], p[1], p[2]); }
inline float3 load3c(constant const float* p) { return (float3)(p[0], p[1], p[2]); }

#endif
