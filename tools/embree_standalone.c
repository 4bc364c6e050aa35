/*
 * Embree 3 outside the suite, on the same rays: the check that the suite's `embree` and
 * `embree-fast` peers cost what Embree costs when called from C (README, "Peers").
 *
 * Build (Debian: apt-get install libembree-dev):
 *   cc -O2 -o /tmp/embree_standalone tools/embree_standalone.c -lembree3
 * Rays (../shared/PROTOCOL.md, written by the suite):
 *   cargo run --release -- rays --scene ../shared/meshes/stanford_bunny.obj --set primary --out /tmp/bunny_primary.rays
 *   cargo run --release -- rays --scene ../shared/meshes/stanford_bunny.obj --set incoherent --out /tmp/bunny_incoherent.rays
 * Run (one thread: the calling thread traces; the build uses threads=1):
 *   /tmp/embree_standalone ../shared/meshes/stanford_bunny.obj /tmp/bunny_primary.rays robust 3
 *   /tmp/embree_standalone ../shared/meshes/stanford_bunny.obj /tmp/bunny_incoherent.rays fast 3
 *
 * Like the suite: build quality medium, RTC_SCENE_FLAG_ROBUST for `robust`, one rtcIntersect1
 * per ray with an incoherent context, the ray's tnear/tfar as given. Prints the median of the
 * repeats in Mrays/s and the number of hits (compare with the suite's `hits` column).
 *
 * The ray's origin with tnear and its direction with time are each written with one 16-byte
 * store, as the suite does (src/index/peers/embree/rtc_ray.rs): rtcIntersect1 loads them as
 * 16-byte vectors, and a vector load over several narrower stores (field by field) cannot be
 * store-forwarded; written field by field, this program ran 0.81x as fast on the bunny's primary
 * rays and 0.94x on its incoherent rays (README, "Peers").
 *
 * HITS=1 stores each ray's answer (its t and primitive, 8 bytes) in an array as it goes, as the
 * suite's timed pass does with every answer (it checks them against its counting pass): without
 * it the program keeps only the count of hits.
 *
 * RAY_STRIDE=96 lays the records out 96 bytes apart, as the suite's `Ray` is (the ray's memory
 * traffic without its extra fields). The traced loop is one function, `trace_all`, so that
 * Callgrind's inclusive count of it is the cost of the rays; tools/peers_standalone.sh runs this
 * program and the suite's `trace` side by side, under Callgrind and on the clock
 * (docs/results/2026-12-07-peers-standalone.md).
 */
#include <embree3/rtcore.h>
#include <emmintrin.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef struct { float *v; size_t nv, cv; unsigned *t; size_t nt, ct; } Mesh;

static void *grow(void *p, size_t *cap, size_t need, size_t elem) {
    if (need <= *cap) return p;
    *cap = need * 2;
    p = realloc(p, *cap * elem);
    if (!p) { fprintf(stderr, "out of memory\n"); exit(1); }
    return p;
}

/* Positions and faces of an OBJ file, faces fan-triangulated (v0, vi, vi+1) as the suite does. */
static Mesh load_obj(const char *path) {
    Mesh m = {0};
    FILE *f = fopen(path, "r");
    if (!f) { perror(path); exit(1); }
    char line[4096];
    while (fgets(line, sizeof line, f)) {
        if (line[0] == 'v' && line[1] == ' ') {
            m.v = grow(m.v, &m.cv, 3 * (m.nv + 1), sizeof(float));
            if (sscanf(line + 2, "%f %f %f", &m.v[3 * m.nv], &m.v[3 * m.nv + 1], &m.v[3 * m.nv + 2]) != 3) {
                fprintf(stderr, "%s: bad vertex line: %s", path, line);
                exit(1);
            }
            m.nv++;
        } else if (line[0] == 'f' && line[1] == ' ') {
            long idx[64];
            int n = 0;
            for (char *tok = strtok(line + 2, " \t\r\n"); tok && n < 64; tok = strtok(NULL, " \t\r\n")) {
                long i = strtol(tok, NULL, 10);
                idx[n++] = i < 0 ? (long)m.nv + i : i - 1;
            }
            for (int k = 1; k + 1 < n; k++) {
                m.t = grow(m.t, &m.ct, 3 * (m.nt + 1), sizeof(unsigned));
                m.t[3 * m.nt] = (unsigned)idx[0];
                m.t[3 * m.nt + 1] = (unsigned)idx[k];
                m.t[3 * m.nt + 2] = (unsigned)idx[k + 1];
                m.nt++;
            }
        }
    }
    fclose(f);
    return m;
}

static float *load_rays(const char *path, size_t *n) {
    FILE *f = fopen(path, "rb");
    if (!f) { perror(path); exit(1); }
    fseek(f, 0, SEEK_END);
    long bytes = ftell(f);
    fseek(f, 0, SEEK_SET);
    if (bytes <= 0 || bytes % 32) { fprintf(stderr, "%s: size %ld is not a multiple of 32\n", path, bytes); exit(1); }
    float *r = malloc((size_t)bytes);
    if (!r || fread(r, 1, (size_t)bytes, f) != (size_t)bytes) { fprintf(stderr, "%s: read failed\n", path); exit(1); }
    fclose(f);
    *n = (size_t)bytes / 32;
    return r;
}

static double now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* A ray's answer as a caller keeps it (HITS=1): the distance and the primitive, or prim ~0u. */
typedef struct { float t; unsigned prim; } Answer;

/* One rtcIntersect1 per record of `rays` (`stride` floats apart); returns the number of hits.
 * With `out` each ray's answer is also stored. Inlined into the two traced regions below, where
 * `out` is a constant, so the region without answers pays nothing for the option. */
static inline __attribute__((always_inline)) size_t trace_loop(RTCScene s, const float *rays,
                                                               size_t nrays, size_t stride,
                                                               Answer *out) {
    const __m128 dir_lanes = _mm_castsi128_ps(_mm_set_epi32(0, -1, -1, -1));
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    size_t hits = 0;
    for (size_t i = 0; i < nrays; i++) {
        const float *r = rays + stride * i;
        struct RTCRayHit rh;
        /* org_x..z, tnear = r[0..3]; dir_x..z = r[4..6] with time = 0 (lane 3 cleared). */
        _mm_store_ps(&rh.ray.org_x, _mm_loadu_ps(r));
        _mm_store_ps(&rh.ray.dir_x, _mm_and_ps(_mm_loadu_ps(r + 4), dir_lanes));
        rh.ray.tfar = r[7];
        rh.ray.mask = 0xFFFFFFFFu; rh.ray.id = 0; rh.ray.flags = 0;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(s, &ctx, &rh);
        int hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        hits += hit;
        if (out) {
            out[i].t = rh.ray.tfar;
            out[i].prim = hit ? rh.hit.primID : ~0u;
        }
    }
    return hits;
}

/* The traced regions, one function each so that Callgrind's inclusive count of one is the cost
 * of the rays: `trace_all` keeps only the count of hits, `trace_all_hits` (HITS=1) also every
 * ray's answer, as the suite's timed pass does. */
__attribute__((noinline)) static size_t trace_all(RTCScene s, const float *rays, size_t nrays,
                                                  size_t stride) {
    return trace_loop(s, rays, nrays, stride, NULL);
}
__attribute__((noinline)) static size_t trace_all_hits(RTCScene s, const float *rays,
                                                       size_t nrays, size_t stride, Answer *out) {
    return trace_loop(s, rays, nrays, stride, out);
}

int main(int argc, char **argv) {
    if (argc != 5 || (strcmp(argv[3], "robust") && strcmp(argv[3], "fast"))) {
        fprintf(stderr, "usage: %s MESH.obj RAYS.rays robust|fast REPEATS\n", argv[0]);
        return 2;
    }
    Mesh m = load_obj(argv[1]);
    size_t nrays;
    float *rays = load_rays(argv[2], &nrays);
    int repeats = atoi(argv[4]) > 0 ? atoi(argv[4]) : 1;
    /* RAY_STRIDE=96 spreads the records 96 bytes apart, as the suite's `Ray` is laid out. */
    const char *stride_env = getenv("RAY_STRIDE");
    size_t stride = stride_env ? (size_t)atoi(stride_env) / 4 : 8;
    if (stride < 8 || stride % 4) { fprintf(stderr, "RAY_STRIDE: a multiple of 16 from 32\n"); return 2; }
    if (stride != 8) {
        float *spread = aligned_alloc(16, nrays * stride * 4);
        if (!spread) { fprintf(stderr, "out of memory\n"); return 1; }
        memset(spread, 0, nrays * stride * 4);
        for (size_t i = 0; i < nrays; i++) memcpy(spread + stride * i, rays + 8 * i, 32);
        free(rays);
        rays = spread;
    }

    RTCDevice dev = rtcNewDevice("threads=1");
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *vb = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, m.nv);
    memcpy(vb, m.v, m.nv * 12);
    unsigned *ib = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, m.nt);
    memcpy(ib, m.t, m.nt * 12);
    rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_MEDIUM);
    rtcCommitGeometry(g);
    RTCScene s = rtcNewScene(dev);
    rtcSetSceneFlags(s, strcmp(argv[3], "robust") ? RTC_SCENE_FLAG_NONE : RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_MEDIUM);
    rtcAttachGeometry(s, g);
    rtcReleaseGeometry(g);
    double t0 = now();
    rtcCommitScene(s);
    double build = now() - t0;

    /* HITS=1 keeps every ray's answer in an array (written before timing, as the suite's is). */
    const char *hits_env = getenv("HITS");
    Answer *out = NULL;
    if (hits_env && strcmp(hits_env, "0")) {
        out = malloc(nrays * sizeof(Answer));
        if (!out) { fprintf(stderr, "out of memory\n"); return 1; }
        memset(out, 0, nrays * sizeof(Answer));
    }
    double *times = malloc(sizeof(double) * (size_t)repeats);
    size_t hits = 0;
    for (int rep = 0; rep < repeats; rep++) {
        double start = now();
        hits = out ? trace_all_hits(s, rays, nrays, stride, out) : trace_all(s, rays, nrays, stride);
        times[rep] = now() - start;
    }
    qsort(times, (size_t)repeats, sizeof(double), cmp_double);
    double median = times[repeats / 2];
    printf("%s %s: %zu triangles, %zu rays, build %.2f ms, median %.2f ms, %.3f Mrays/s, %zu hits\n",
           argv[2], argv[3], m.nt, nrays, build * 1e3, median * 1e3, nrays / median / 1e6, hits);
    rtcReleaseScene(s);
    rtcReleaseDevice(dev);
    free(times);
    free(out);
    free(rays);
    free(m.v);
    free(m.t);
    return 0;
}
