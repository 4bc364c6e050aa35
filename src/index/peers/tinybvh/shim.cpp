// The C interface of the `tinybvh-bvh8` peer: tinybvh's BVH8_CPU (AVX2 traversal of 8-wide
// nodes, leaves of up to four triangles) built, traced and freed through plain functions, so
// the Rust side needs no C++ binding. Compiled by build.rs with the feature `tinybvh`.
//
// Rays are filled in here field by field instead of by tinybvh's Ray constructor, which
// normalizes the direction: `t` stays in the caller's units (the direction as given).

#define TINYBVH_IMPLEMENTATION
#include "tiny_bvh.h"

#include <cstdint>
#include <cstring>
#include <new>

using tinybvh::BVH;
using tinybvh::BVH8_CPU;
using tinybvh::bvhvec3;
using tinybvh::bvhvec4;
using tinybvh::bvhvec4slice;
using tinybvh::Ray;

namespace {

Ray make_ray(const float* o, const float* d, float t_max) {
    Ray r;
    std::memset(static_cast<void*>(&r), 0, sizeof(Ray));
    r.O = bvhvec3(o[0], o[1], o[2]);
    r.D = bvhvec3(d[0], d[1], d[2]);
    r.rD = tinybvh::tinybvh_safercp(r.D);
    r.mask = RAY_MASK_INTERSECT_ALL;
    r.hit.t = t_max;
    r.hit.prim = UINT32_MAX;
    return r;
}

}  // namespace

extern "C" {

// Builds over `tris` triangles, `verts` holding 3 vertices per triangle of 4 floats each
// (x, y, z, unused), with tinybvh's reference binned SAH builder, then BVH8_CPU's own
// conversion (leaves combined and split to at most 4 triangles, 8-wide collapse). `threaded`
// lets the builder use its job system (tinybvh uses it only from 50,000 triangles up).
// Returns null when tinybvh throws. `verts` may be freed once this returns.
BVH8_CPU* accelbench_tinybvh_build(const float* verts, uint32_t tris, int threaded) {
    try {
        BVH8_CPU* h = new BVH8_CPU();
        BVH& b = h->bvh8.bvh;
        b.context = h->bvh8.context = h->context;
        b.threadedBuild = threaded != 0;
        b.Build(bvhvec4slice(reinterpret_cast<const bvhvec4*>(verts), tris * 3, sizeof(bvhvec4)));
        b.PrepareBuild4_8();
        b.Compact();
        h->bvh8.ConvertFrom(b, true);
        h->ConvertFrom(h->bvh8);
        return h;
    } catch (...) {
        return nullptr;
    }
}

// Nodes and leaves of the 8-wide tree, and the bytes of the BVH8_CPU block array.
void accelbench_tinybvh_info(const BVH8_CPU* h, uint32_t* nodes, uint32_t* leaves, uint64_t* bytes) {
    *nodes = h->bvh8.usedNodes;
    *leaves = h->bvh8.LeafCount(0);
    *bytes = uint64_t(h->allocatedBlocks) * 16;
}

// The closest hit with t below `t_max`: returns 1 and writes `t` and `prim`, or returns 0.
int accelbench_tinybvh_intersect(const BVH8_CPU* h, const float* o, const float* d, float t_max,
                                 float* t, uint32_t* prim) {
    Ray r = make_ray(o, d, t_max);
    h->Intersect(r);
    *t = r.hit.t;
    *prim = r.hit.prim;
    return r.hit.t < t_max ? 1 : 0;
}

// Whether anything is hit with t below `t_max` (tinybvh stops at the first hit it finds).
int accelbench_tinybvh_occluded(const BVH8_CPU* h, const float* o, const float* d, float t_max) {
    return h->IsOccluded(make_ray(o, d, t_max)) ? 1 : 0;
}

void accelbench_tinybvh_free(BVH8_CPU* h) { delete h; }

}  // extern "C"
