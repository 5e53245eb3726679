//! `.atr` surface attributes: `Attr NAME ... enddef` blocks of `key value` lines, read as
//! written (the mapping to materials is in `material.rs`). Keys raygine does not use (`ka`,
//! `kf`, `gm`, `Ft`, `HeatType` ...) are skipped; other blocks are skipped whole.

use super::error::IntegraError;
use super::lines::{self, Line, blocks, numbers, switch, word};
use std::path::Path;

/// One `Attr` block as written.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Attr {
    /// The name as written (`a000001`); `.prb` files refer to it in upper case.
    pub name: String,
    /// 1-based line of `Attr NAME`.
    pub line: usize,
    /// `kd`: diffuse reflectance factor.
    pub kd: Option<f64>,
    /// `ks`: specular reflectance factor.
    pub ks: Option<f64>,
    /// `kts`, `ktd`: specular and diffuse transmission factors.
    pub kts: Option<f64>,
    pub ktd: Option<f64>,
    /// `eta`: refractive index.
    pub eta: Option<f64>,
    /// `gs`: glossiness of the specular lobe.
    pub gs: Option<f64>,
    /// `color R G B`, 0..=255.
    pub color: Option<[f64; 3]>,
    /// `mirror on|off`.
    pub mirror: Option<bool>,
    /// `SelfLuminance`: emitted luminance (cd/m²).
    pub self_luminance: Option<f64>,
    /// `SelfLumDirection Pos|Neg|Both` as written.
    pub self_lum_direction: Option<String>,
    /// `shading smooth` (true) or `flat`.
    pub smooth: Option<bool>,
    /// Texture keys (`texture`, `TextureMap`, `bump` ...), with their line, as written.
    pub textures: Vec<(usize, String)>,
}

/// Reads an `.atr` file's bytes (`path` only names it in messages).
pub fn parse_atr(bytes: &[u8], path: &Path) -> Result<Vec<Attr>, IntegraError> {
    let text = lines::decode(bytes, path)?;
    let mut attrs: Vec<Attr> = Vec::new();
    for block in blocks(lines::lines(&text), path, ".atr")? {
        if !block.keyword.eq_ignore_ascii_case("Attr") {
            continue;
        }
        if let Some(first) = attrs
            .iter()
            .find(|a| a.name.eq_ignore_ascii_case(block.name))
        {
            return Err(IntegraError::new(
                path,
                block.line,
                format!(
                    "attribute {} is defined twice (first at line {})",
                    block.name, first.line
                ),
            ));
        }
        let mut attr = Attr {
            name: block.name.to_owned(),
            line: block.line,
            ..Attr::default()
        };
        for line in &block.body {
            read_key(&mut attr, line, path)?;
        }
        attrs.push(attr);
    }
    Ok(attrs)
}

fn read_key(attr: &mut Attr, line: &Line, path: &Path) -> Result<(), IntegraError> {
    let one = |line: &Line| numbers::<1>(path, line).map(|[x]| Some(x));
    match line.key().to_ascii_lowercase().as_str() {
        "kd" => attr.kd = one(line)?,
        "ks" => attr.ks = one(line)?,
        "kts" => attr.kts = one(line)?,
        "ktd" => attr.ktd = one(line)?,
        "eta" => attr.eta = one(line)?,
        "gs" => attr.gs = one(line)?,
        "selfluminance" => attr.self_luminance = one(line)?,
        "color" => attr.color = Some(numbers::<3>(path, line)?),
        "mirror" => attr.mirror = Some(switch(path, line)?),
        "selflumdirection" => attr.self_lum_direction = Some(word(path, line)?.to_owned()),
        "shading" => {
            attr.smooth = Some(match word(path, line)?.to_ascii_lowercase().as_str() {
                "smooth" => true,
                "flat" => false,
                other => {
                    return Err(IntegraError::new(
                        path,
                        line.no,
                        format!("`shading` takes flat or smooth, found `{other}`"),
                    ));
                }
            })
        }
        key if key.contains("texture") || key == "bump" || key == "tpa" => {
            attr.textures.push((line.no, line.values().join(" ")))
        }
        _ => {}
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn reads_the_keys_raygine_uses_and_skips_the_rest() {
        let text = "Geography x\n  time 12:00\nenddef\nAttr a000008\n  kd 0.45\n  ks 0.55\n  \
                    gs 29\n  gm 20\n  eta 1.5\n  color 128 128 128\n  mirror off\n  \
                    SelfLuminance 0\n  SelfLumDirection Pos\n  shading smooth\n  Ft 1.0e+000\nenddef\n";
        let attrs = parse_atr(text.as_bytes(), Path::new("r.atr")).unwrap();
        assert_eq!(attrs.len(), 1);
        let a = &attrs[0];
        assert_eq!((a.name.as_str(), a.line), ("a000008", 4));
        assert_eq!(
            (a.kd, a.ks, a.gs, a.eta),
            (Some(0.45), Some(0.55), Some(29.0), Some(1.5))
        );
        assert_eq!(a.color, Some([128.0; 3]));
        assert_eq!((a.mirror, a.smooth), (Some(false), Some(true)));
    }

    #[test]
    fn bad_values_name_the_file_and_line() {
        let cases = [
            (
                "Attr a\n kd x\nenddef\n",
                "r.atr:2: kd: expected a number, found `x`",
            ),
            (
                "Attr a\n color 1 2\nenddef\n",
                "r.atr:2: `color` takes 3 numbers, found 2",
            ),
            (
                "Attr a\n mirror maybe\nenddef\n",
                "r.atr:2: `mirror` takes on or off, found `maybe`",
            ),
            (
                "Attr a\nenddef\nAttr A\nenddef\n",
                "r.atr:3: attribute A is defined twice (first at line 1)",
            ),
            (
                "color 1 2 3\n",
                "r.atr:1: expected a block `Keyword NAME` of a .atr file, found `color 1 2 3`",
            ),
        ];
        for (text, message) in cases {
            let err = parse_atr(text.as_bytes(), Path::new("r.atr")).unwrap_err();
            assert_eq!(err.to_string(), message);
        }
    }
}
