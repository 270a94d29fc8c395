//! A screenshot or texture file of arbitrary bytes (PNG, BMP or GIF by content).
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let dir = std::env::temp_dir().join(format!("rasterlab-fuzz-image-{}", std::process::id()));
    let _ = std::fs::create_dir_all(&dir);
    let path = dir.join("x.png");
    std::fs::write(&path, data).unwrap();
    if let Err(e) = rasterlab::app::check::read_screenshot(&path) {
        assert!(!e.contains('\n'), "{e}");
    }
});
