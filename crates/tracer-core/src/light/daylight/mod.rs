//! Daylight: where the sun is for a place and time ([`sun_position`]), and the sidecar's
//! `[daylight]` section that names them ([`Daylight`]).

mod spec;
mod sun;

pub use spec::{Daylight, DaylightSpec};
pub use sun::{ClockTime, Date, PlaceTime, SunPosition, sun_position};
