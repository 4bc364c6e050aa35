// The C interface of the `tinybvh-bvh8` peer: tinybvh's BVH8_CPU (AVX2 traversal of 8-wide
// nodes, leaves of up to four triangles) built, traced and freed through plain functions, so
// the Rust side needs no C++ binding. Compiled by build.rs with the feature `tinybvh`.
//
// Rays are written here in whole 16-byte lanes (`make_ray`) instead of by tinybvh's Ray
// constructor, which normalizes the direction: `t` stays in the caller's units (the direction
// as given). Origins and directions come as pointers to 16-byte aligned lanes of four floats
// (glam's Vec3A on the Rust side), the fourth ignored.

#define TINYBVH_IMPLEMENTATION
#include "tiny_bvh.h"

#include <immintrin.h>

// BVH8_CPU traverses with AVX2 and FMA (without them tinybvh's Intersect exits the process);
// `make_ray` uses them too. build.rs compiles for the building machine (-march=native).
#if !defined(__AVX2__) || !defined(__FMA__)
#error "the tinybvh-bvh8 peer needs a CPU with AVX2 and FMA; on other CPUs use --features embree instead of peers or tinybvh"
#endif

#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <new>

using tinybvh::BVH;
using tinybvh::BVH8_CPU;
using tinybvh::bvhvec3;
using tinybvh::bvhvec4;
using tinybvh::bvhvec4slice;
using tinybvh::Ray;

namespace {

// tinybvh fills the unused child slots of an 8-wide node with the box [1e30, 1.00001e30]^3 and a
// child index with EMPTY_BIT set. A ray whose slab test passes that box descends into the slot
// and reads outside the tree (a segfault): with t_max = +inf, for example (1, 1, 1) from
// (-100, -100, -100), or a direction like (0, 0, 1e-15), whose 1e30 reciprocals (tinybvh's
// safercp) put every slab at +inf. tinybvh's own rays avoid it with t = 1e30 (BVH_FAR) and
// normalized directions; ours keep the caller's t_max and direction, so the shim evaluates the
// slab test on that box exactly as BVH8_CPU's traversal does (the same fused multiply-subtract,
// max and min, in the same order) and, where it passes, lowers the ray's t below the box's entry.
// That changes no hit: whatever lies in front of the box is still found.
constexpr float kEmptyMin = 1e30f, kEmptyMax = 1.00001e30f;

// _mm256_max_ps and _mm256_min_ps on one lane (the second operand when either is NaN).
float max_ps(float a, float b) { return a > b ? a : b; }
float min_ps(float a, float b) { return a < b ? a : b; }

// The t below which a ray from `o` with reciprocal direction `rd` cannot reach an empty child
// slot: `t_max`, or just below the slot's entry. Per axis BVH8_CPU's slab terms:
// t1 = fma(near, rd, -(o * rd)), t2 = fma(far, rd, -(o * rd)), with `near` the slot's low
// corner where the direction is positive (or +0) and its high corner otherwise.
float below_empty_slots(__m128 o, __m128 d, __m128 rd, float t_max) {
    const __m128 pos = _mm_cmpge_ps(d, _mm_setzero_ps());
    const __m128 lo = _mm_set1_ps(kEmptyMin), hi = _mm_set1_ps(kEmptyMax);
    const __m128 ro = _mm_mul_ps(o, rd);
    alignas(16) float t1[4], t2[4];
    _mm_store_ps(t1, _mm_fmsub_ps(_mm_blendv_ps(hi, lo, pos), rd, ro));
    _mm_store_ps(t2, _mm_fmsub_ps(_mm_blendv_ps(lo, hi, pos), rd, ro));
    const float tmin = max_ps(max_ps(max_ps(0.0f, t1[0]), t1[1]), t1[2]);
    const float tmax = min_ps(min_ps(min_ps(t2[0], t_max), t2[1]), t2[2]);
    return tmin <= tmax ? std::nextafter(tmin, -INFINITY) : t_max;
}

// tinybvh_safercp on each lane: 1 / x where |x| > 1e-12, else BVH_FAR with the sign of x
// (+BVH_FAR for -0, as `x >= 0` decides there).
__m128 safercp(__m128 d) {
    const __m128 abs = _mm_andnot_ps(_mm_set1_ps(-0.0f), d);
    const __m128 far = _mm_blendv_ps(_mm_set1_ps(-BVH_FAR), _mm_set1_ps(BVH_FAR),
                                     _mm_cmpge_ps(d, _mm_setzero_ps()));
    return _mm_blendv_ps(far, _mm_div_ps(_mm_set1_ps(1.0f), d), _mm_cmpgt_ps(abs, _mm_set1_ps(1e-12f)));
}

// tinybvh's VALIDATE_RAY exits the process when this sum is NaN, which finite rays reach when
// their coordinates overflow it (components near 3.4e38 of both signs).
bool fails_validation(const Ray& r) {
    const float test = r.D.x + r.D.y + r.D.z + r.hit.t + r.O.x + r.O.y + r.O.z;
    return std::isnan(test);
}

// tinybvh's Ray: four 16-byte lanes (origin and mask; direction and instIdx; the reciprocal
// direction and hit.inst; hit.t, u, v and prim), then 64 bytes of user data (hit.auxData and
// the union), which the shim zeroes as tinybvh's constructor does.
static_assert(sizeof(Ray) == 128 && alignof(Ray) == 64);
static_assert(offsetof(Ray, O) == 0 && offsetof(Ray, mask) == 12 && offsetof(Ray, D) == 16);
static_assert(offsetof(Ray, instIdx) == 28 && offsetof(Ray, rD) == 32);
static_assert(offsetof(Ray, hit) + offsetof(tinybvh::Intersection, inst) == 44);
static_assert(offsetof(Ray, hit) + offsetof(tinybvh::Intersection, t) == 48);
static_assert(offsetof(Ray, hit) + offsetof(tinybvh::Intersection, prim) == 60);

// tinybvh's ray for ours (`o` and `d`: 16-byte aligned lanes whose fourth float is ignored),
// with t (hit.t) set from `t_max` as above, written in whole lanes (no field by field stores, no
// memset call: this runs once per ray). Returns false when tinybvh cannot take it
// (`fails_validation`): the caller answers a miss without tracing.
bool make_ray(const float* o, const float* d, float t_max, Ray& r) {
    const __m128 xyz = _mm_castsi128_ps(_mm_set_epi32(0, -1, -1, -1));
    const __m128 ov = _mm_and_ps(_mm_load_ps(o), xyz), dv = _mm_and_ps(_mm_load_ps(d), xyz);
    const __m128 rd = _mm_and_ps(safercp(dv), xyz);
    const float t = below_empty_slots(ov, dv, rd, t_max);
    float* lanes = reinterpret_cast<float*>(&r);
    _mm_store_ps(lanes, _mm_or_ps(ov, _mm_castsi128_ps(_mm_set_epi32(RAY_MASK_INTERSECT_ALL, 0, 0, 0))));
    _mm_store_ps(lanes + 4, dv);
    _mm_store_ps(lanes + 8, rd);
    _mm_store_ps(lanes + 12, _mm_blend_ps(_mm_castsi128_ps(_mm_set_epi32(-1, 0, 0, 0)), _mm_set_ss(t), 1));
    _mm256_store_ps(lanes + 16, _mm256_setzero_ps());
    _mm256_store_ps(lanes + 24, _mm256_setzero_ps());
    return !fails_validation(r);
}

// What tinybvh holds through its allocation hooks (BVHContext), in bytes: every array of the
// build goes through them except BVH8_CPU's block array (malloc64), added by the build.
struct Meter {
    std::atomic<uint64_t> held{0}, peak{0};
};

// Each block carries its size in a 64-byte header, so the free hook knows what it returns and
// the block stays 64-byte aligned as tinybvh's own malloc64 makes it.
constexpr size_t kHeader = 64;

void* metered_malloc(size_t size, void* userdata) {
    if (size == 0) return nullptr;
    void* block = tinybvh::malloc64(size + kHeader, nullptr);
    if (!block) return nullptr;
    *static_cast<uint64_t*>(block) = size;
    Meter* m = static_cast<Meter*>(userdata);
    const uint64_t now = m->held.fetch_add(size) + size;
    uint64_t peak = m->peak.load();
    while (now > peak && !m->peak.compare_exchange_weak(peak, now)) {
    }
    return static_cast<char*>(block) + kHeader;
}

void metered_free(void* ptr, void* userdata) {
    if (!ptr) return;
    void* block = static_cast<char*>(ptr) - kHeader;
    static_cast<Meter*>(userdata)->held.fetch_sub(*static_cast<uint64_t*>(block));
    tinybvh::free64(block, nullptr);
}

}  // namespace

// A build with its meter; the meter outlives the tree (members are destroyed in reverse order),
// whose destructor frees through the hooks.
struct AccelbenchTinyBvh {
    Meter meter;
    BVH8_CPU bvh;
};

extern "C" {

// Builds over `tris` triangles, `verts` holding 3 vertices per triangle of 4 floats each
// (x, y, z, unused), with tinybvh's reference binned SAH builder, then BVH8_CPU's own
// conversion (leaves combined and split to at most 4 triangles, 8-wide collapse). `threaded`
// lets the builder use its job system (tinybvh uses it only from 50,000 triangles up).
// Returns null when tinybvh throws. `verts` may be freed once this returns.
AccelbenchTinyBvh* accelbench_tinybvh_build(const float* verts, uint32_t tris, int threaded) {
    try {
        AccelbenchTinyBvh* a = new AccelbenchTinyBvh();
        BVH8_CPU* h = &a->bvh;
        h->context.malloc = metered_malloc;
        h->context.free = metered_free;
        h->context.userdata = &a->meter;
        BVH& b = h->bvh8.bvh;
        b.context = h->bvh8.context = h->context;
        b.threadedBuild = threaded != 0;
        b.Build(bvhvec4slice(reinterpret_cast<const bvhvec4*>(verts), tris * 3, sizeof(bvhvec4)));
        b.PrepareBuild4_8();
        b.Compact();
        h->bvh8.ConvertFrom(b, true);
        h->ConvertFrom(h->bvh8);
        // The block array is allocated last, with everything above still held.
        const uint64_t blocks = uint64_t(h->allocatedBlocks) * sizeof(*h->bvh8Data);
        const uint64_t at_end = a->meter.held.load() + blocks;
        if (at_end > a->meter.peak.load()) a->meter.peak.store(at_end);
        return a;
    } catch (...) {
        return nullptr;
    }
}

// Nodes and leaves of the 8-wide tree; the bytes of the BVH8_CPU block array (64-byte blocks:
// tinybvh's comment on `allocatedBlocks` says 16, its allocation is `blocksNeeded * 64`), what
// tinybvh holds beside it (the binary and 8-wide trees it was converted from, which BVH8_CPU
// keeps), and the most it held during the build.
void accelbench_tinybvh_info(const AccelbenchTinyBvh* a, uint32_t* nodes, uint32_t* leaves,
                             uint64_t* bytes, uint64_t* other_bytes, uint64_t* peak_bytes) {
    const BVH8_CPU* h = &a->bvh;
    *nodes = h->bvh8.usedNodes;
    *leaves = h->bvh8.LeafCount(0);
    *bytes = uint64_t(h->allocatedBlocks) * sizeof(*h->bvh8Data);
    *other_bytes = a->meter.held.load();
    *peak_bytes = a->meter.peak.load();
}

// A closest hit: `prim` is UINT32_MAX when there is none (the peers take fewer triangles).
struct AccelbenchTinyHit {
    float t;
    uint32_t prim;
};

// The closest hit with t below `t_max`.
AccelbenchTinyHit accelbench_tinybvh_intersect(const AccelbenchTinyBvh* a, const float* o,
                                               const float* d, float t_max) {
    Ray r;
    if (!make_ray(o, d, t_max, r)) return {0.0f, UINT32_MAX};
    const float t_start = r.hit.t;
    a->bvh.Intersect(r);
    return {r.hit.t, r.hit.t < t_start ? r.hit.prim : UINT32_MAX};
}

// Whether anything is hit with t below `t_max` (tinybvh stops at the first hit it finds).
int accelbench_tinybvh_occluded(const AccelbenchTinyBvh* a, const float* o, const float* d,
                                float t_max) {
    Ray r;
    return make_ray(o, d, t_max, r) && a->bvh.IsOccluded(r) ? 1 : 0;
}

// Whether tinybvh cannot take the ray (`fails_validation`): the two calls above answer it as a
// miss without tracing it.
int accelbench_tinybvh_refuses(const float* o, const float* d, float t_max) {
    Ray r;
    return make_ray(o, d, t_max, r) ? 0 : 1;
}

// The block array came from malloc64, not the hooks the destructor frees through.
void accelbench_tinybvh_free(AccelbenchTinyBvh* a) {
    tinybvh::free64(a->bvh.bvh8Data, nullptr);
    a->bvh.bvh8Data = nullptr;
    delete a;
}

}  // extern "C"
