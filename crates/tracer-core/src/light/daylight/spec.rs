//! The sidecar's `[daylight]`: the place, the local time and the scene's orientation.
//!
//! ```toml
//! [daylight]
//! latitude = 36.0               # degrees north
//! longitude = -140.0            # degrees, east positive unless longitude_convention = "west"
//! longitude_convention = "west" # Integra and Radiance count west positive (Tokyo: -140)
//! date = "2026-06-21"           # local
//! time = "12:00"                # local clock time
//! timezone = 9.0                # hours east of UTC
//! daylight_saving = false
//! north = [0.0, 0.0, -1.0]      # the scene direction of north (default -Z)
//! zenith = [0.0, 1.0, 0.0]      # default: the scene's up, +Y
//! sky = "cie-overcast"          # "none" (default), "uniform", "cie-overcast", "cie:1".."cie:15"
//!                               # or "perez" (with direct_normal_lx and diffuse_horizontal_lx)
//! zenith_luminance_cd_m2 = 3000.0   # or diffuse_horizontal_lx = 7330.0, not both
//! ground_reflectance = 0.2      # the ground below the horizon (default 0.2)
//! sun = true                    # a disc 0.533° across (default false)
//! sun_normal_illuminance_lx = 80000.0   # its illuminance on a plane facing it
//! ```

use super::sun::{ClockTime, Date, PlaceTime, SunPosition, sun_position};
use glam::Vec3;
use serde::{Deserialize, Serialize};

/// `[daylight]` as written.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DaylightSpec {
    pub latitude: f64,
    pub longitude: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub longitude_convention: Option<String>,
    pub date: String,
    pub time: String,
    pub timezone: f64,
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub daylight_saving: bool,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub north: Option<[f32; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub zenith: Option<[f32; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sky: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub zenith_luminance_cd_m2: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diffuse_horizontal_lx: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ground_reflectance: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub direct_normal_lx: Option<f64>,
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub sun: bool,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sun_normal_illuminance_lx: Option<f64>,
}

/// A sky's luminance distribution.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SkyModel {
    Uniform,
    CieOvercast,
    /// ISO 15469 / CIE S 011 general sky of type 1..=15.
    CieGeneral(u8),
    /// Perez all-weather sky (its coefficients are the `Sky`'s).
    Perez,
}

/// A sky with its scale and the ground below it (see `super::sky`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sky {
    pub model: SkyModel,
    pub zenith_luminance_cd_m2: f64,
    /// Reflectance of the ground below the horizon, 0..=1.
    pub ground_reflectance: f64,
    /// The sun's zenith angle (radians), which shapes the general skies.
    pub sun_zenith_rad: f64,
    /// The Perez sky's coefficients (`SkyModel::Perez`).
    pub perez: Option<super::PerezSky>,
    /// E_h / Lz, computed once (a quadrature for the skies that follow the sun).
    pub(super) horizontal_over_zenith: f64,
}

/// The place, the time and the scene's orientation, checked.
#[derive(Clone, Debug, PartialEq)]
pub struct Daylight {
    /// As written (saved back as written).
    pub spec: DaylightSpec,
    pub place_time: PlaceTime,
    /// Unit scene direction of north, horizontal (perpendicular to `zenith`).
    pub north: Vec3,
    /// Unit scene direction of the zenith.
    pub zenith: Vec3,
    /// The sky, an environment light (None: `sky = "none"`).
    pub sky: Option<Sky>,
    /// The sun's illuminance on a plane facing it (lx) when the sun is on.
    pub sun_normal_illuminance_lx: Option<f64>,
}

impl DaylightSpec {
    /// The checked model, or what is wrong, naming the key.
    pub fn to_model(&self) -> Result<Daylight, String> {
        let finite = |key: &str, v: f64, range: std::ops::RangeInclusive<f64>| {
            if v.is_finite() && range.contains(&v) {
                Ok(v)
            } else {
                Err(format!(
                    "daylight: {key} = {v} is outside {}..{}",
                    range.start(),
                    range.end()
                ))
            }
        };
        let latitude_deg = finite("latitude", self.latitude, -90.0..=90.0)?;
        let longitude = finite("longitude", self.longitude, -180.0..=180.0)?;
        let longitude_deg = match self.longitude_convention.as_deref() {
            None | Some("east") => longitude,
            Some("west") => -longitude,
            Some(other) => {
                return Err(format!(
                    "daylight: longitude_convention = \"{other}\": give \"east\" (east positive, \
                     the default) or \"west\""
                ));
            }
        };
        let timezone_h = finite("timezone", self.timezone, -12.0..=14.0)?;
        let date = Date::parse(&self.date).map_err(|e| format!("daylight: date: {e}"))?;
        let time = ClockTime::parse(&self.time).map_err(|e| format!("daylight: time: {e}"))?;
        let vector = |key: &str, v: Option<[f32; 3]>, default: Vec3| match v {
            None => Ok(default),
            Some(v) => Vec3::from(v)
                .try_normalize()
                .filter(|v| v.is_finite())
                .ok_or_else(|| format!("daylight: {key} = {v:?} is not a direction")),
        };
        let zenith = vector("zenith", self.zenith, Vec3::Y)?;
        let north = vector("north", self.north, Vec3::NEG_Z)?;
        // North is made horizontal; it must not point along the zenith.
        let north = (north - zenith * north.dot(zenith))
            .try_normalize()
            .ok_or_else(|| "daylight: north points along the zenith".to_owned())?;
        let place_time = PlaceTime {
            latitude_deg,
            longitude_deg,
            date,
            time,
            timezone_h,
            daylight_saving: self.daylight_saving,
        };
        let sun_zenith_rad = sun_position(&place_time).zenith_deg().to_radians();
        let sky = self.sky_model(zenith, sun_zenith_rad, date.day_of_year())?;
        let perez = sky.is_some_and(|s| s.model == SkyModel::Perez);
        let sun_keys = match (perez, self.sun_normal_illuminance_lx) {
            // The Perez sky gives the sun its direct normal illuminance.
            (true, Some(_)) => {
                return Err(
                    "daylight: the Perez sky's sun is its direct_normal_lx; leave \
                     sun_normal_illuminance_lx out"
                        .into(),
                );
            }
            (true, None) if self.sun => (true, self.direct_normal_lx),
            (_, given) => (self.sun, given),
        };
        let sun_normal_illuminance_lx = match sun_keys {
            (true, Some(e)) if e.is_finite() && e >= 0.0 => Some(e),
            (true, Some(e)) => {
                return Err(format!(
                    "daylight: sun_normal_illuminance_lx = {e} must be 0 or more"
                ));
            }
            (true, None) => {
                return Err(
                    "daylight: sun = true needs sun_normal_illuminance_lx (lx on a \
                            plane facing the sun; a clear day: 70000-100000)"
                        .into(),
                );
            }
            (false, Some(_)) => {
                return Err("daylight: sun_normal_illuminance_lx without sun = true".into());
            }
            (false, None) => None,
        };
        Ok(Daylight {
            spec: self.clone(),
            sky,
            place_time,
            north,
            zenith,
            sun_normal_illuminance_lx,
        })
    }
}

impl DaylightSpec {
    /// The sky the keys give, checked.
    fn sky_model(
        &self,
        zenith: Vec3,
        sun_zenith_rad: f64,
        day_of_year: u32,
    ) -> Result<Option<Sky>, String> {
        let model = match self.sky.as_deref() {
            None | Some("none") => {
                let stray: Vec<&str> = [
                    (
                        "zenith_luminance_cd_m2",
                        self.zenith_luminance_cd_m2.is_some(),
                    ),
                    (
                        "diffuse_horizontal_lx",
                        self.diffuse_horizontal_lx.is_some(),
                    ),
                    ("ground_reflectance", self.ground_reflectance.is_some()),
                    ("direct_normal_lx", self.direct_normal_lx.is_some()),
                ]
                .iter()
                .filter_map(|&(k, given)| given.then_some(k))
                .collect();
                if !stray.is_empty() {
                    return Err(format!(
                        "daylight: {} without a sky (sky = \"uniform\", \"cie-overcast\" or \
                         \"cie:1\"..\"cie:15\")",
                        stray.join(", ")
                    ));
                }
                return Ok(None);
            }
            Some("uniform") => SkyModel::Uniform,
            Some("cie-overcast") => SkyModel::CieOvercast,
            Some("perez") => SkyModel::Perez,
            Some(other) => match other.strip_prefix("cie:").map(str::parse::<u8>) {
                Some(Ok(t)) if (1..=15).contains(&t) => SkyModel::CieGeneral(t),
                _ => {
                    return Err(format!(
                        "daylight: sky = \"{other}\": give \"none\", \"uniform\", \
                         \"cie-overcast\", a general sky \"cie:1\" to \"cie:15\" or \"perez\""
                    ));
                }
            },
        };
        let perez = match (model, self.direct_normal_lx) {
            (SkyModel::Perez, Some(dn)) => {
                let (Some(dh), None) = (self.diffuse_horizontal_lx, self.zenith_luminance_cd_m2)
                else {
                    return Err("daylight: sky = \"perez\" takes direct_normal_lx and \
                         diffuse_horizontal_lx (lx), not zenith_luminance_cd_m2"
                        .into());
                };
                Some(
                    super::PerezSky::from_illuminances(dn, dh, sun_zenith_rad, day_of_year)
                        .map_err(|e| format!("daylight: {e}"))?,
                )
            }
            (SkyModel::Perez, None) => {
                return Err(
                    "daylight: sky = \"perez\" needs direct_normal_lx and diffuse_horizontal_lx \
                     (lx)"
                        .into(),
                );
            }
            (_, Some(_)) => {
                return Err(
                    "daylight: direct_normal_lx is the Perez sky's (sky = \"perez\"); under \
                     another sky the sun takes sun = true and sun_normal_illuminance_lx"
                        .into(),
                );
            }
            (_, None) => None,
        };
        if zenith.dot(Vec3::Y) < 0.9999 {
            return Err(
                "daylight: a sky needs the zenith along +Y (the environment's up) for now".into(),
            );
        }
        let positive = |key: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(v)
            } else {
                Err(format!("daylight: {key} = {v} must be above 0"))
            }
        };
        let zenith_luminance_cd_m2 = match (self.zenith_luminance_cd_m2, self.diffuse_horizontal_lx)
        {
            (Some(lz), None) => positive("zenith_luminance_cd_m2", lz)?,
            (None, Some(eh)) => {
                let ratio = Sky::new(model, 1.0, 0.0, sun_zenith_rad, perez).horizontal_over_zenith;
                positive("diffuse_horizontal_lx", eh)? / ratio
            }
            (Some(_), Some(_)) => {
                return Err(
                    "daylight: give zenith_luminance_cd_m2 or diffuse_horizontal_lx, not both"
                        .into(),
                );
            }
            (None, None) => {
                return Err(format!(
                    "daylight: sky = \"{}\" needs zenith_luminance_cd_m2 (cd/m²) or \
                     diffuse_horizontal_lx (lx)",
                    model.name()
                ));
            }
        };
        let ground_reflectance = self.ground_reflectance.unwrap_or(0.2);
        if !(0.0..=1.0).contains(&ground_reflectance) {
            return Err(format!(
                "daylight: ground_reflectance = {ground_reflectance} is outside 0..1"
            ));
        }
        Ok(Some(Sky::new(
            model,
            zenith_luminance_cd_m2,
            ground_reflectance,
            sun_zenith_rad,
            perez,
        )))
    }
}

impl Daylight {
    pub fn sun(&self) -> SunPosition {
        sun_position(&self.place_time)
    }

    /// Unit scene direction towards the sun. East is where the sun rises: to the right of
    /// north seen from above, `north × zenith` in a right-handed frame and `zenith × north` in
    /// a left-handed one (`right_handed`), so that a mirrored `.shp` scene still has its
    /// morning sun in the east.
    pub fn sun_direction(&self, right_handed: bool) -> Vec3 {
        let s = self.sun();
        let east = if right_handed {
            self.north.cross(self.zenith)
        } else {
            self.zenith.cross(self.north)
        };
        let (alt, az) = (
            (s.altitude_deg as f32).to_radians(),
            (s.azimuth_deg as f32).to_radians(),
        );
        let horizontal = self.north * az.cos() + east * az.sin();
        (horizontal * alt.cos() + self.zenith * alt.sin()).normalize()
    }

    /// The sun's disc when it is on and above the horizon: its unit scene direction and its
    /// illuminance on a plane facing it (lx).
    pub fn sun_disc(&self, right_handed: bool) -> Option<(Vec3, f64)> {
        let e = self.sun_normal_illuminance_lx?;
        (self.sun().altitude_deg > 0.0 && e > 0.0).then(|| (self.sun_direction(right_handed), e))
    }

    /// The sun's illuminance on the unobstructed horizontal plane (lx).
    pub fn sun_horizontal_illuminance(&self) -> f64 {
        self.sun_disc(true)
            .map_or(0.0, |(_, e)| e * self.sun().altitude_deg.to_radians().sin())
    }

    /// The sky with its ground (lit by the sky and the sun) as the environment light, None
    /// without a sky.
    pub fn sky_environment(&self, right_handed: bool) -> Option<crate::light::Environment> {
        let sky = self.sky.as_ref()?;
        Some(sky.environment(
            self.sun_direction(right_handed),
            self.sun_horizontal_illuminance(),
            if right_handed { 1.0 } else { -1.0 },
        ))
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    fn spec(extra: &str) -> Result<Daylight, String> {
        let text = format!(
            "latitude = 36.0\nlongitude = -140.0\nlongitude_convention = \"west\"\n\
             date = \"2026-06-21\"\ntime = \"12:00\"\ntimezone = 9.0\n{extra}"
        );
        let spec: DaylightSpec = toml::from_str(&text).map_err(|e| e.to_string())?;
        spec.to_model()
    }

    /// The Integra room's `Geography TokyoMidday`: west-positive -140 is 140° E. 12:00 JST is
    /// 18 minutes after solar noon there (the zone's meridian is 135° E, 20 minutes, and the
    /// equation of time is −1.7 minutes), so the sun is just past the south (hour angle 4.5°,
    /// which turns the azimuth fast so near the zenith), a little below its noon altitude
    /// 90 − 36 + 23.44 = 77.4°.
    #[test]
    fn tokyo_midday() {
        let d = spec("").unwrap();
        assert_eq!(d.place_time.longitude_deg, 140.0);
        let s = d.sun();
        assert!(s.altitude_deg > 76.5 && s.altitude_deg < 77.4, "{s:?}");
        assert!(s.azimuth_deg > 185.0 && s.azimuth_deg < 210.0, "{s:?}");
        // North −Z, up +Y, right-handed: south is +Z, so the sun is towards +Z and up.
        let w = d.sun_direction(true);
        assert!(w.y > 0.97 && w.z > 0.2, "{w}");
    }

    /// The morning sun is in the east: +X in a right-handed frame with north −Z, −X in a
    /// left-handed one.
    #[test]
    fn east_follows_the_handedness() {
        let d = spec("").unwrap();
        let morning = Daylight {
            place_time: PlaceTime {
                time: ClockTime {
                    hour: 7,
                    minute: 0,
                    second: 0,
                },
                ..d.place_time
            },
            ..d.clone()
        };
        assert!(morning.sun_direction(true).x > 0.5);
        assert!(morning.sun_direction(false).x < -0.5);
    }

    #[test]
    fn sky_keys() {
        let d = spec("sky = \"cie-overcast\"\ndiffuse_horizontal_lx = 7000.0").unwrap();
        let sky = d.sky.unwrap();
        assert_eq!(sky.model, SkyModel::CieOvercast);
        // E_h = 7π/9 Lz.
        assert!(
            (sky.zenith_luminance_cd_m2 * 7.0 * std::f64::consts::PI / 9.0 - 7000.0).abs() < 1e-9
        );
        assert_eq!(sky.ground_reflectance, 0.2);
        let e = |extra: &str| spec(extra).unwrap_err();
        assert!(e("sky = \"perez\"").contains("needs direct_normal_lx"));
        assert!(
            e("sky = \"uniform\"\nzenith_luminance_cd_m2 = 1.0\ndirect_normal_lx = 5.0")
                .contains("Perez sky's")
        );
        let p = spec(
            "sky = \"perez\"\ndirect_normal_lx = 60000.0\ndiffuse_horizontal_lx = 15000.0\n\
                      sun = true",
        )
        .unwrap();
        let sky = p.sky.unwrap();
        assert!((sky.horizontal_illuminance() - 15000.0).abs() < 1e-6);
        assert_eq!(p.sun_normal_illuminance_lx, Some(60000.0));
        assert!(e("sky = \"cie:16\"").contains("cie:15"));
        assert!(e("sun = true").contains("needs sun_normal_illuminance_lx"));
        assert!(e("sun_normal_illuminance_lx = 5.0").contains("without sun = true"));
        let d = spec(
            "sky = \"cie:12\"\ndiffuse_horizontal_lx = 10000.0\nsun = true\n\
                      sun_normal_illuminance_lx = 80000.0",
        )
        .unwrap();
        let sky = d.sky.unwrap();
        assert_eq!(sky.model, SkyModel::CieGeneral(12));
        assert!((sky.horizontal_illuminance() - 10000.0).abs() < 1e-6);
        assert_eq!(d.sun_normal_illuminance_lx, Some(80000.0));
        assert!(e("sky = \"uniform\"").contains("needs zenith_luminance_cd_m2"));
        assert!(e("zenith_luminance_cd_m2 = 10.0").contains("without a sky"));
        assert!(
            e("sky = \"uniform\"\nzenith_luminance_cd_m2 = 1.0\ndiffuse_horizontal_lx = 2.0")
                .contains("not both")
        );
        assert!(
            e("sky = \"uniform\"\nzenith_luminance_cd_m2 = 1.0\nground_reflectance = 2.0")
                .contains("ground_reflectance")
        );
        assert!(
            e("sky = \"uniform\"\nzenith_luminance_cd_m2 = 1.0\nzenith = [0.0, 0.0, 1.0]\nnorth = [0.0, 1.0, 0.0]")
                .contains("zenith along +Y")
        );
    }

    #[test]
    fn bad_keys_are_named() {
        assert!(spec("").is_ok());
        let e = |extra: &str| spec(extra).unwrap_err();
        assert!(e("north = [0.0, 1.0, 0.0]").contains("north points along the zenith"));
        assert!(e("zenith = [0.0, 0.0, 0.0]").contains("zenith"));
        let bad_lat = "latitude = 95.0\nlongitude = 0.0\ndate = \"2026-01-01\"\n\
                       time = \"12:00\"\ntimezone = 0.0";
        let s: DaylightSpec = toml::from_str(bad_lat).unwrap();
        assert!(s.to_model().unwrap_err().contains("latitude = 95"));
        let bad_date = "latitude = 5.0\nlongitude = 0.0\ndate = \"2026-02-30\"\n\
                        time = \"12:00\"\ntimezone = 0.0";
        let s: DaylightSpec = toml::from_str(bad_date).unwrap();
        assert!(s.to_model().unwrap_err().contains("daylight: date"));
    }
}
