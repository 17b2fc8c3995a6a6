/* Pinhole camera. Conventions: pixel (0, 0) is the top-left corner of the
 * image, rows go down; image right is forward x up (right-handed); each sample
 * is jittered uniformly inside its pixel (a box filter). */

typedef struct {
    float3 o;
    float3 d;
} Ray;

inline float3 load3(const float* p) { return (float3)(p[0], p[1], p[2]); }
inline float3 load3g(global const float* p) { return (float3)(p[0], p[1], p[2]); }
inline float3 load3c(constant const float* p) { return (float3)(p[0], p[1], p[2]); }

/* (jx, jy) in [0,1)^2 is the position inside the pixel. */
inline Ray camera_ray(constant const CameraData* cam, uint px, uint py, float jx, float jy) {
    float x = 2.0f * ((float)px + jx) / (float)cam->width - 1.0f;
    float y = 1.0f - 2.0f * ((float)py + jy) / (float)cam->height;
    Ray r;
    r.o = load3c(cam->eye);
    r.d = normalize(load3c(cam->forward) + x * load3c(cam->right) + y * load3c(cam->up));
    return r;
}
