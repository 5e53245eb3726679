//! Image textures against answers worked out here: a quad carrying a checker of known sRGB
//! codes, under a uniform sky of luminance L (illuminance E = πL), seen straight down through an
//! orthographic camera so every pixel's texture coordinates are known. Where bilinear filtering
//! is constant over a pixel's whole footprint, the pixel reads E · ρ / π = L · ρ for a Lambertian
//! OBJ material (`map_Kd`), and L · A(0°) with A the directional albedo of glTF's model for a
//! glTF base colour texture read through `KHR_texture_transform`. ρ comes from the sRGB codes
//! by IEC 61966-2-1, written again below (188 → 0.5029, 94 → 0.1119).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use base64::Engine;
use std::path::{Path, PathBuf};
use tracer_core::integrator::IntegratorKind;
use tracer_core::light::{Environment, EnvironmentSource};
use tracer_core::render::{RenderSettings, render};
use tracer_core::scene::{Camera, LoadOptions, Projection, load};

const SKY_CD_M2: f64 = 100.0;
/// The texture: 8 x 8 texels in 2 x 2 blocks of 4 x 4, alternating two colours.
const TEXELS: u32 = 8;
const BLOCK: u32 = 4;
const CODES: [[u8; 3]; 2] = [[188, 94, 30], [94, 188, 250]];
/// Image side, pixels (4 per texel).
const SIDE: u32 = 32;

/// The sRGB transfer function's inverse, IEC 61966-2-1.
fn srgb(code: u8) -> f64 {
    let c = f64::from(code) / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// `img` as PNG bytes.
pub(crate) fn png_bytes(img: image::DynamicImage) -> Vec<u8> {
    let mut out = Vec::new();
    img.write_to(&mut std::io::Cursor::new(&mut out), image::ImageFormat::Png)
        .unwrap();
    out
}

fn checker_png() -> Vec<u8> {
    let mut img = image::RgbImage::new(TEXELS, TEXELS);
    for (x, y, p) in img.enumerate_pixels_mut() {
        p.0 = CODES[((x / BLOCK + y / BLOCK) % 2) as usize];
    }
    png_bytes(img.into())
}

/// The unit quad in OBJ: x right, z down the image, y up; OBJ's v points up the image, so the
/// image's top row (v = 1 in OBJ) lies at z = 0. Faces follow.
const QUAD_OBJ: &str =
    "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nvt 0 1\nvt 1 1\nvt 1 0\nvt 0 0\n";

/// Writes `quad.mtl` (`mtl`) and `quad.obj` ([`QUAD_OBJ`] then `faces`) into `dir`; the OBJ's
/// path.
fn write_quad(dir: &Path, mtl: &str, faces: &str) -> PathBuf {
    std::fs::write(dir.join("quad.mtl"), mtl).unwrap();
    let path = dir.join("quad.obj");
    std::fs::write(&path, format!("{QUAD_OBJ}{faces}")).unwrap();
    path
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("raygine-tex-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Which colour of [`CODES`] a pixel reads, when bilinear filtering (with repeat) is the same
/// over its whole footprint: the footprint's corners, mapped by `to_uv` (pixel coordinates to
/// texture coordinates), all lie where the four texels around them are one block's.
fn block_of_pixel(px: u32, py: u32, to_uv: &dyn Fn(f64, f64) -> [f64; 2]) -> Option<usize> {
    let mut found = None;
    for (cx, cy) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
        let [u, v] = to_uv(f64::from(px) + cx, f64::from(py) + cy);
        // Texel space, centres at integers: the four texels around are floor and floor + 1.
        let (x, y) = (u * f64::from(TEXELS) - 0.5, v * f64::from(TEXELS) - 0.5);
        let blocks = |t: f64| {
            let a = (t.floor() as i64).rem_euclid(i64::from(TEXELS)) / i64::from(BLOCK);
            let b = (t.floor() as i64 + 1).rem_euclid(i64::from(TEXELS)) / i64::from(BLOCK);
            (a == b).then_some(a)
        };
        let (bx, by) = (blocks(x)?, blocks(y)?);
        let b = ((bx + by) % 2) as usize;
        if found.is_some_and(|f| f != b) {
            return None;
        }
        found = Some(b);
    }
    found
}

/// Renders `path` straight down onto the unit quad (x right, z down the image) under the sky,
/// and returns each pixel's RGB mean and the relative standard error of its luminance.
fn render_down(path: &Path, spp: u32) -> (Vec<glam::Vec3>, Vec<f64>, Vec<String>) {
    let mut loaded = load(path, &LoadOptions::default()).unwrap();
    let setup = &mut loaded.setup;
    setup.camera = Camera {
        position: [0.5, 5.0, 0.5],
        look_at: [0.5, 0.0, 0.5],
        up: [0.0, 0.0, -1.0],
        projection: Projection::Orthographic,
        width: Some(1.0),
        ..Camera::default()
    };
    setup.lights.clear();
    setup.environment = Some(Environment {
        source: EnvironmentSource::Uniform {
            luminance_cd_m2: SKY_CD_M2 as f32,
            color: [1.0; 3],
        },
        scale: 1.0,
        rotation_deg: 0.0,
        background: true,
    });
    let settings = RenderSettings {
        width: SIDE,
        height: SIDE,
        samples_per_pixel: spp,
        integrator: IntegratorKind::Path,
        ..RenderSettings::default()
    };
    let (film, _) = render(&loaded.scene, &loaded.setup, &settings);
    let n = (SIDE * SIDE) as usize;
    let rgb = (0..n).map(|i| film.mean_rgb(i)).collect();
    // The standard error relative to the pixel's luminance (every channel of a Lambertian
    // pixel under a grey sky carries the same relative noise).
    let se = (0..n)
        .map(|i| film.luminance_std_error(i).unwrap_or(f64::INFINITY) / film.mean_luminance(i))
        .collect();
    (rgb, se, loaded.warnings)
}

/// Checks every pixel with a known block against `expected(block)` per channel; returns how
/// many pixels were checked.
fn check_pixels(
    what: &str,
    rgb: &[glam::Vec3],
    se: &[f64],
    to_uv: &dyn Fn(f64, f64) -> [f64; 2],
    expected: &dyn Fn(usize) -> [f64; 3],
) -> usize {
    let mut checked = 0;
    let mut worst = 0.0f64;
    // Sum of got / want − 1 and the count per block and channel.
    let mut sums = [[0.0f64; 3]; 2];
    let mut counts = [0usize; 2];
    for py in 0..SIDE {
        for px in 0..SIDE {
            let Some(b) = block_of_pixel(px, py, to_uv) else {
                continue;
            };
            let i = (py * SIDE + px) as usize;
            let want = expected(b);
            counts[b] += 1;
            for c in 0..3 {
                let got = f64::from(rgb[i][c]);
                let rel = got / want[c] - 1.0;
                sums[b][c] += rel;
                worst = worst.max(rel.abs());
                // 1 % or 5 standard errors of the pixel (the sky's sampling noise).
                assert!(
                    rel.abs() < 0.01 || rel.abs() < 5.0 * se[i],
                    "{what}: pixel ({px}, {py}) channel {c}: {got} vs {} (block {b})",
                    want[c]
                );
            }
            checked += 1;
        }
    }
    println!(
        "{what}: {checked} pixels at known texels, worst {:.3} % off",
        worst * 100.0
    );
    // Over each block's pixels the noise averages out: the mean is within 0.5 %.
    for (b, (sum, count)) in sums.iter().zip(counts).enumerate() {
        for (c, s) in sum.iter().enumerate() {
            let mean = s / count.max(1) as f64;
            println!(
                "{what}: block {b} channel {c}: mean {:+.3} % off",
                mean * 100.0
            );
            assert!(mean.abs() < 0.005, "{what}: block {b} channel {c}: {mean}");
        }
    }
    checked
}

#[test]
fn an_obj_quad_with_map_kd_reads_l_times_the_decoded_texel() {
    // The decode by hand, as the issue states it.
    assert!((srgb(188) - 0.5029).abs() < 5e-5 && (srgb(94) - 0.1119).abs() < 5e-5);
    let dir = scratch("obj");
    std::fs::write(dir.join("checker.png"), checker_png()).unwrap();
    let path = write_quad(
        &dir,
        "newmtl checker\nKd 1 1 1\nmap_Kd checker.png\n",
        "usemtl checker\nf 1/1 4/4 3/3 2/2\n",
    );
    let (rgb, se, warnings) = render_down(&path, 64);
    assert!(
        !warnings.iter().any(|w| w.contains("texture")),
        "{warnings:?}"
    );
    let to_uv = |x: f64, y: f64| [x / f64::from(SIDE), y / f64::from(SIDE)];
    let checked = check_pixels("OBJ map_Kd", &rgb, &se, &to_uv, &|b| {
        CODES[b].map(|c| SKY_CD_M2 * srgb(c))
    });
    // In each of the 4 blocks, 11 x 11 pixels lie wholly where its texels are constant.
    assert_eq!(checked, 4 * 11 * 11);
    let _ = std::fs::remove_dir_all(&dir);
}

/// KHR_texture_transform as its specification writes it: translation · rotation · scale, the
/// rotation matrix with rows (cos, sin) and (−sin, cos), applied to (u, v, 1).
fn khr_transform(
    offset: [f64; 2],
    rotation: f64,
    scale: [f64; 2],
) -> impl Fn([f64; 2]) -> [f64; 2] {
    let t =
        glam::DMat3::from_cols_array(&[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, offset[0], offset[1], 1.0]);
    let (s, c) = rotation.sin_cos();
    let r = glam::DMat3::from_cols_array(&[c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0]);
    let sc = glam::DMat3::from_diagonal(glam::DVec3::new(scale[0], scale[1], 1.0));
    let m = t * r * sc;
    move |uv: [f64; 2]| {
        let p = m * glam::DVec3::new(uv[0], uv[1], 1.0);
        [p.x, p.y]
    }
}

#[test]
fn a_gltf_base_colour_texture_is_read_through_khr_texture_transform() {
    let dir = scratch("gltf");
    let png = checker_png();
    // Positions, then texture coordinates (the image's frame), then indices.
    let positions: [[f32; 3]; 4] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 0.0, 1.0],
        [0.0, 0.0, 1.0],
    ];
    let uvs: [[f32; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let indices: [u16; 6] = [0, 3, 2, 0, 2, 1];
    let mut bin = Vec::new();
    positions
        .iter()
        .flatten()
        .for_each(|f| bin.extend(f.to_le_bytes()));
    uvs.iter()
        .flatten()
        .for_each(|f| bin.extend(f.to_le_bytes()));
    indices.iter().for_each(|i| bin.extend(i.to_le_bytes()));
    let b64 = |b: &[u8]| base64::engine::general_purpose::STANDARD.encode(b);
    let (offset, rotation, scale) = ([0.5f64, 0.25], std::f64::consts::FRAC_PI_2, [1.0f64, 2.0]);
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"extensionsUsed":["KHR_texture_transform"],
        "scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"TEXCOORD_0":1}},"indices":2,"material":0}}]}}],
        "materials":[{{"name":"checker","pbrMetallicRoughness":{{"metallicFactor":0.0,"roughnessFactor":1.0,
            "baseColorTexture":{{"index":0,"extensions":{{"KHR_texture_transform":
                {{"offset":[{},{}],"rotation":{},"scale":[{},{}]}}}}}}}}}}],
        "textures":[{{"source":0,"sampler":0}}],"samplers":[{{"wrapS":10497,"wrapT":10497}}],
        "images":[{{"uri":"data:image/png;base64,{}"}}],
        "buffers":[{{"byteLength":{},"uri":"data:application/octet-stream;base64,{}"}}],
        "bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":48}},{{"buffer":0,"byteOffset":48,"byteLength":32}},
            {{"buffer":0,"byteOffset":80,"byteLength":12}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,0,1]}},
            {{"bufferView":1,"componentType":5126,"count":4,"type":"VEC2"}},
            {{"bufferView":2,"componentType":5123,"count":6,"type":"SCALAR"}}]}}"#,
        offset[0],
        offset[1],
        rotation,
        scale[0],
        scale[1],
        b64(&png),
        bin.len(),
        b64(&bin)
    );
    std::fs::write(dir.join("quad.gltf"), json).unwrap();
    let (rgb, se, warnings) = render_down(&dir.join("quad.gltf"), 256);
    assert!(
        !warnings.iter().any(|w| w.contains("texture")),
        "{warnings:?}"
    );
    let transform = khr_transform(offset, rotation, scale);
    let to_uv = |x: f64, y: f64| transform([x / f64::from(SIDE), y / f64::from(SIDE)]);
    // Straight down, glTF's model (metallic 0, roughness 1) reflects L · A(0°) of the colour.
    let per_block = CODES
        .map(|b| b.map(|c| SKY_CD_M2 * crate::metal_rough::albedo(srgb(c), 0.0, 1.0, 0.0, 0.0)));
    let expected = |b: usize| per_block[b];
    let checked = check_pixels("glTF KHR_texture_transform", &rgb, &se, &to_uv, &expected);
    assert!(checked >= 200, "{checked}");
    // Without the transform the pattern would differ: the test can tell.
    let plain = |x: f64, y: f64| [x / f64::from(SIDE), y / f64::from(SIDE)];
    let differs = (0..SIDE * SIDE).any(|i| {
        let (px, py) = (i % SIDE, i / SIDE);
        matches!((block_of_pixel(px, py, &to_uv), block_of_pixel(px, py, &plain)), (Some(a), Some(b)) if a != b)
    });
    assert!(differs);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A 1 m OBJ quad (u along +x, the image's v along +z, normal +y) whose material `mtl` names
/// `image` as `file`; rendered straight down in direct mode under a point light of `cd`
/// candela at `light`. Returns the pixels' luminance (SIDE x SIDE).
fn lit_quad(
    name: &str,
    mtl: &str,
    file: &str,
    image: image::DynamicImage,
    light: [f32; 3],
    cd: f32,
) -> Vec<f64> {
    let dir = scratch(name);
    std::fs::write(dir.join(file), png_bytes(image)).unwrap();
    let path = write_quad(&dir, mtl, "usemtl m\nf 1/1 4/4 3/3 2/2\n");
    let mut loaded = load(&path, &LoadOptions::default()).unwrap();
    assert!(
        !loaded.warnings.iter().any(|w| w.contains("texture")),
        "{:?}",
        loaded.warnings
    );
    loaded.setup.camera = Camera {
        position: [0.5, 5.0, 0.5],
        look_at: [0.5, 0.0, 0.5],
        up: [0.0, 0.0, -1.0],
        projection: Projection::Orthographic,
        width: Some(1.0),
        ..Camera::default()
    };
    loaded.setup.lights = vec![tracer_core::scene::Light::point(light, cd)];
    loaded.setup.unit = tracer_core::scene::LengthUnit::M;
    let settings = RenderSettings {
        width: SIDE,
        height: SIDE,
        samples_per_pixel: 16,
        integrator: IntegratorKind::Direct,
        ..RenderSettings::default()
    };
    let (film, _) = render(&loaded.scene, &loaded.setup, &settings);
    let _ = std::fs::remove_dir_all(&dir);
    (0..(SIDE * SIDE) as usize)
        .map(|i| film.mean_luminance(i))
        .collect()
}

/// The luminance of a Lambertian point of reflectance `rho` and unit normal `n` at `p` under
/// a point light: ρ/π · I max(0, n·l) / R².
fn lambert(rho: f64, n: glam::DVec3, p: glam::DVec3, light: glam::DVec3, cd: f64) -> f64 {
    let d = light - p;
    rho / std::f64::consts::PI * cd * n.normalize().dot(d.normalize()).max(0.0) / d.length_squared()
}

/// The largest |a / b − 1| over the pixels of columns `xs` and rows `ys`.
fn worst_ratio(
    xs: std::ops::Range<u32>,
    ys: std::ops::Range<u32>,
    a: impl Fn(u32, u32) -> f64,
    b: impl Fn(u32, u32) -> f64,
) -> f64 {
    ys.flat_map(|y| xs.clone().map(move |x| (x, y)))
        .map(|(x, y)| (a(x, y) / b(x, y) - 1.0).abs())
        .fold(0.0, f64::max)
}

/// The centre of pixel (x, y) on the quad.
fn pixel_point(x: u32, y: u32) -> glam::DVec3 {
    glam::DVec3::new(
        (f64::from(x) + 0.5) / f64::from(SIDE),
        0.0,
        (f64::from(y) + 0.5) / f64::from(SIDE),
    )
}

#[test]
fn a_normal_mapped_plane_shades_like_the_tilted_plane_its_map_encodes() {
    let light = [4.0f32, 8.0, 5.0];
    let cd = 100.0;
    // Tilts of 30° towards the tangent (+x) and towards the bitangent (up the image: −z).
    for (name, code) in [
        ("tangent", [191u8, 128, 221]),
        ("bitangent", [128u8, 191, 221]),
    ] {
        let img = image::RgbImage::from_pixel(4, 4, image::Rgb(code));
        let seen = lit_quad(
            &format!("normal-{name}"),
            "newmtl m\nKd 0.5 0.5 0.5\nnorm n.png\n",
            "n.png",
            img.into(),
            light,
            cd,
        );
        // The normal the codes encode (linear data: 2 · code / 255 − 1), in the world.
        let [tx, ty, tz] = code.map(|c| 2.0 * f64::from(c) / 255.0 - 1.0);
        // T = +x (u), B = −z (up the image), N = +y.
        let n = glam::DVec3::new(tx, tz, -ty);
        let flat = glam::DVec3::Y;
        let l = glam::DVec3::from(light.map(f64::from));
        let tilted = |x: u32, y: u32| lambert(0.5, n, pixel_point(x, y), l, f64::from(cd));
        let inner = 4..SIDE - 4;
        let worst = worst_ratio(
            inner.clone(),
            inner.clone(),
            |x, y| seen[(y * SIDE + x) as usize],
            tilted,
        );
        let differs_from_flat = worst_ratio(
            inner.clone(),
            inner,
            |x, y| lambert(0.5, flat, pixel_point(x, y), l, f64::from(cd)),
            tilted,
        );
        println!(
            "normal map tilted towards the {name}: worst {:.3} % from the tilted plane (the flat \
             plane is up to {:.1} % off)",
            worst * 100.0,
            differs_from_flat * 100.0
        );
        assert!(worst < 0.005, "{name}: {worst}");
        assert!(
            differs_from_flat > 0.05,
            "the test cannot tell: {differs_from_flat}"
        );
    }
}

#[test]
fn a_bump_map_ramp_tilts_the_normal_by_its_slope() {
    let light = [4.0f32, 8.0, 5.0];
    let cd = 100.0;
    // Heights rise along u: code x in texel x, so h = bm · (u · 256 − ½) / 255 between the
    // first and last texel centres: slope bm · 256 / 255 per metre along +x.
    let img = image::GrayImage::from_fn(256, 1, |x, _| image::Luma([x as u8]));
    let bm = 0.25;
    let seen = lit_quad(
        "bump",
        &format!("newmtl m\nKd 0.5 0.5 0.5\nbump -bm {bm} h.png\n"),
        "h.png",
        img.into(),
        light,
        cd,
    );
    let slope = bm * 256.0 / 255.0;
    let n = glam::DVec3::new(-slope, 1.0, 0.0);
    let l = glam::DVec3::from(light.map(f64::from));
    // Away from u = 0 and 1, where the repeating ramp jumps.
    let worst = worst_ratio(
        4..SIDE - 4,
        2..SIDE - 2,
        |x, y| seen[(y * SIDE + x) as usize],
        |x, y| lambert(0.5, n, pixel_point(x, y), l, f64::from(cd)),
    );
    println!(
        "bump ramp of slope {slope:.4}: worst {:.3} % from the tilted plane",
        worst * 100.0
    );
    assert!(worst < 0.005, "{worst}");
}

#[test]
fn missing_corrupt_and_huge_textures_are_noted_and_the_material_keeps_its_factor() {
    let dir = scratch("bad");
    std::fs::write(dir.join("corrupt.png"), b"\x89PNG\r\n\x1a\nnot really").unwrap();
    // A PNG header that declares 100 000 x 100 000 texels.
    let mut huge = png_bytes(image::RgbImage::new(1, 1).into());
    huge[16..20].copy_from_slice(&100_000u32.to_be_bytes());
    huge[20..24].copy_from_slice(&100_000u32.to_be_bytes());
    // The IHDR chunk's CRC-32 (over type and data), so the header itself is valid.
    let crc = crc32(&huge[12..29]);
    huge[29..33].copy_from_slice(&crc.to_be_bytes());
    std::fs::write(dir.join("huge.png"), huge).unwrap();
    let path = write_quad(
        &dir,
        "newmtl lost\nKd 0.25 0.5 0.75\nmap_Kd missing.png\nnewmtl broken\nKd 0.5 0.5 0.5\n\
         map_Kd corrupt.png\nnewmtl big\nKd 0.5 0.5 0.5\nmap_Kd huge.png\n",
        "o a\nusemtl lost\nf 1/1 4/4 3/3\no b\nusemtl broken\nf 1/1 3/3 2/2\no c\nusemtl big\n\
         f 1/1 2/2 4/4\n",
    );
    let loaded = load(&path, &LoadOptions::default()).unwrap();
    let notes = loaded.warnings.join("\n");
    println!("{notes}");
    for (line, material, file) in [
        (1, "lost", "missing.png"),
        (4, "broken", "corrupt.png"),
        (7, "big", "huge.png"),
    ] {
        assert!(
            loaded.warnings.iter().any(|w| w.contains(&format!(
                "quad.mtl:{line}: material {material}: base colour texture"
            )) && w.contains(file)
                && w.ends_with("the material keeps its factor")),
            "{material}: {notes}"
        );
    }
    assert!(
        notes.contains("100000 x 100000 texels is too large"),
        "{notes}"
    );
    // No texture loaded, and every material keeps its factor.
    assert!(loaded.scene.textures.is_empty());
    assert!(loaded.setup.materials.iter().all(|m| m.textures.is_none()));
    assert!(
        loaded
            .setup
            .materials
            .iter()
            .any(|m| m.kd == [0.25, 0.5, 0.75])
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// CRC-32 (IEEE 802.3, reflected, as PNG uses), bit by bit.
fn crc32(bytes: &[u8]) -> u32 {
    let mut c = 0xffff_ffffu32;
    for &b in bytes {
        c ^= u32::from(b);
        for _ in 0..8 {
            c = if c & 1 != 0 {
                (c >> 1) ^ 0xedb8_8320
            } else {
                c >> 1
            };
        }
    }
    !c
}

/// A 1 m square emitter 1 m above a floor, its `map_Ke` white on the left half and black on the
/// right (64 x 1 texels: the bilinear step is symmetric about the middle). Below its centre
/// the illuminance is half the untextured square's, E = π L F / 2 with F by Lambert's contour
/// formula, in every integrator; seen from below, the left half glows at L and the right does
/// not.
#[test]
fn an_emissive_map_varies_the_emission_over_the_surface_in_every_integrator() {
    let dir = scratch("emissive");
    let img = image::GrayImage::from_fn(64, 1, |x, _| image::Luma([if x < 32 { 255 } else { 0 }]));
    std::fs::write(dir.join("half.png"), png_bytes(img.into())).unwrap();
    std::fs::write(
        dir.join("lamp.mtl"),
        "newmtl glow\nKd 0 0 0\nKe 1 1 1\nmap_Ke -clamp on half.png\nnewmtl floor\nKd 0.5 0.5 0.5\n",
    )
    .unwrap();
    // The emitter faces down (its front towards −y), u along +x.
    std::fs::write(
        dir.join("lamp.obj"),
        "mtllib lamp.mtl\no lamp\nv -0.5 1 -0.5\nv 0.5 1 -0.5\nv 0.5 1 0.5\nv -0.5 1 0.5\n\
         vt 0 1\nvt 1 1\nvt 1 0\nvt 0 0\nusemtl glow\nf 1/1 2/2 3/3 4/4\n\
         o floor\nv -5 0 -5\nv 5 0 -5\nv 5 0 5\nv -5 0 5\nusemtl floor\nf 5 8 7 6\n",
    )
    .unwrap();
    let luminance = 1000.0f32;
    let exact_full = std::f64::consts::PI
        * f64::from(luminance)
        * crate::gi_support::form_factor(
            glam::DVec3::ZERO,
            glam::DVec3::Y,
            &[
                glam::DVec3::new(-0.5, 1.0, -0.5),
                glam::DVec3::new(0.5, 1.0, -0.5),
                glam::DVec3::new(0.5, 1.0, 0.5),
                glam::DVec3::new(-0.5, 1.0, 0.5),
            ],
        );
    let render_with = |camera: Camera, integrator: IntegratorKind, spp: u32, side: u32| {
        let mut loaded = load(&dir.join("lamp.obj"), &LoadOptions::default()).unwrap();
        let lamp = loaded
            .scene
            .breps
            .iter()
            .find(|b| b.name == "lamp")
            .unwrap()
            .first_slot;
        let m = &mut loaded.setup.materials[lamp as usize];
        assert!(m.textures.is_some(), "{:?}", loaded.warnings);
        m.emission_cd_m2 = luminance;
        m.emission_color = [1.0; 3];
        loaded.setup.unit = tracer_core::scene::LengthUnit::M;
        loaded.setup.lights.clear();
        loaded.setup.camera = camera;
        let settings = RenderSettings {
            width: side,
            height: side,
            samples_per_pixel: spp,
            integrator,
            ..RenderSettings::default()
        };
        render(&loaded.scene, &loaded.setup, &settings).0
    };
    // The floor's centre through a 1° camera from under the emitter (a spot 1.7 cm across,
    // where E is flat to 0.01 %): ρ/π · E.
    let floor_view = Camera {
        position: [0.0, 0.9, 0.3],
        look_at: [0.0, 0.0, 0.0],
        up: [0.0, 1.0, 0.0],
        fov_deg: 1.0,
        ..Camera::default()
    };
    let want = 0.5 / std::f64::consts::PI * exact_full / 2.0;
    for (integrator, spp) in [
        (IntegratorKind::Direct, 16384),
        (IntegratorKind::Path, 16384),
        (IntegratorKind::Bidirectional, 16384),
    ] {
        let film = render_with(floor_view, integrator, spp, 4);
        let (mean, se) = crate::gi_support::film_mean_luminance(&film);
        println!(
            "{integrator}: floor under the half-lit emitter {mean:.3} ± {se:.3} cd/m², exact {want:.3} \
             ({:+.2} %)",
            (mean / want - 1.0) * 100.0
        );
        assert!(
            (mean / want - 1.0).abs() < 0.01 && (mean - want).abs() < 4.0 * se + 1e-9,
            "{integrator}: {mean} ± {se} vs {want}"
        );
    }
    // From below, looking up at the emitter: the left half (x < 0) glows at L, the right not.
    let up_view = Camera {
        position: [0.0, 0.2, 0.0],
        look_at: [0.0, 1.0, 0.0],
        up: [0.0, 0.0, -1.0],
        projection: Projection::Orthographic,
        width: Some(1.0),
        ..Camera::default()
    };
    let film = render_with(up_view, IntegratorKind::Direct, 4, 8);
    // Image right is +x or −x depending on the view; find the bright side, then check both.
    let column = |x: u32| {
        (0..8)
            .map(|y| film.mean_luminance((y * 8 + x) as usize))
            .sum::<f64>()
            / 8.0
    };
    let (a, b) = (column(1), column(6));
    let (bright, dark) = if a > b { (a, b) } else { (b, a) };
    assert!(
        (bright / f64::from(luminance) - 1.0).abs() < 1e-3,
        "{bright}"
    );
    assert!(dark < 1e-6, "{dark}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Two materials naming one image share one texture; the denoiser's albedo guide of a texel
/// is the decoded texel times the factor.
#[test]
fn one_image_is_loaded_once_and_the_albedo_guide_takes_the_textured_colour() {
    let dir = scratch("shared");
    std::fs::write(dir.join("checker.png"), checker_png()).unwrap();
    let path = write_quad(
        &dir,
        "newmtl a\nKd 1 1 1\nmap_Kd checker.png\nnewmtl b\nKd 0.5 0.5 0.5\nmap_Kd checker.png\n",
        "o a\nusemtl a\nf 1/1 4/4 3/3\no b\nusemtl b\nf 1/1 3/3 2/2\n",
    );
    let loaded = load(&path, &LoadOptions::default()).unwrap();
    assert_eq!(loaded.scene.textures.len(), 1);
    assert_eq!(loaded.scene.texture_sets.len(), 2);
    let lit = tracer_core::lit_scene::LitScene::new(&loaded.scene, &loaded.setup, 4);
    let mut rng = tracer_core::sampling::SampleRng::new(1, 0);
    // Straight down onto texel (0, 2) (block 0) of material a (the triangle where z > x) and
    // texel (6, 2) (block 1) of material b (where x > z); u = x, v = z.
    for (x, z, factor, block) in [(0.1f32, 0.3f32, 1.0, 0usize), (0.81, 0.31, 0.5, 1)] {
        let ray = tracer_core::geometry::Ray::new(glam::Vec3::new(x, 1.0, z), glam::Vec3::NEG_Y);
        let guide = tracer_core::render::trace_guide(&lit, &ray, &mut rng);
        for (c, &code) in CODES[block].iter().enumerate() {
            let want = factor * srgb(code);
            assert!(
                (f64::from(guide.albedo[c]) - want).abs() < 1e-4,
                "({x}, {z}) channel {c}: {} vs {want}",
                guide.albedo[c]
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
