/* Pinhole, thin-lens or orthographic camera. Conventions: pixel (0, 0) is the top-left corner of the
 * image, rows go down; image right is forward x up (right-handed); each sample
 * is jittered uniformly inside its pixel (a box filter). */
#ifndef CLP_CAMERA_CL
#define CLP_CAMERA_CL

#include "common.h"
#include "rng.cl"
#include "sampling.cl"

typedef struct {
    float3 o;
    float3 d;
} Ray;

/* (jx, jy) in [0,1)^2 is the position inside the pixel. */
static inline Ray camera_ray(constant const CameraData* cam, uint px, uint py, float jx, float jy) {
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

/* Thin lens (depth of field): moves a pinhole ray's origin to a uniform
 * point of the lens disk, sampled by Shirley & Chiu's (1997) concentric map,
 * and aims it at the point where the pinhole ray meets the plane of focus
 * (focus_distance along forward: forward is a unit vector orthogonal to right
 * and up, so the pinhole direction forward + x right + y up reaches that plane
 * at focus_distance times itself). A pinhole (lens_radius 0) draws no random
 * numbers, so its samples stay those of a camera without a lens. Draws after
 * the pixel jitter, in the megakernel and the wavefront camera alike. The
 * host never gives an orthographic camera a lens. */
static inline void camera_lens(constant const CameraData* cam, Rng* rng, Ray* r) {
    if (!(cam->lens_radius > 0.0f)) return;
    float u1 = rng_next(rng), u2 = rng_next(rng);
    float2 disk = sample_concentric_disk(u1, u2) * cam->lens_radius;
    float3 right = normalize3(load3c(cam->right)), up = normalize3(load3c(cam->up));
    float3 offset = disk.x * right + disk.y * up;
    float3 fwd = load3c(cam->forward);
    float3 focus = r->d * (cam->focus_distance / dot(r->d, fwd));
    r->o = r->o + offset;
    r->d = normalize3(focus - offset);
}

#endif
