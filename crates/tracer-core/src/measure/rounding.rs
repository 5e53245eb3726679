//! Readings rounded to what their uncertainty supports, for people and for files: a value keeps
//! decimals down to its standard error's first significant digit, and never more than three
//! significant figures; a standard error keeps two significant figures. Nothing is written
//! below 10⁻⁶ (a reading of 5.7e-14 lx is float noise, and reads 0).

/// The most decimals any rounded number keeps.
pub const MAX_DECIMALS: i32 = 6;

/// How precisely files and reports write numbers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Precision {
    /// Rounded to what the uncertainty supports (people read these).
    #[default]
    Rounded,
    /// Every digit the computation has (for machines: `--precision full`).
    Full,
}

impl Precision {
    pub fn from_name(name: &str) -> Option<Precision> {
        match name {
            "rounded" => Some(Precision::Rounded),
            "full" => Some(Precision::Full),
            _ => None,
        }
    }

    /// `value` with standard error `std_error`, as written at this precision.
    pub fn value(self, value: f64, std_error: f64) -> f64 {
        match self {
            Precision::Rounded => round_to(value, decimals(value, std_error)),
            Precision::Full => value,
        }
    }

    /// A standard error as written at this precision.
    pub fn std_error(self, std_error: f64) -> f64 {
        match self {
            Precision::Rounded => round_to(std_error, significant_decimals(std_error, 2)),
            Precision::Full => std_error,
        }
    }
}

/// The decimals (negative: tens, hundreds) that `value ± std_error` supports: down to the
/// standard error's first significant digit, at most three significant figures of the value,
/// and at most [`MAX_DECIMALS`]. An exact value (`std_error` 0) keeps three significant
/// figures.
pub fn decimals(value: f64, std_error: f64) -> i32 {
    let figures = significant_decimals(value, 3);
    let supported = if std_error > 0.0 && std_error.is_finite() {
        significant_decimals(std_error, 1)
    } else {
        figures
    };
    supported.min(figures).min(MAX_DECIMALS)
}

/// The decimals that keep `figures` significant figures of `v` (at most [`MAX_DECIMALS`]).
fn significant_decimals(v: f64, figures: i32) -> i32 {
    if v == 0.0 || !v.is_finite() {
        return 0;
    }
    let leading = v.abs().log10().floor() as i32;
    (figures - 1 - leading).min(MAX_DECIMALS)
}

/// `v` rounded to `decimals` decimals (negative: to tens, hundreds, ...), with no float noise
/// left in its shortest printed form.
pub fn round_to(v: f64, decimals: i32) -> f64 {
    if !v.is_finite() {
        return v;
    }
    let rounded = if decimals >= 0 {
        let text = format!("{v:.0$}", decimals as usize);
        text.parse::<f64>().unwrap_or(v)
    } else {
        let scale = 10f64.powi(-decimals);
        (v / scale).round() * scale
    };
    // No "-0".
    if rounded == 0.0 { 0.0 } else { rounded }
}

/// `value` as text with the decimals its standard error supports (trailing zeros kept, so
/// "0.500" says it is known to the thousandth).
pub fn format_reading(value: f64, std_error: f64) -> String {
    let d = decimals(value, std_error);
    format_with(value, d)
}

/// A standard error as text, two significant figures.
pub fn format_std_error(std_error: f64) -> String {
    format_with(std_error, significant_decimals(std_error, 2))
}

/// `v` as text with `decimals` decimals (negative: rounded to tens, hundreds, ...).
pub fn format_with(v: f64, decimals: i32) -> String {
    let r = round_to(v, decimals);
    if r.abs() < 0.5 * 10f64.powi(-MAX_DECIMALS) {
        return "0".to_owned();
    }
    if decimals > 0 {
        format!("{r:.0$}", decimals as usize)
    } else {
        format!("{r:.0}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn readings_keep_what_their_error_supports_and_three_figures_at_most() {
        assert_eq!(format_reading(104.53, 0.84), "105");
        assert_eq!(format_reading(104.53, 8.4), "105");
        assert_eq!(format_reading(104.53, 84.0), "100");
        assert_eq!(format_reading(0.5, 0.001), "0.500");
        assert_eq!(format_reading(12.345, 0.05), "12.3");
        assert_eq!(format_reading(1234.5, 3.0), "1230");
        assert_eq!(format_reading(3.24591, 0.0), "3.25");
        // Float noise reads 0, never "5.684341886080802e-14".
        assert_eq!(format_reading(5.684341886080802e-14, 0.0), "0");
        assert_eq!(format_reading(-0.0, 0.0), "0");
        assert_eq!(format_std_error(0.8437), "0.84");
        assert_eq!(format_std_error(123.4), "120");
        assert_eq!(Precision::Rounded.value(104.53, 0.84), 105.0);
        assert_eq!(Precision::Rounded.value(0.1 + 0.2, 0.01), 0.3);
        assert_eq!(Precision::Full.value(0.1 + 0.2, 0.01), 0.1 + 0.2);
        assert_eq!(Precision::Rounded.std_error(0.012345), 0.012);
        assert_eq!(round_to(5.684341886080802e-14, 6), 0.0);
    }
}
