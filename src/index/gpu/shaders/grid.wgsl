// gpu-grid: our uniform grid's cells (compressed rows of primitive ids) walked by a 3D-DDA per
// thread (Amanatides & Woo 1987), with the CPU grid's boundary planes, so both walks cross
// the cells at the same distances. A walk ends once the best hit lies at or before the exit of
// the current cell. No mailbox: a primitive in several cells may be tested again.

// [res x, y, z, pad, bounds min xyz, max xyz, inv_cell xyz (f32 bits)].
@group(0) @binding(4) var<storage, read> header: array<u32>;
// Cell c's primitives are prims[offsets[c] .. offsets[c + 1]].
@group(0) @binding(5) var<storage, read> offsets: array<u32>;
@group(0) @binding(6) var<storage, read> prims: array<u32>;
// The planes of x (res x + 1 values), then of y, then of z.
@group(0) @binding(7) var<storage, read> planes: array<f32>;

fn plane(axis: u32, i: u32) -> f32 {
    var base = 0u;
    if (axis >= 1u) {
        base += header[0] + 1u;
    }
    if (axis >= 2u) {
        base += header[1] + 1u;
    }
    return planes[base + i];
}

fn f(k: u32) -> f32 {
    return bitcast<f32>(header[k]);
}

fn trace(r: Ray, initial: Best, any_hit: bool) -> Best {
    var best = initial;
    let res = vec3u(header[0], header[1], header[2]);
    let lo = vec3f(f(4u), f(5u), f(6u));
    let hi = vec3f(f(7u), f(8u), f(9u));
    let inv_cell = vec3f(f(10u), f(11u), f(12u));
    let span = slab(lo, hi, r, r.t_max);
    if (span.x > span.y) {
        return best;
    }
    let start = r.o + r.d * span.x;
    var cell: vec3i;
    var step = vec3i(0);
    var end: vec3i;
    var t_next = vec3f(INF);
    for (var a = 0u; a < 3u; a++) {
        let c = clamp(i32(floor((start[a] - lo[a]) * inv_cell[a])), 0, i32(res[a]) - 1);
        cell[a] = c;
        end[a] = c;
        let inv = r.inv[a];
        if (abs(r.d[a]) >= MIN_NORMAL) {
            if (inv > 0.0) {
                step[a] = 1;
                end[a] = i32(res[a]);
                t_next[a] = (plane(a, u32(c + 1)) - r.o[a]) * inv;
            } else {
                step[a] = -1;
                end[a] = -1;
                t_next[a] = (plane(a, u32(c)) - r.o[a]) * inv;
            }
        }
    }
    loop {
        let linear = u32(cell.x) + res.x * (u32(cell.y) + res.y * u32(cell.z));
        var axis = 2u;
        if (t_next.x <= t_next.y && t_next.x <= t_next.z) {
            axis = 0u;
        } else if (t_next.y <= t_next.z) {
            axis = 1u;
        }
        let exit = t_next[axis];
        var found = false;
        for (var k = offsets[linear]; k < offsets[linear + 1u]; k++) {
            let prim = prims[k];
            let t = triangle(prim, r, best.t);
            if (better(t, prim, best)) {
                best.t = t;
                best.prim = prim;
                found = true;
            }
        }
        if ((found && any_hit) || best.t <= exit) {
            break;
        }
        let next = cell[axis] + step[axis];
        if (next == end[axis]) {
            break;
        }
        cell[axis] = next;
        var p = u32(next);
        if (step[axis] > 0) {
            p += 1u;
        }
        t_next[axis] = (plane(axis, p) - r.o[axis]) * r.inv[axis];
    }
    return best;
}
