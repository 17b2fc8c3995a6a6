/* Every struct of kernels/shared_structs.h and every field of each, listed
 * once for the host test and the device probe alike (X macros: the caller
 * passes S(struct) and F(struct, field)). The test also checks that each
 * struct's fields tile it without a gap, so a field missing here is noticed. */
#ifndef CLP_SHARED_STRUCT_FIELDS_H
#define CLP_SHARED_STRUCT_FIELDS_H

#define CLP_SHARED_STRUCTS(S) \
    S(BvhNode64) S(Bvh4Node128) S(TriVerts) S(Material) S(MaterialExt) S(Light) S(AliasEntry) S(LightBvhNode) S(CameraData) S(FrameParams) S(Counters) \
    S(AccumPixel) S(BatchRay) S(Hit) S(TextureDesc) S(Instance)

#define CLP_SHARED_FIELDS(F) \
    F(Instance, object_to_world) F(Instance, world_to_object) F(Instance, blas_root) F(Instance, first_tri) \
    F(Instance, first_prim) F(Instance, det_sign) F(Instance, mesh) F(Instance, pad0) F(Instance, pad1) F(Instance, pad2) \
    F(BvhNode64, lo0) F(BvhNode64, child0) F(BvhNode64, hi0) F(BvhNode64, count0) \
    F(BvhNode64, lo1) F(BvhNode64, child1) F(BvhNode64, hi1) F(BvhNode64, count1) \
    F(Bvh4Node128, lo_x) F(Bvh4Node128, hi_x) F(Bvh4Node128, lo_y) F(Bvh4Node128, hi_y) F(Bvh4Node128, lo_z) F(Bvh4Node128, hi_z) \
    F(Bvh4Node128, child) F(Bvh4Node128, count) \
    F(TriVerts, v0) F(TriVerts, prim) F(TriVerts, v1) F(TriVerts, light) F(TriVerts, v2) F(TriVerts, pad2) \
    F(Material, albedo) F(Material, kind) F(Material, emission) F(Material, flags) F(Material, roughness) \
    F(Material, ior) F(Material, metallic) F(Material, pad0) \
    F(MaterialExt, texture) F(MaterialExt, alpha) F(MaterialExt, alpha_mode) F(MaterialExt, alpha_cutoff) \
    F(MaterialExt, normal_scale) F(MaterialExt, clearcoat) F(MaterialExt, clearcoat_roughness) \
    F(MaterialExt, clearcoat_normal_scale) F(MaterialExt, transmission) \
    F(Light, a) F(Light, type) F(Light, b) F(Light, flags) F(Light, c) F(Light, cos_outer) F(Light, L) \
    F(Light, cos_inner) \
    F(AliasEntry, prob) F(AliasEntry, alias) F(AliasEntry, pmf) F(AliasEntry, pad) \
    F(LightBvhNode, qbounds) F(LightBvhNode, axis) F(LightBvhNode, power) F(LightBvhNode, cones) \
    F(LightBvhNode, child) F(LightBvhNode, flags) \
    F(CameraData, eye) F(CameraData, width) F(CameraData, forward) F(CameraData, height) F(CameraData, right) \
    F(CameraData, lens_radius) F(CameraData, up) F(CameraData, focus_distance) \
    F(CameraData, orthographic) F(CameraData, pad0) F(CameraData, pad1) F(CameraData, pad2) \
    F(FrameParams, camera) F(FrameParams, seed) F(FrameParams, first_sample) F(FrameParams, samples) \
    F(FrameParams, rr_rule) F(FrameParams, rr_min_depth) F(FrameParams, pixel_offset) \
    F(FrameParams, pixel_count) F(FrameParams, light_count) F(FrameParams, env_light) F(FrameParams, ao_distance) \
    F(FrameParams, depth_scale) F(FrameParams, env_color) F(FrameParams, env_width) F(FrameParams, env_scale) \
    F(FrameParams, env_rot_cos) F(FrameParams, env_rot_sin) F(FrameParams, env_height) F(FrameParams, scene_flags) \
    F(FrameParams, attr_stride) F(FrameParams, adaptive) F(FrameParams, pad2) F(FrameParams, pad3) \
    F(FrameParams, lbvh_origin) F(FrameParams, lbvh_node_count) F(FrameParams, lbvh_scale) F(FrameParams, lbvh_infinite_count) \
    F(Counters, rays) F(Counters, nonfinite) F(Counters, pad0) F(Counters, pad1) \
    F(AccumPixel, sum) F(AccumPixel, comp) \
    F(BatchRay, o) F(BatchRay, tmax) F(BatchRay, d) F(BatchRay, src) \
    F(Hit, t) F(Hit, b1) F(Hit, b2) F(Hit, tri) \
    F(TextureDesc, offset) F(TextureDesc, width) F(TextureDesc, height) F(TextureDesc, flags)

#endif
