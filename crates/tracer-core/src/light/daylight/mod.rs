//! Daylight: where the sun is for a place and time ([`sun_position`]), the CIE overcast and
//! uniform skies as environment lights ([`Sky`]), and the sidecar's `[daylight]` section that
//! names them ([`Daylight`]).

mod sky;
mod spec;
mod sun;

pub use spec::{Daylight, DaylightSpec, Sky, SkyModel};
pub use sun::{ClockTime, Date, PlaceTime, SunPosition, sun_position};
