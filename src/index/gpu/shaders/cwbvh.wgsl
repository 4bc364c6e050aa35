// gpu-cwbvh: the compressed 8-wide BVH of Ylitie, Karras & Laine (2017), one ray per thread:
// a node's eight quantized child boxes tested together into one hit mask (inner children in the
// top 8 bits, ordered by the ray's octant; the leaves' triangles in the low 24), the stack
// holding node groups (a base index and the children still to visit) as in the paper.

// 20 words per node (cwbvh_layout.rs): p xyz, exponents and imask, child base, triangle
// base, meta[8], lo.x[8], lo.y[8], lo.z[8], hi.x[8], hi.y[8], hi.z[8].
@group(0) @binding(4) var<storage, read> nodes: array<u32>;
// The scene id of each triangle position (tris holds the triangles in that order).
@group(0) @binding(5) var<storage, read> ids: array<u32>;

fn byte_of(word: u32, k: u32) -> u32 {
    return (nodes[word + k / 4u] >> (8u * (k % 4u))) & 0xFFu;
}

struct Visit { hits: u32, child_base: u32, tri_base: u32, imask: u32 }

// The hit mask of node `n`'s children within [t_min, t_max] (Ylitie et al., section 3).
fn visit(n: u32, r: Ray, t_max: f32, oct_inv: u32) -> Visit {
    let w = 20u * n;
    let p = vec3f(bitcast<f32>(nodes[w]), bitcast<f32>(nodes[w + 1u]), bitcast<f32>(nodes[w + 2u]));
    let ew = nodes[w + 3u];
    let scale = vec3f(
        bitcast<f32>((ew & 0xFFu) << 23u),
        bitcast<f32>(((ew >> 8u) & 0xFFu) << 23u),
        bitcast<f32>(((ew >> 16u) & 0xFFu) << 23u),
    );
    var v: Visit;
    v.imask = ew >> 24u;
    v.child_base = nodes[w + 4u];
    v.tri_base = nodes[w + 5u];
    v.hits = 0u;
    for (var c = 0u; c < 8u; c++) {
        let m = byte_of(w + 6u, c);
        if (m == 0u) {
            continue;
        }
        let q_lo = vec3f(f32(byte_of(w + 8u, c)), f32(byte_of(w + 10u, c)), f32(byte_of(w + 12u, c)));
        let q_hi = vec3f(f32(byte_of(w + 14u, c)), f32(byte_of(w + 16u, c)), f32(byte_of(w + 18u, c)));
        let span = slab(p + scale * q_lo, p + scale * q_hi, r, t_max);
        if (span.x <= span.y) {
            let inner = (v.imask >> c) & 1u;
            var bit = m & 0x1Fu;
            if (inner != 0u) {
                bit = bit ^ oct_inv;
            }
            v.hits |= ((m >> 5u) & 7u) << bit;
        }
    }
    return v;
}

fn trace(r: Ray, initial: Best, any_hit: bool) -> Best {
    var best = initial;
    var oct_inv = 7u;
    if (r.d.x < 0.0) {
        oct_inv ^= 4u;
    }
    if (r.d.y < 0.0) {
        oct_inv ^= 2u;
    }
    if (r.d.z < 0.0) {
        oct_inv ^= 1u;
    }
    var stack: array<vec2u, STACK>;
    var sp = 0u;
    // The root as the one inner child of a group with base 0 and no imask bits.
    var group = vec2u(0u, 0x80000000u);
    var done = false;
    loop {
        if (done) {
            break;
        }
        // `group` holds inner children still to visit (bits 24..31).
        let bit = firstLeadingBit(group.y);
        group.y &= ~(1u << bit);
        let base = group.x;
        let imask = group.y & 0xFFu;
        if (group.y > 0x00FFFFFFu) {
            stack[sp] = group;
            sp = min(sp + 1u, STACK - 1u);
        }
        let slot = (bit - 24u) ^ oct_inv;
        let node = base + countOneBits(imask & ~(0xFFFFFFFFu << slot));
        let v = visit(node, r, best.t, oct_inv);
        group = vec2u(v.child_base, (v.hits & 0xFF000000u) | v.imask);
        var tris_left = v.hits & 0x00FFFFFFu;
        while (tris_left != 0u) {
            let k = firstLeadingBit(tris_left);
            tris_left &= ~(1u << k);
            let at = v.tri_base + k;
            let t = triangle(at, r, best.t);
            let prim = ids[at];
            if (better(t, prim, best)) {
                best.t = t;
                best.prim = prim;
                if (any_hit) {
                    done = true;
                    break;
                }
            }
        }
        if (!done && group.y <= 0x00FFFFFFu) {
            if (sp == 0u) {
                break;
            }
            sp -= 1u;
            group = stack[sp];
        }
    }
    return best;
}
