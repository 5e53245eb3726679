//! Length units and the handedness of a scene's coordinate frame.

use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// The unit of the file's coordinates. Photometry is SI (metres), so distances are converted with
/// [`LengthUnit::metres_per_unit`] before `E = I cos θ / R²`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LengthUnit {
    #[default]
    Mm,
    Cm,
    M,
}

impl LengthUnit {
    pub const ALL: [LengthUnit; 3] = [LengthUnit::Mm, LengthUnit::Cm, LengthUnit::M];

    pub fn metres_per_unit(self) -> f32 {
        match self {
            LengthUnit::Mm => 1e-3,
            LengthUnit::Cm => 1e-2,
            LengthUnit::M => 1.0,
        }
    }

    pub fn symbol(self) -> &'static str {
        match self {
            LengthUnit::Mm => "mm",
            LengthUnit::Cm => "cm",
            LengthUnit::M => "m",
        }
    }

    /// A hint when a scene of this size (bounding-box diagonal in this unit) looks like it was
    /// written in another unit: rooms and objects people light are 5 cm to 500 m across.
    /// Returns `None` when the size is plausible. Never applied silently.
    pub fn size_hint(self, diagonal: f32) -> Option<String> {
        let suggestion = self.suggested_unit(diagonal)?;
        let metres = diagonal * self.metres_per_unit();
        Some(format!(
            "the scene is {diagonal:.4} {} across ({metres:.4} m) if its unit is {}; if it was \
             written in {}, pass --units {}",
            self.symbol(),
            self.symbol(),
            suggestion.symbol(),
            suggestion.symbol()
        ))
    }

    /// The unit a scene of this size (bounding-box diagonal in this unit) was more likely
    /// written in, when this one makes it implausibly small or large (see
    /// [`LengthUnit::size_hint`]).
    pub fn suggested_unit(self, diagonal: f32) -> Option<LengthUnit> {
        let metres = diagonal * self.metres_per_unit();
        if !metres.is_finite() || metres <= 0.0 {
            return None;
        }
        let suggestion = if metres < 0.05 {
            LengthUnit::ALL
                .into_iter()
                .rev()
                .find(|u| diagonal * u.metres_per_unit() >= 0.05)
        } else if metres > 500.0 {
            LengthUnit::ALL
                .into_iter()
                .find(|u| diagonal * u.metres_per_unit() <= 500.0)
        } else {
            None
        }?;
        (suggestion != self).then_some(suggestion)
    }
}

impl fmt::Display for LengthUnit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.symbol())
    }
}

impl FromStr for LengthUnit {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "mm" | "millimetre" | "millimeter" => Ok(LengthUnit::Mm),
            "cm" | "centimetre" | "centimeter" => Ok(LengthUnit::Cm),
            "m" | "metre" | "meter" => Ok(LengthUnit::M),
            other => Err(format!(
                "unknown length unit `{other}` (expected mm, cm or m)"
            )),
        }
    }
}

/// How the file's coordinates map to the picture. Lumicept swaps Y and Z on export, so its files
/// are mirror images: read as left-handed, +X appears on the LEFT for a camera at +Z looking
/// towards -Z. Only the camera basis depends on this; coordinates stay the file's own numbers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Handedness {
    #[default]
    Left,
    Right,
}
