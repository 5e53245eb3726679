//! Daylight: where the sun is for a place and time ([`sun_position`]), the CIE overcast,
//! uniform and general skies and the Perez all-weather sky as environment lights ([`Sky`],
//! [`GeneralSky`], [`PerezSky`]), the sun's disc,
//! and the sidecar's `[daylight]` section that names them ([`Daylight`]).

mod cie_general;
mod perez;
mod sky;
mod spec;
mod sun;

pub use cie_general::GeneralSky;
pub use perez::PerezSky;
pub use spec::{Daylight, DaylightSpec, Sky, SkyModel};
pub use sun::{ClockTime, Date, PlaceTime, SunPosition, sun_position};

/// The sun's angular diameter, degrees.
pub const SUN_DIAMETER_DEG: f64 = 0.533;
