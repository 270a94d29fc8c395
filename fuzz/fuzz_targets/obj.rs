//! An OBJ file of arbitrary bytes, with an MTL beside it of the same bytes.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let dir = std::env::temp_dir().join(format!("rasterlab-fuzz-obj-{}", std::process::id()));
    let _ = std::fs::create_dir_all(&dir);
    let path = dir.join("m.obj");
    std::fs::write(&path, data).unwrap();
    std::fs::write(dir.join("m.mtl"), data).unwrap();
    if let Err(e) = rasterlab::scene::read_obj(&path) {
        assert!(!e.contains('\n'), "{e}");
    }
});
