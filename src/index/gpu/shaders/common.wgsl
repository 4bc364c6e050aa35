// What every trace shader shares: the bindings of the batch (program.rs), the ray with its
// shear, the slab test and the f32 watertight triangle test (Woop, Benthin & Wald 2013), in the
// order of the CPU kernel's f32 operations, its t clamped into the triangle's box as on the CPU.
// Where they differ: WGSL has no f64, so an edge function of exactly zero is recomputed with
// Kahan's fma difference of products (exact sign, within 2 ulp) where the CPU kernel uses f64;
// WGSL's division is accurate to 2.5 ulp, and `div` refines it by one fma step, which lands on
// or next to the correctly rounded quotient (the shear factors, the inverse direction and t).
// The kernel's products are kept from being fused into the additions after them (`unfused`).
// So a hit's t can differ from ours in the last bit where a quotient does.

// `inf_bits` is 0x7f800000: WGSL has no infinite constant (a const-expression may not be one);
// `zero` is 0, a value the compiler cannot see (`unfused`).
struct Params { count: u32, any_hit: u32, inf_bits: u32, zero: u32 }

@group(0) @binding(0) var<storage, read> rays: array<f32>;
@group(0) @binding(1) var<storage, read_write> hits: array<u32>;
@group(0) @binding(2) var<uniform> params: Params;
// Triangles, 9 f32 each (three corners), in the order the structure's leaves reference them.
@group(0) @binding(3) var<storage, read> tris: array<f32>;

// +infinity and 0, set by `begin` from the parameters.
var<private> INF: f32;
var<private> ZERO: u32;
const NO_PRIM: u32 = 0xffffffffu;
// The slab test's exit distance is grown by this factor (the CPU's is 1 + 2 gamma(3),
// geometry/aabb.rs): WGSL's division, so the inverse direction, is accurate to 2.5 ulp only,
// and 2^-20 covers that error in entry and exit with room.
const FAR_SCALE: f32 = 1.00000095367431640625;
// Direction components below the smallest normal f32 are taken as zero (a driver may flush
// them, and their inverse may overflow).
const MIN_NORMAL: f32 = 1.17549435e-38;
const STACK: u32 = 64u;

struct Ray {
    o: vec3f,
    d: vec3f,
    inv: vec3f,
    t_min: f32,
    t_max: f32,
    // Shear axes and factors (geometry/ray.rs).
    kx: u32,
    ky: u32,
    kz: u32,
    s: vec3f,
}

// Sets the private constants; the first call of every entry point.
fn begin() {
    INF = bitcast<f32>(params.inf_bits);
    ZERO = params.zero;
}

// `x` as it is, through an integer operation the compiler cannot fold (ZERO comes from the
// parameters): a product wrapped in it is rounded on its own and cannot be fused with the
// addition that follows (SPIR-V from naga carries no NoContraction), so the kernel's edge
// functions and t round as the CPU kernel's do.
fn unfused(x: f32) -> f32 {
    return bitcast<f32>(bitcast<u32>(x) ^ ZERO);
}

// a / b refined by one fma step from WGSL's 2.5-ulp division: the remainder a - q b is exact
// in fma, so q + r / b lands on or next to the correctly rounded quotient the CPU computes
// (finite nonzero b and a finite quotient; anything else gives NaN or infinity, which every
// caller rejects).
fn div(a: f32, b: f32) -> f32 {
    let q = a / b;
    let r = fma(-q, b, a);
    return fma(r, 1.0 / b, q);
}

fn load_ray(i: u32) -> Ray {
    let b = 8u * i;
    var r: Ray;
    r.o = vec3f(rays[b], rays[b + 1u], rays[b + 2u]);
    var d = vec3f(rays[b + 3u], rays[b + 4u], rays[b + 5u]);
    r.d = d;
    for (var a = 0u; a < 3u; a++) {
        // Axes below MIN_NORMAL are treated as parallel (line_slab) and never read it.
        r.inv[a] = select(0.0, div(1.0, d[a]), abs(d[a]) >= MIN_NORMAL);
    }
    r.t_min = rays[b + 6u];
    r.t_max = rays[b + 7u];
    let a = abs(d);
    var kz = 2u;
    if (a.x >= a.y && a.x >= a.z) {
        kz = 0u;
    } else if (a.y >= a.z) {
        kz = 1u;
    }
    var kx = (kz + 1u) % 3u;
    var ky = (kx + 1u) % 3u;
    if (d[kz] < 0.0) {
        let k = kx;
        kx = ky;
        ky = k;
    }
    r.kx = kx;
    r.ky = ky;
    r.kz = kz;
    r.s = vec3f(div(d[kx], d[kz]), div(d[ky], d[kz]), div(1.0, d[kz]));
    return r;
}

// Entry and exit distances of the box [lo, hi] along the whole line (the CPU's
// `Aabb::ray_interval`, exit grown by FAR_SCALE); entry > exit: a miss. Written without NaN:
// shader compilers may fold a NaN test (`x != x`) to false, so an axis the ray parallels is
// decided by whether the origin lies in the slab (the CPU's NaN rule gives the same answer).
fn line_slab(lo: vec3f, hi: vec3f, r: Ray) -> vec2f {
    var near = vec3f(-INF);
    var far3 = vec3f(INF);
    for (var a = 0u; a < 3u; a++) {
        if (abs(r.d[a]) < MIN_NORMAL) {
            if (r.o[a] < lo[a] || r.o[a] > hi[a]) {
                return vec2f(INF, -INF);
            }
        } else {
            let t0 = (lo[a] - r.o[a]) * r.inv[a];
            let t1 = (hi[a] - r.o[a]) * r.inv[a];
            near[a] = min(t0, t1);
            far3[a] = max(t0, t1);
        }
    }
    var far = min(min(far3.x, far3.z), min(far3.y, far3.z));
    far = far * select(2.0 - FAR_SCALE, FAR_SCALE, far >= 0.0);
    return vec2f(max(max(near.x, near.z), max(near.y, near.z)), far);
}

// Entry and exit distances of the box [lo, hi] within [t_min, t_max]; entry > exit: a miss.
fn slab(lo: vec3f, hi: vec3f, r: Ray, t_max: f32) -> vec2f {
    let s = line_slab(lo, hi, r);
    return vec2f(max(s.x, r.t_min), min(s.y, t_max));
}

// a * b - c * d with Kahan's fma form: within 2 ulp of the exact value, so its sign (and zero)
// is exact, as the CPU kernel's recomputation in f64.
fn diff_of_products(a: f32, b: f32, c: f32, d: f32) -> f32 {
    let w = c * d;
    let e = fma(-c, d, w);
    let f = fma(a, b, -w);
    return f + e;
}

// The watertight test of triangle `i` (position in `tris`): its t when the ray hits it within
// [t_min, t_max], else -INF. As the CPU's `Geometry::intersect` (scene/accept.rs), the kernel's
// t is clamped into the slab interval of the triangle's box, and a box the slab test rejects is
// a miss.
fn triangle(i: u32, r: Ray, t_max: f32) -> f32 {
    let b = 9u * i;
    let v0 = vec3f(tris[b], tris[b + 1u], tris[b + 2u]);
    let v1 = vec3f(tris[b + 3u], tris[b + 4u], tris[b + 5u]);
    let v2 = vec3f(tris[b + 6u], tris[b + 7u], tris[b + 8u]);
    var a = v0 - r.o;
    var bb = v1 - r.o;
    var c = v2 - r.o;
    let ax = a[r.kx] - unfused(r.s.x * a[r.kz]);
    let ay = a[r.ky] - unfused(r.s.y * a[r.kz]);
    let bx = bb[r.kx] - unfused(r.s.x * bb[r.kz]);
    let by = bb[r.ky] - unfused(r.s.y * bb[r.kz]);
    let cx = c[r.kx] - unfused(r.s.x * c[r.kz]);
    let cy = c[r.ky] - unfused(r.s.y * c[r.kz]);
    var u = unfused(cx * by) - unfused(cy * bx);
    var v = unfused(ax * cy) - unfused(ay * cx);
    var w = unfused(bx * ay) - unfused(by * ax);
    if (u == 0.0 || v == 0.0 || w == 0.0) {
        u = diff_of_products(cx, by, cy, bx);
        v = diff_of_products(ax, cy, ay, cx);
        w = diff_of_products(bx, ay, by, ax);
    }
    if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) {
        return -INF;
    }
    let det = u + v + w;
    if (det == 0.0) {
        return -INF;
    }
    let az = r.s.z * a[r.kz];
    let bz = r.s.z * bb[r.kz];
    let cz = r.s.z * c[r.kz];
    var t = div(unfused(u * az) + unfused(v * bz) + unfused(w * cz), det);
    if (!(t >= r.t_min && t <= t_max)) {
        return -INF;
    }
    let span = line_slab(min(min(v0, v1), v2), max(max(v0, v1), v2), r);
    if (span.x > span.y) {
        return -INF;
    }
    t = select(t, span.x, span.x > t);
    t = select(t, span.y, span.y < t);
    if (t >= r.t_min && t <= t_max && t < INF) {
        return t;
    }
    return -INF;
}

// The running closest hit: the closest-hit order of the CPU (lower t, then lower id).
struct Best { t: f32, prim: u32 }

fn better(t: f32, prim: u32, best: Best) -> bool {
    return t > -INF && (t < best.t || (t == best.t && prim < best.prim));
}

// One ray per thread: the structure's `trace` (each shader's own) from the running hit
// (`t_max`, no primitive), stopping at the first hit when `any_hit`.
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) gid: vec3u) {
    begin();
    let i = gid.x;
    if (i >= params.count) {
        return;
    }
    let r = load_ray(i);
    store(i, trace(r, Best(r.t_max, NO_PRIM), params.any_hit != 0u));
}

fn store(i: u32, best: Best) {
    if (best.prim == NO_PRIM) {
        hits[2u * i] = bitcast<u32>(INF);
    } else {
        hits[2u * i] = bitcast<u32>(best.t);
    }
    hits[2u * i + 1u] = best.prim;
}
