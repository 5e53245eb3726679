//! Numbers and notes as the viewer shows them.

/// A note as a sentence: its first letter capital, a full stop at its end.
pub fn sentence(note: &str) -> String {
    let mut chars = note.trim().chars();
    let mut text: String = match chars.next() {
        Some(first) => first.to_uppercase().chain(chars).collect(),
        None => return String::new(),
    };
    if !text.ends_with(['.', '!', '?']) {
        text.push('.');
    }
    text
}

/// A value with 3 significant digits.
pub fn format_value(v: f32) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let digits = (2 - v.abs().log10().floor() as i32).max(0) as usize;
    format!("{v:.digits$}")
}

/// A quantity with its unit and an SI prefix, so small values keep their digits: "100 cd",
/// "3.20 mcd", "45.0 µcd", "1.26 klm". Zero reads "0 cd".
pub fn format_quantity(v: f32, unit: &str) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v} {unit}");
    }
    const PREFIXES: [(f32, &str); 7] = [
        (1e9, "G"),
        (1e6, "M"),
        (1e4, "k"),
        (1.0, ""),
        (1e-3, "m"),
        (1e-6, "µ"),
        (1e-9, "n"),
    ];
    let a = v.abs();
    let (scale, prefix) = PREFIXES
        .iter()
        .copied()
        .find(|&(s, _)| a >= s)
        .unwrap_or((1e-9, "n"));
    // Ten thousand and above in k (the plain number is short enough below).
    let (scale, prefix) = if scale == 1e4 {
        (1e3, "k")
    } else {
        (scale, prefix)
    };
    format!("{} {prefix}{unit}", format_value(v / scale))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantities_keep_their_digits() {
        assert_eq!(format_quantity(100.0, "cd"), "100 cd");
        assert_eq!(format_quantity(0.0032, "cd"), "3.20 mcd");
        assert_eq!(format_quantity(4.5e-5, "cd"), "45.0 µcd");
        assert_eq!(format_quantity(12_566.0, "lm"), "12.6 klm");
        assert_eq!(format_quantity(1257.0, "lm"), "1257 lm");
        assert_eq!(format_quantity(0.0, "cd"), "0 cd");
    }
}
