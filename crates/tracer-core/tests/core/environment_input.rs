//! Bad environment maps behind a sidecar's `[environment] file = ...`: each is an error that
//! names the file (never a panic), invalid texels are counted in a note, and a small Radiance
//! file written here reads back its texels within RGBE's precision.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use glam::Vec3;
use std::path::{Path, PathBuf};
use tracer_core::light::{EnvironmentMap, EnvironmentSource};
use tracer_core::scene::Sidecar;

/// A directory of this test's own, removed when dropped.
struct Scratch(PathBuf);

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

fn scratch(name: &str) -> Scratch {
    let dir = std::env::temp_dir().join(format!("raygine-envin-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    Scratch(dir)
}

/// One texel in Radiance's shared-exponent RGBE: the largest channel's mantissa is in
/// [128, 256), each channel truncated (as Radiance writes them).
pub(crate) fn rgbe(c: Vec3) -> [u8; 4] {
    let m = c.max_element();
    if m < 1e-32 {
        return [0; 4];
    }
    // m = f * 2^e with f in [0.5, 1).
    let mut e = m.log2().floor() as i32 + 1;
    if m / 2f32.powi(e) >= 1.0 {
        e += 1;
    } else if m / 2f32.powi(e) < 0.5 {
        e -= 1;
    }
    let s = 256.0 / 2f32.powi(e);
    [
        (c.x * s) as u8,
        (c.y * s) as u8,
        (c.z * s) as u8,
        (e + 128) as u8,
    ]
}

/// A Radiance .hdr of flat (not run-length encoded) scanlines, top row first.
pub(crate) fn hdr(width: usize, height: usize, texel: impl Fn(usize, usize) -> Vec3) -> Vec<u8> {
    let mut out =
        format!("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {height} +X {width}\n").into_bytes();
    for y in 0..height {
        for x in 0..width {
            out.extend_from_slice(&rgbe(texel(x, y)));
        }
    }
    out
}

fn sky(x: usize, y: usize) -> Vec3 {
    Vec3::new(
        0.25 + x as f32,
        0.5 + 0.5 * y as f32,
        2.0 + 0.125 * (x * y) as f32,
    )
}

/// `map_bytes` saved as `dir/name`, then a sidecar beside it that names it.
fn parse_with_map(dir: &Path, name: &str, map_bytes: Option<&[u8]>) -> Result<Sidecar, String> {
    if let Some(bytes) = map_bytes {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
    let text = format!("[environment]\nfile = \"{name}\"\nscale = 179.0\n");
    Sidecar::parse(&text, &dir.join("room.raygine.toml")).map_err(|e| e.to_string())
}

/// The error of a sidecar naming `name`, which must name the file's full path and `what`.
fn refused(dir: &Path, name: &str, map_bytes: Option<&[u8]>, what: &str) {
    let err = match parse_with_map(dir, name, map_bytes) {
        Ok(_) => panic!("{name} was accepted"),
        Err(e) => e,
    };
    let path = dir.join(name).display().to_string();
    assert!(
        err.contains(&path),
        "{name}: the error does not name {path}: {err}"
    );
    assert!(err.contains(what), "{name}: expected '{what}' in: {err}");
    assert!(
        err.contains("room.raygine.toml"),
        "the sidecar is not named: {err}"
    );
}

#[test]
fn a_truncated_hdr_is_an_error_naming_it() {
    let dir = scratch("truncated");
    let full = hdr(8, 4, sky);
    refused(
        &dir,
        "cut.hdr",
        Some(&full[..full.len() - 40]),
        "ends before",
    );
    // Cut inside the header too.
    refused(&dir, "head.hdr", Some(&full[..20]), "head.hdr");
}

#[test]
fn a_corrupt_exr_is_an_error_naming_it() {
    let dir = scratch("exr");
    // Fixed pseudo-random bytes (a 64-bit LCG), not an OpenEXR file.
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let noise: Vec<u8> = (0..4096)
        .map(|_| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 56) as u8
        })
        .collect();
    refused(
        &dir,
        "noise.exr",
        Some(&noise),
        "not a readable .hdr or .exr image",
    );
    // The OpenEXR magic number, then noise.
    let mut magic = vec![0x76, 0x2f, 0x31, 0x01];
    magic.extend_from_slice(&noise);
    refused(
        &dir,
        "magic.exr",
        Some(&magic),
        "not a readable .hdr or .exr image",
    );
}

#[test]
fn a_map_that_is_not_two_to_one_is_an_error_naming_it() {
    let dir = scratch("ratio");
    refused(&dir, "square.hdr", Some(&hdr(3, 2, sky)), "3 x 2 px");
}

#[test]
fn a_missing_map_is_an_error_naming_it() {
    let dir = scratch("missing");
    refused(&dir, "nowhere.hdr", None, "nowhere.hdr");
}

#[test]
fn other_image_formats_and_huge_headers_are_refused_before_decoding() {
    let dir = scratch("other");
    // A PNG signature under an .hdr name: the content decides, and PNG is not a map format.
    let png = b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR\0\0\0\x08\0\0\0\x04\x08\x02\0\0\0";
    refused(&dir, "photo.hdr", Some(png), "Radiance .hdr or OpenEXR");
    // A header asking for 32768 x 16384 px (6 GiB as RGB f32) and no pixels: refused by its
    // size, before anything that large is allocated.
    let huge = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 16384 +X 32768\n";
    refused(
        &dir,
        "huge.hdr",
        Some(huge),
        "32768 x 16384 px is too large",
    );
    // A square header is refused by its ratio, also before decoding.
    let square = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 60000 +X 60000\n";
    refused(&dir, "square.hdr", Some(square), "60000 x 60000 px");
}

/// The header of a single-part scanline OpenEXR of float channels B, G, R, uncompressed,
/// whose display window is `display` px and whose data window is `data` px.
fn exr_header(display: (i32, i32), data: (i32, i32)) -> Vec<u8> {
    fn attr(out: &mut Vec<u8>, name: &str, kind: &str, value: &[u8]) {
        out.extend_from_slice(name.as_bytes());
        out.push(0);
        out.extend_from_slice(kind.as_bytes());
        out.push(0);
        out.extend_from_slice(&(value.len() as i32).to_le_bytes());
        out.extend_from_slice(value);
    }
    let words = |v: &[i32]| -> Vec<u8> { v.iter().flat_map(|x| x.to_le_bytes()).collect() };
    let mut channels = Vec::new();
    for name in ["B", "G", "R"] {
        channels.extend_from_slice(name.as_bytes());
        channels.push(0);
        // Float samples, not linear, sampled 1 x 1.
        channels.extend_from_slice(&words(&[2, 0, 1, 1]));
    }
    channels.push(0);
    let mut out = vec![0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0];
    attr(&mut out, "channels", "chlist", &channels);
    attr(&mut out, "compression", "compression", &[0]);
    attr(
        &mut out,
        "dataWindow",
        "box2i",
        &words(&[0, 0, data.0 - 1, data.1 - 1]),
    );
    attr(
        &mut out,
        "displayWindow",
        "box2i",
        &words(&[0, 0, display.0 - 1, display.1 - 1]),
    );
    attr(&mut out, "lineOrder", "lineOrder", &[0]);
    attr(&mut out, "pixelAspectRatio", "float", &1f32.to_le_bytes());
    attr(&mut out, "screenWindowCenter", "v2f", &[0; 8]);
    attr(&mut out, "screenWindowWidth", "float", &1f32.to_le_bytes());
    out.push(0);
    out
}

/// An OpenEXR of `size` px (both windows), every texel 1.
fn exr(size: (i32, i32)) -> Vec<u8> {
    let words = |v: &[i32]| -> Vec<u8> { v.iter().flat_map(|x| x.to_le_bytes()).collect() };
    let data = size;
    let mut out = exr_header(size, size);
    // The offset table, then one scanline a block: y, byte count, B, G and R in turn.
    let line_bytes = 3 * 4 * data.0 as usize;
    let first = out.len() + 8 * data.1 as usize;
    for y in 0..data.1 as usize {
        out.extend_from_slice(&((first + y * (8 + line_bytes)) as u64).to_le_bytes());
    }
    for y in 0..data.1 {
        out.extend_from_slice(&words(&[y, line_bytes as i32]));
        for _ in 0..3 * data.0 {
            out.extend_from_slice(&1f32.to_le_bytes());
        }
    }
    out
}

/// A layer's data window, not only its display window, is bounded: OpenEXR is read block by
/// block at the data window's width, before `image` crops it to the display window.
#[test]
fn an_exr_with_a_huge_data_window_is_refused_before_its_blocks_are_read() {
    let dir = scratch("exr-window");
    // The writer is right: 8 x 4 px in both windows reads.
    let sidecar = parse_with_map(&dir, "small.exr", Some(&exr((8, 4)))).unwrap();
    let (env, _) = sidecar.environment_model.unwrap();
    let EnvironmentSource::Map(map) = env.source else {
        panic!("not a map")
    };
    assert!(map.texels.iter().all(|t| *t == Vec3::ONE));
    // An 8 x 4 px display window over a 2^29 x 8 px data window, then a little of its offset
    // table: 48 GiB of samples, 6 GiB a block, if its blocks were read.
    let mut huge = exr_header((8, 4), (1 << 29, 8));
    huge.extend_from_slice(&[0; 64]);
    refused(
        &dir,
        "huge.exr",
        Some(&huge),
        "536870912 x 8 px in 3 channels is too large",
    );
}

/// image 0.25.10 overflows an integer on a chain of old-style run markers (a panic where
/// overflow checks are on, as in tests); the reader turns that into an error.
#[test]
fn a_decoder_panic_is_an_error_naming_the_file() {
    let mut chain = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 2\n".to_vec();
    chain.extend_from_slice(&rgbe(Vec3::ONE));
    for _ in 0..10 {
        chain.extend_from_slice(&[1, 1, 1, 0]);
    }
    let err = EnvironmentMap::from_bytes(&chain, Path::new("chain.hdr")).unwrap_err();
    assert!(err.starts_with("chain.hdr: "), "{err}");
}

#[test]
fn nan_and_negative_texels_are_zeroed_and_counted() {
    let mut texels = vec![Vec3::splat(0.5); 8];
    texels[1] = Vec3::new(f32::NAN, 1.0, 1.0);
    texels[6] = Vec3::new(-1.0, 0.5, 0.5);
    texels[7] = Vec3::new(1.0, f32::INFINITY, 1.0);
    let (map, bad) = EnvironmentMap::from_texels(Path::new("sky.exr"), 4, 2, texels).unwrap();
    assert_eq!(bad, 3);
    for i in [1, 6, 7] {
        assert_eq!(map.texels[i], Vec3::ZERO, "texel {i}");
    }
    assert_eq!(map.texels[0], Vec3::splat(0.5));
}

/// RGBE cannot hold a NaN or a negative value; OpenEXR can. Written by `image`'s own encoder,
/// read through a sidecar: the map loads, with a note that counts the invalid texels.
#[test]
fn invalid_texels_in_an_exr_give_a_note_that_counts_them() {
    let dir = scratch("exr-nan");
    let mut raw: Vec<f32> = (0..8 * 4)
        .flat_map(|i| sky(i % 8, i / 8).to_array())
        .collect();
    raw[3 * 3] = f32::NAN;
    raw[3 * 17 + 1] = -1.0;
    let image = image::Rgb32FImage::from_raw(8, 4, raw).unwrap();
    image.save(dir.join("sky.exr")).unwrap();
    let sidecar = parse_with_map(&dir, "sky.exr", None).unwrap();
    let (env, notes) = sidecar.environment_model.unwrap();
    let EnvironmentSource::Map(map) = env.source else {
        panic!("not a map")
    };
    assert_eq!((map.width, map.height), (8, 4));
    assert_eq!(map.texels[3], Vec3::ZERO);
    assert_eq!(map.texels[17], Vec3::ZERO);
    assert_eq!(notes.len(), 1, "{notes:?}");
    assert!(
        notes[0].contains("sky.exr") && notes[0].contains("2 texels are NaN"),
        "{notes:?}"
    );
}

#[test]
fn a_file_and_a_uniform_luminance_together_are_an_error_naming_both_keys() {
    let dir = scratch("both");
    std::fs::write(dir.join("sky.hdr"), hdr(4, 2, sky)).unwrap();
    let text = "[environment]\nfile = \"sky.hdr\"\nluminance_cd_m2 = 1000.0\n";
    let err = Sidecar::parse(text, &dir.join("room.raygine.toml"))
        .map(|_| ())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("`file`") && err.contains("`luminance_cd_m2`"),
        "{err}"
    );
}

#[test]
fn a_small_hdr_reads_back_within_rgbe_precision() {
    let dir = scratch("roundtrip");
    let (width, height) = (8, 4);
    let bytes = hdr(width, height, sky);
    let sidecar = parse_with_map(&dir, "sky.hdr", Some(&bytes)).unwrap();
    let (env, notes) = sidecar.environment_model.unwrap();
    assert!(notes.is_empty(), "{notes:?}");
    assert_eq!(env.scale, 179.0);
    let EnvironmentSource::Map(map) = env.source else {
        panic!("not a map")
    };
    assert_eq!((map.width, map.height), (width, height));
    assert_eq!(map.file, dir.join("sky.hdr"));
    for y in 0..height {
        for x in 0..width {
            let (want, got) = (sky(x, y), map.texels[y * width + x]);
            // A truncated 8-bit mantissa under a shared exponent: within 1/128 of the largest
            // channel, below it.
            let tolerance = 0.01 * want.max_element();
            assert!(
                (got - want).abs().max_element() <= tolerance && got.cmple(want).all(),
                "texel ({x}, {y}): wrote {want}, read {got}"
            );
        }
    }
    // The same bytes from memory give the same map.
    let (from_memory, _) = EnvironmentMap::from_bytes(&bytes, &dir.join("sky.hdr")).unwrap();
    assert_eq!(from_memory, *map);
}
