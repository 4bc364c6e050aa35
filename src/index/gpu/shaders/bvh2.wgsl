// gpu-bvh2: our binary BVH as it is on the CPU (64-byte nodes holding both children's boxes),
// one ray per thread, a while-while stack walk in the manner of Aila & Laine (2009): nearer
// child first, the farther one pushed, children whose entry is beyond the best hit culled.

// [root index, root count, root box min xyz, max xyz (f32 bits)].
@group(0) @binding(4) var<storage, read> header: array<u32>;
// Four vec4 per node: x, y, z as [a.min, b.min, a.max, b.max]; then the children's
// (index, count) as f32 bits: count 0 is the inner node `index`, count > 0 a leaf over
// positions index..index + count.
@group(0) @binding(5) var<storage, read> nodes: array<vec4f>;
// The scene id of each leaf position (tris holds the triangles in that order).
@group(0) @binding(6) var<storage, read> ids: array<u32>;

// Tests the leaf over positions [first, first + count): updates `best`; true on any hit.
fn leaf(first: u32, count: u32, r: Ray, best: ptr<function, Best>) -> bool {
    var any = false;
    for (var k = first; k < first + count; k++) {
        let t = triangle(k, r, (*best).t);
        let prim = ids[k];
        if (better(t, prim, *best)) {
            (*best).t = t;
            (*best).prim = prim;
            any = true;
        }
    }
    return any;
}

fn trace(r: Ray, initial: Best, any_hit: bool) -> Best {
    var best = initial;
    let lo = vec3f(bitcast<f32>(header[2]), bitcast<f32>(header[3]), bitcast<f32>(header[4]));
    let hi = vec3f(bitcast<f32>(header[5]), bitcast<f32>(header[6]), bitcast<f32>(header[7]));
    let root = slab(lo, hi, r, best.t);
    var stack_index: array<u32, STACK>;
    var stack_count: array<u32, STACK>;
    var sp = 0u;
    var index = header[0];
    var count = header[1];
    var live = root.x <= root.y;
    loop {
        if (!live) {
            break;
        }
        if (count > 0u) {
            if (leaf(index, count, r, &best) && any_hit) {
                break;
            }
            if (sp == 0u) {
                break;
            }
            sp -= 1u;
            index = stack_index[sp];
            count = stack_count[sp];
            continue;
        }
        let n = 4u * index;
        let x = nodes[n];
        let y = nodes[n + 1u];
        let z = nodes[n + 2u];
        let c = bitcast<vec4u>(nodes[n + 3u]);
        let ta = slab(vec3f(x.x, y.x, z.x), vec3f(x.z, y.z, z.z), r, best.t);
        let tb = slab(vec3f(x.y, y.y, z.y), vec3f(x.w, y.w, z.w), r, best.t);
        let hit_a = ta.x <= ta.y;
        let hit_b = tb.x <= tb.y;
        if (hit_a && hit_b) {
            // Nearer first; the farther one waits on the stack.
            if (tb.x < ta.x) {
                stack_index[sp] = c.x;
                stack_count[sp] = c.y;
                index = c.z;
                count = c.w;
            } else {
                stack_index[sp] = c.z;
                stack_count[sp] = c.w;
                index = c.x;
                count = c.y;
            }
            sp = min(sp + 1u, STACK - 1u);
        } else if (hit_a) {
            index = c.x;
            count = c.y;
        } else if (hit_b) {
            index = c.z;
            count = c.w;
        } else {
            if (sp == 0u) {
                break;
            }
            sp -= 1u;
            index = stack_index[sp];
            count = stack_count[sp];
        }
    }
    return best;
}
