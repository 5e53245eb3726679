//! The variants of a sweep: `[[variants]]` tables in a TOML file, each an optional `name` and
//! sidecar keys that patch the scene's sidecar.
//!
//! ```toml
//! [[variants]]
//! name = "left"                                   # A-Z a-z 0-9 _ - (default: variant-I)
//! lights = [{ position = [100.0, 540.0, -100.0] }]  # patches the first light only
//!
//! [[variants]]
//! name = "dim_red"
//! lights = [{}, { intensity_cd = 20.0 }]          # the second light
//! camera = { fov_deg = 60.0 }
//! materials.red_wall = { kd = [0.8, 0.1, 0.1] }
//! ```
//!
//! A patch merges into the sidecar key by key: tables merge recursively, an array of tables
//! merges element by element (element i of the patch into element i of the sidecar, extra
//! elements appended), anything else replaces the sidecar's value.

use std::path::Path;
use toml::{Table, Value};

/// One variant: its name and its patch.
#[derive(Clone, Debug, PartialEq)]
pub struct Variant {
    pub name: String,
    pub patch: Table,
}

/// Reads the variants file; errors name it (and the variant).
pub fn read_variants(path: &Path) -> Result<Vec<Variant>, String> {
    let at = |m: String| format!("{}: {m}", path.display());
    let text = std::fs::read_to_string(path).map_err(|e| at(format!("cannot read: {e}")))?;
    parse_variants(&text).map_err(at)
}

/// Parses the text of a variants file.
pub fn parse_variants(text: &str) -> Result<Vec<Variant>, String> {
    let mut doc: Table = toml::from_str(text).map_err(|e| e.message().to_owned())?;
    if let Some(key) = doc.keys().find(|k| *k != "variants") {
        return Err(format!(
            "unknown key `{key}` (the file holds [[variants]] tables)"
        ));
    }
    let Some(Value::Array(list)) = doc.remove("variants") else {
        return Err("no [[variants]] tables".to_owned());
    };
    let mut variants: Vec<Variant> = Vec::with_capacity(list.len());
    for (i, v) in list.into_iter().enumerate() {
        let Value::Table(mut patch) = v else {
            return Err(format!("variant {i} is not a table"));
        };
        let name = match patch.remove("name") {
            None => format!("variant-{i}"),
            Some(Value::String(s)) => s,
            Some(_) => return Err(format!("variant {i}: `name` must be a string")),
        };
        let valid = !name.is_empty()
            && name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
        if !valid {
            return Err(format!(
                "variant {i}: name `{name}` must use only A-Z, a-z, 0-9, _ and -"
            ));
        }
        if variants.iter().any(|o| o.name == name) {
            return Err(format!("two variants are named {name}"));
        }
        variants.push(Variant { name, patch });
    }
    if variants.is_empty() {
        return Err("no [[variants]] tables".to_owned());
    }
    Ok(variants)
}

/// `base` with `patch` merged in (the rules in the module docs).
pub fn patched(base: &Table, patch: &Table) -> Table {
    let mut out = base.clone();
    for (key, p) in patch {
        let merged = match (out.get(key), p) {
            (Some(Value::Table(b)), Value::Table(p)) => Value::Table(patched(b, p)),
            (Some(Value::Array(b)), Value::Array(p)) if all_tables(b) && all_tables(p) => {
                let mut list = b.clone();
                for (i, item) in p.iter().enumerate() {
                    match (list.get_mut(i), item) {
                        (Some(Value::Table(bt)), Value::Table(pt)) => {
                            *bt = patched(bt, pt);
                        }
                        _ => list.push(item.clone()),
                    }
                }
                Value::Array(list)
            }
            _ => p.clone(),
        };
        out.insert(key.clone(), merged);
    }
    out
}

fn all_tables(list: &[Value]) -> bool {
    list.iter().all(Value::is_table)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    #[test]
    fn patches_merge_tables_and_arrays_of_tables_element_by_element() {
        let base: Table = toml::from_str(
            "unit = \"mm\"\n[camera]\nfov_deg = 40.0\nposition = [0.0, 1.0, 2.0]\n\
             [[lights]]\nposition = [1.0, 2.0, 3.0]\nintensity_cd = 100.0\n\
             [[lights]]\nposition = [4.0, 5.0, 6.0]\n",
        )
        .unwrap();
        let variants = parse_variants(
            "[[variants]]\nname = \"a\"\nlights = [{}, { intensity_cd = 5.0 }]\n\
             camera = { fov_deg = 60.0 }\n[[variants]]\nlights = [{ position = [9.0, 9.0, 9.0] }]\n",
        )
        .unwrap();
        assert_eq!(variants[1].name, "variant-1");
        let a = patched(&base, &variants[0].patch);
        assert_eq!(a["camera"]["fov_deg"].as_float(), Some(60.0));
        assert_eq!(a["camera"]["position"], base["camera"]["position"]);
        assert_eq!(a["lights"][0], base["lights"][0]);
        assert_eq!(a["lights"][1]["intensity_cd"].as_float(), Some(5.0));
        assert_eq!(a["lights"][1]["position"], base["lights"][1]["position"]);
        let b = patched(&base, &variants[1].patch);
        assert_eq!(b["lights"][0]["position"][0].as_float(), Some(9.0));
        assert_eq!(b["lights"][0]["intensity_cd"].as_float(), Some(100.0));
    }

    #[test]
    fn bad_variant_files_are_refused() {
        assert!(parse_variants("").unwrap_err().contains("no [[variants]]"));
        assert!(parse_variants("[[variants]]\nname = \"a b\"\n").is_err());
        assert!(
            parse_variants("[[variants]]\nname = \"a\"\n[[variants]]\nname = \"a\"\n").is_err()
        );
        assert!(
            parse_variants("[[variant]]\n")
                .unwrap_err()
                .contains("unknown key")
        );
    }
}
