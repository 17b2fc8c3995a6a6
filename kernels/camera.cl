/* Pinhole or orthographic camera. Conventions: pixel (0, 0) is the top-left corner of the
 * image, rows go down; image right is forward x up (right-handed); each sample
 * is jittered uniformly inside its pixel (a box filter). */
#ifndef CLP_CAMERA_CL
#define CLP_CAMERA_CL

#include "common.h"

typedef struct {
    float3 o;
    float3 d;
} Ray;

/* (jx, jy) in [0,1)^2 is the position inside the pixel. */
inline Ray camera_ray(constant const CameraData* cam, uint px, uint py, float jx, float jy) {
    float x = 2.0f * ((float)px + jx) / (float)cam->width - 1.0f;
    float y = 1.0f - 2.0f * ((float)py + jy) / (float)cam->height;
    Ray r;
    if (cam->orthographic) {
        r.o = load3c(cam->eye) + x * load3c(cam->right) + y * load3c(cam->up);
        r.d = load3c(cam->forward);
        return r;
    }
    r.o = load3c(cam->eye);
    r.d = normalize3(load3c(cam->forward) + x * load3c(cam->right) + y * load3c(cam->up));
    return r;
}

#endif
