//! Scenes too large for memory are refused up front, from their declared counts, with a message
//! in the usual `file: line N: reason` form, before anything is allocated for them.
//!
//! Two rules meet here. A count the rest of the file cannot hold is refused first (the file is
//! cut short or corrupt: that message is the precise one). A count the file does hold, but whose
//! scene would need more memory than the machine has available, is refused next; the unit tests
//! of `shp::memory` drive that one with a small memory budget, since a real file past this
//! machine's memory would take gigabytes of test data.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;
use std::time::{Duration, Instant};

use tracer_core::formats::SceneFileError;
use tracer_core::scene::{LoadOptions, SceneError, load};
use tracer_core::shp::{ShpError, parse_shp};

/// Small, but declares two billion triangles (about 400 GB with the BVH).
const HUGE: &str = "\
;; a synthetic file that announces far more than any machine holds
define breps big
vertices 3
0 0 0
1 0 0
0 1 0
triangles 2000000000
0 1 2
enddef
";

fn assert_refused_up_front(err: &ShpError, file: &str, started: Instant) {
    let message = err.to_string();
    println!("{message}");
    assert!(
        matches!(
            err,
            ShpError::CountTooLarge {
                line: 7,
                count: 2_000_000_000,
                ..
            }
        ),
        "{message}"
    );
    assert!(
        message.starts_with(&format!(
            "{file}: line 7: `triangles 2000000000` announces more triangles than the rest of the file can hold"
        )),
        "{message}"
    );
    assert!(started.elapsed() < Duration::from_secs(1), "not up front");
}

#[test]
fn two_billion_triangles_in_a_small_file_are_refused_before_reading_them() {
    let started = Instant::now();
    let err = parse_shp(HUGE.as_bytes(), Path::new("huge.shp")).unwrap_err();
    assert_refused_up_front(&err, "huge.shp", started);
}

#[test]
fn the_same_through_scene_load() {
    let dir = std::env::temp_dir().join(format!("raygine-stress-limits-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("huge.shp");
    std::fs::write(&file, HUGE).unwrap();
    let started = Instant::now();
    let result = load(&file, &LoadOptions::default());
    std::fs::remove_dir_all(&dir).ok();
    let err = match result {
        Err(SceneError::Shp(err)) | Err(SceneError::Format(SceneFileError::Shp(err))) => err,
        _ => panic!("expected the reader's error from scene::load"),
    };
    assert_refused_up_front(&err, &file.display().to_string(), started);
}

#[test]
fn the_memory_error_reads_like_every_reader_error() {
    // The message form, as `shp::memory`'s unit tests produce it with a 0.2 GB budget.
    let err = ShpError::TooLargeForMemory {
        path: "big.shp".into(),
        line: 6,
        keyword: "triangles".into(),
        count: 1_400_000,
        needed: "0.3 GB".into(),
        available: "0.2 GB".into(),
    };
    assert_eq!(err.line(), Some(6));
    assert_eq!(err.path(), Path::new("big.shp"));
    assert_eq!(
        err.to_string(),
        "big.shp: line 6: `triangles 1400000` makes the scene need about 0.3 GB of memory, \
         more than the 0.2 GB available"
    );
}
