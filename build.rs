//! Compiles the tinybvh peer's C++ shim (feature `tinybvh`): tinybvh's single header
//! (`third_party/tinybvh`) with `src/index/peers/tinybvh/shim.cpp`. Nothing to do otherwise.

fn main() {
    #[cfg(feature = "tinybvh")]
    {
        let shim = "src/index/peers/tinybvh/shim.cpp";
        cc::Build::new()
            .cpp(true)
            .std("c++20")
            .file(shim)
            .include("third_party/tinybvh")
            // BVH8_CPU's traversal is written for AVX2 and FMA.
            .flag("-march=native")
            .opt_level(3)
            .warnings(false)
            .compile("accelbench_tinybvh");
        println!("cargo:rerun-if-changed={shim}");
        println!("cargo:rerun-if-changed=third_party/tinybvh/tiny_bvh.h");
    }
    println!("cargo:rerun-if-changed=build.rs");
}
