//! MTL texture statements (`map_Kd -s 2 2 wood.png`) as raygine's maps:
//!
//! | MTL | raygine |
//! |-----|---------|
//! | `map_Kd` | multiplies Kd (or the base colour with `Pr`/`Pm`), sRGB |
//! | `map_Ks` | multiplies Ks, sRGB |
//! | `map_d` | alpha: the image's alpha channel, or its red channel when it has none; the surface is there with that probability (stochastic: a 0/1 mask cuts out exactly) |
//! | `map_Pr`, `map_Pm` | multiply roughness and metallic (red channel, linear) |
//! | `norm` | a tangent-space normal map (MikkTSpace tangents) |
//! | `bump`, `map_Bump` | a height map (red channel, linear) in scene units times `-bm` |
//! | `map_Ke` | multiplies the emission (`Ke`), sRGB |
//! | `map_Ka`, `map_Ns`, `refl`, `disp` | not used (noted) |
//!
//! Options: `-s u v` and `-o u v` scale and offset the texture coordinates, `-clamp on` clamps
//! them (else they repeat), `-bm` scales a bump map's heights; others (`-imfchan`, `-blendu`,
//! `-mm`, ...) are skipped with a note. File names are relative to the MTL file's folder; `\` separators are read as `/`.
//! OBJ's `v` points up the image, so the reader stores `1 − v` (the image's frame) and the
//! transform here works in that frame.

use crate::formats::ImageSource;
use crate::texture::{AlphaMode, Filter, Maps, TextureRef, UvTransform, Wrap};
use std::path::Path;

/// One parsed texture statement: the file and the options raygine reads.
#[derive(Debug, PartialEq)]
struct Statement {
    file: String,
    scale: [f32; 2],
    offset: [f32; 2],
    clamp: bool,
    /// `-bm`: the bump multiplier.
    bump_multiplier: Option<f32>,
    /// Options read but not used, for the note.
    skipped: Vec<String>,
}

/// Parses `[-option values...]... file`.
fn statement(text: &str) -> Result<Statement, String> {
    let words: Vec<&str> = text.split_whitespace().collect();
    let mut out = Statement {
        file: String::new(),
        scale: [1.0; 2],
        offset: [0.0; 2],
        clamp: false,
        bump_multiplier: None,
        skipped: Vec::new(),
    };
    let mut i = 0;
    // Numbers after an option, up to `max` of them.
    let numbers = |i: &mut usize, max: usize| -> Vec<f32> {
        let mut v = Vec::new();
        while v.len() < max {
            match words.get(*i).and_then(|w| w.parse::<f32>().ok()) {
                Some(x) if x.is_finite() => {
                    v.push(x);
                    *i += 1;
                }
                _ => break,
            }
        }
        v
    };
    while let Some(&w) = words.get(i) {
        if !w.starts_with('-') || w.len() < 2 || w[1..].parse::<f32>().is_ok() {
            break;
        }
        i += 1;
        match w {
            "-s" | "-o" => {
                let v = numbers(&mut i, 3);
                if v.len() < 2 {
                    return Err(format!("{w} takes two or three numbers"));
                }
                let target = if w == "-s" {
                    &mut out.scale
                } else {
                    &mut out.offset
                };
                *target = [v[0], v[1]];
            }
            "-clamp" => {
                let on = words.get(i).copied().unwrap_or("");
                out.clamp = match on {
                    "on" => true,
                    "off" => false,
                    _ => return Err(format!("-clamp takes on or off, found `{on}`")),
                };
                i += 1;
            }
            "-blendu" | "-blendv" | "-cc" | "-imfchan" | "-type" => {
                out.skipped.push(w.to_owned());
                i += 1;
            }
            "-bm" => {
                let v = numbers(&mut i, 1);
                out.bump_multiplier = Some(*v.first().ok_or("-bm takes a number")?);
            }
            "-boost" | "-texres" => {
                out.skipped.push(w.to_owned());
                numbers(&mut i, 1);
            }
            "-mm" => {
                out.skipped.push(w.to_owned());
                numbers(&mut i, 2);
            }
            "-t" => {
                out.skipped.push(w.to_owned());
                numbers(&mut i, 3);
            }
            other => return Err(format!("unknown option {other}")),
        }
    }
    out.file = words[i.min(words.len())..].join(" ");
    if out.file.is_empty() {
        return Err("names no file".into());
    }
    Ok(out)
}

/// The maps of an MTL material `m` read from `source` (notes name `at`).
pub(super) fn maps(
    m: &tobj::Material,
    source: &Path,
    at: &str,
    notes: &mut Vec<String>,
) -> Maps<TextureRef<ImageSource>> {
    let folder = source.parent().unwrap_or(Path::new(""));
    let mut bump_multiplier = None;
    let mut one = |key: &str, value: Option<&String>| {
        let value = value?;
        let s = match statement(value) {
            Ok(s) => s,
            Err(why) => {
                notes.push(format!("{at}: {key} {value}: {why}; not used"));
                return None;
            }
        };
        if !s.skipped.is_empty() {
            notes.push(format!(
                "{at}: {key}: options {} are not used",
                s.skipped.join(", ")
            ));
        }
        if s.bump_multiplier.is_some() {
            bump_multiplier = s.bump_multiplier;
        }
        let [su, sv] = s.scale;
        let [ou, ov] = s.offset;
        Some(TextureRef {
            texture: ImageSource::File(folder.join(s.file.replace('\\', "/"))),
            set: 0,
            // -s/-o act on OBJ's v (up the image); the stored v is 1 − that.
            transform: UvTransform([su, 0.0, ou, 0.0, sv, 1.0 - sv - ov]),
            wrap: [if s.clamp { Wrap::Clamp } else { Wrap::Repeat }; 2],
            filter: Filter::Linear,
        })
    };
    let param = |k: &str| m.unknown_param.get(k);
    let mut out = Maps {
        material: m.name.clone(),
        ..Maps::default()
    };
    out.base_color = one("map_Kd", m.diffuse_texture.as_ref());
    out.specular = one("map_Ks", m.specular_texture.as_ref());
    out.roughness = one("map_Pr", param("map_Pr"));
    out.metallic = one("map_Pm", param("map_Pm"));
    out.alpha_map = one("map_d", m.dissolve_texture.as_ref());
    out.normal = one("norm", param("norm"));
    out.emissive = one("map_Ke", param("map_Ke"));
    // tobj files `bump` and `map_Bump` as its "normal texture": they are height maps.
    out.bump = one("bump", m.normal_texture.as_ref());
    out.bump_scale = bump_multiplier.unwrap_or(1.0);
    if out.alpha_map.is_some() {
        out.alpha_mode = AlphaMode::Blend;
    }
    let unused: Vec<&str> = [
        ("map_Ka", m.ambient_texture.is_some()),
        ("map_Ns", m.shininess_texture.is_some()),
        ("refl", param("refl").is_some()),
        ("disp", param("disp").is_some()),
    ]
    .into_iter()
    .filter_map(|(k, has)| has.then_some(k))
    .collect();
    if !unused.is_empty() {
        notes.push(format!("{at}: not used: {}", unused.join(", ")));
    }
    out
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;

    #[test]
    fn options_are_read_and_the_file_keeps_its_spaces() {
        let s = statement("-s 2 3 1 -o 0.5 0.25 -clamp on my wood.png").unwrap();
        assert_eq!(s.file, "my wood.png");
        assert_eq!(
            (s.scale, s.offset, s.clamp),
            ([2.0, 3.0], [0.5, 0.25], true)
        );
        let s = statement("-bm 0.5 -imfchan l bump.png").unwrap();
        assert_eq!(s.file, "bump.png");
        assert_eq!(s.bump_multiplier, Some(0.5));
        assert_eq!(s.skipped, vec!["-imfchan"]);
        assert!(statement("-s 2").unwrap_err().contains("two or three"));
        assert!(
            statement("-clamp maybe a.png")
                .unwrap_err()
                .contains("on or off")
        );
        assert!(statement("-s 1 1").unwrap_err().contains("no file"));
        assert!(
            statement("-zz a.png")
                .unwrap_err()
                .contains("unknown option")
        );
    }

    #[test]
    fn the_offset_and_scale_act_on_objs_v_up_the_image() {
        let (mats, _) =
            tobj::load_mtl_buf(&mut "newmtl a\nmap_Kd -s 2 2 -o 0.5 0.25 t.png\n".as_bytes())
                .unwrap();
        let mut notes = Vec::new();
        let maps = maps(&mats[0], Path::new("dir/m.mtl"), "a", &mut notes);
        let r = maps.base_color.unwrap();
        assert_eq!(r.texture, ImageSource::File("dir/t.png".into()));
        // OBJ (u, v) = (0.1, 0.2) is stored as (0.1, 0.8); MTL maps it to (0.7, 0.65) in OBJ's
        // frame, which is (0.7, 0.35) in the image's.
        let p = r.transform.apply(glam::Vec2::new(0.1, 0.8));
        assert!((p - glam::Vec2::new(0.7, 0.35)).length() < 1e-6, "{p}");
    }
}
