/*
 * tinybvh outside the suite, on the same rays: the check that the suite's `tinybvh-bvh8` peer
 * costs what tinybvh costs when called directly from C++ (docs/peers.md, "Peers at their own
 * speed"). The counterpart of tools/embree_standalone.c.
 *
 * Build (the same header and flags as build.rs compiles the suite's shim with):
 *   g++ -O3 -std=c++20 -march=native -Ithird_party/tinybvh -o /tmp/tinybvh_standalone \
 *       tools/tinybvh_standalone.cpp -lpthread
 * Rays (../shared/PROTOCOL.md, written by the suite):
 *   cargo run --release -- rays --scene ../shared/meshes/stanford_bunny.obj --set primary --out /tmp/p.rays
 * Run (one thread):
 *   /tmp/tinybvh_standalone ../shared/meshes/stanford_bunny.obj /tmp/p.rays 5
 * tools/peers_standalone.sh runs it and the suite's `trace` on the same rays, also under
 * Callgrind (instructions per ray; Valgrind does not decode AVX-512, so for Callgrind build it
 * with -march=x86-64-v3 instead of -march=native).
 *
 * Like the suite's shim (src/index/peers/tinybvh/shim.cpp): 3 vertices per triangle (x, y, z,
 * 0), tinybvh's reference binned SAH build, then BVH8_CPU's own conversion (the steps of
 * BVH8_CPU::Build with Build in place of BuildDefault, which picks BuildAVX), one
 * BVH8_CPU::Intersect per ray. The ray is made as a tinybvh user makes it: tinybvh's Ray
 * constructor (which normalizes the direction; the protocol's directions are unit already) with
 * t = min(tfar, BVH_FAR), tinybvh's own far distance, which needs none of the shim's guards
 * against rays that reach the 1e30 boxes of empty child slots. Prints the median of the repeats
 * in Mrays/s and the number of hits (compare with the suite's `hits`).
 */
#define TINYBVH_IMPLEMENTATION
#include "tiny_bvh.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using tinybvh::BVH;
using tinybvh::BVH8_CPU;
using tinybvh::bvhvec3;
using tinybvh::bvhvec4;
using tinybvh::bvhvec4slice;
using tinybvh::Ray;

// Triangles of an OBJ file, 3 vertices each, faces fan-triangulated (v0, vi, vi+1).
static std::vector<bvhvec4> load_obj(const char* path) {
    std::ifstream f(path);
    if (!f) { std::perror(path); std::exit(1); }
    std::vector<bvhvec3> v;
    std::vector<bvhvec4> tris;
    std::string line;
    while (std::getline(f, line)) {
        if (line.size() > 2 && line[0] == 'v' && line[1] == ' ') {
            bvhvec3 p;
            if (std::sscanf(line.c_str() + 2, "%f %f %f", &p.x, &p.y, &p.z) != 3) {
                std::fprintf(stderr, "%s: bad vertex line: %s\n", path, line.c_str());
                std::exit(1);
            }
            v.push_back(p);
        } else if (line.size() > 2 && line[0] == 'f' && line[1] == ' ') {
            std::istringstream s(line.substr(2));
            std::vector<long> idx;
            std::string tok;
            while (s >> tok) {
                const long i = std::strtol(tok.c_str(), nullptr, 10);
                idx.push_back(i < 0 ? long(v.size()) + i : i - 1);
            }
            for (size_t k = 1; k + 1 < idx.size(); k++)
                for (long i : {idx[0], idx[k], idx[k + 1]}) tris.push_back(bvhvec4(v[i], 0));
        }
    }
    return tris;
}

static std::vector<float> load_rays(const char* path) {
    std::ifstream f(path, std::ios::binary | std::ios::ate);
    if (!f) { std::perror(path); std::exit(1); }
    const long bytes = long(f.tellg());
    if (bytes <= 0 || bytes % 32) {
        std::fprintf(stderr, "%s: size %ld is not a multiple of 32\n", path, bytes);
        std::exit(1);
    }
    std::vector<float> r(size_t(bytes) / 4);
    f.seekg(0);
    f.read(reinterpret_cast<char*>(r.data()), bytes);
    return r;
}

// The traced region, one function so that Callgrind's inclusive count of it is the cost of the
// rays: one Ray and one Intersect per record; returns the number of hits.
__attribute__((noinline)) static size_t trace_all(const BVH8_CPU& bvh, const float* rays, size_t n) {
    size_t hits = 0;
    for (size_t i = 0; i < n; i++) {
        const float* r = rays + 8 * i;
        Ray ray(bvhvec3(r[0], r[1], r[2]), bvhvec3(r[4], r[5], r[6]), std::min(r[7], BVH_FAR));
        bvh.Intersect(ray);
        hits += ray.hit.t < BVH_FAR;
    }
    return hits;
}

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: %s MESH.obj RAYS.rays REPEATS\n", argv[0]);
        return 2;
    }
    const std::vector<bvhvec4> verts = load_obj(argv[1]);
    const std::vector<float> rays = load_rays(argv[2]);
    const size_t nrays = rays.size() / 8, ntris = verts.size() / 3;
    const int repeats = std::max(1, std::atoi(argv[3]));

    using clock = std::chrono::steady_clock;
    const auto t0 = clock::now();
    BVH8_CPU bvh;
    BVH& b = bvh.bvh8.bvh;
    b.context = bvh.bvh8.context = bvh.context;
    b.threadedBuild = false;
    b.Build(bvhvec4slice(verts.data(), uint32_t(verts.size()), sizeof(bvhvec4)));
    b.PrepareBuild4_8();
    b.Compact();
    bvh.bvh8.ConvertFrom(b, true);
    bvh.ConvertFrom(bvh.bvh8);
    const double build = std::chrono::duration<double>(clock::now() - t0).count();

    std::vector<double> times;
    size_t hits = 0;
    for (int rep = 0; rep < repeats; rep++) {
        const auto start = clock::now();
        hits = trace_all(bvh, rays.data(), nrays);
        times.push_back(std::chrono::duration<double>(clock::now() - start).count());
    }
    std::sort(times.begin(), times.end());
    const double median = times[times.size() / 2];
    std::printf("%s: %zu triangles, %zu rays, build %.2f ms, median %.2f ms, %.3f Mrays/s, %zu hits\n",
                argv[2], ntris, nrays, build * 1e3, median * 1e3, nrays / median / 1e6, hits);
    return 0;
}
