//! The sun's position for a place and a local time: NOAA's solar calculator, after Meeus'
//! *Astronomical Algorithms* (the low-precision solar coordinates, good to about 0.01° for
//! 1800-2100). Angles in degrees.
//!
//! The altitude includes atmospheric refraction for a standard atmosphere (1010 hPa, 10 °C), as
//! NOAA's calculator gives it: the apparent position, the direction light arrives from.

/// A calendar date (proleptic Gregorian).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Date {
    pub year: i32,
    pub month: u32,
    pub day: u32,
}

/// A clock time of day.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ClockTime {
    pub hour: u32,
    pub minute: u32,
    pub second: u32,
}

impl Date {
    /// `YYYY-MM-DD`, or why not.
    pub fn parse(text: &str) -> Result<Date, String> {
        let bad = || format!("`{text}` is not a date YYYY-MM-DD");
        let mut parts = text.trim().split('-');
        let (Some(y), Some(m), Some(d), None) =
            (parts.next(), parts.next(), parts.next(), parts.next())
        else {
            return Err(bad());
        };
        let year: i32 = y.parse().map_err(|_| bad())?;
        let month: u32 = m.parse().map_err(|_| bad())?;
        let day: u32 = d.parse().map_err(|_| bad())?;
        let leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
        let days = match month {
            1 | 3 | 5 | 7 | 8 | 10 | 12 => 31,
            4 | 6 | 9 | 11 => 30,
            2 if leap => 29,
            2 => 28,
            _ => return Err(format!("`{text}`: month {month} is not 1-12")),
        };
        if y.len() != 4 {
            return Err(bad());
        }
        if !(1..=days).contains(&day) {
            return Err(format!(
                "`{text}`: {year:04}-{month:02} has days 1 to {days}, not {day}"
            ));
        }
        Ok(Date { year, month, day })
    }
}

impl Date {
    /// The day of the year, 1 on 1 January.
    pub fn day_of_year(&self) -> u32 {
        let leap = (self.year % 4 == 0 && self.year % 100 != 0) || self.year % 400 == 0;
        let before: u32 = [
            31,
            if leap { 29 } else { 28 },
            31,
            30,
            31,
            30,
            31,
            31,
            30,
            31,
            30,
        ]
        .iter()
        .take(self.month.saturating_sub(1) as usize)
        .sum();
        before + self.day
    }
}

impl std::fmt::Display for Date {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{:04}-{:02}-{:02}", self.year, self.month, self.day)
    }
}

impl ClockTime {
    /// `HH:MM` or `HH:MM:SS` (24-hour clock), or why not.
    pub fn parse(text: &str) -> Result<ClockTime, String> {
        let bad = || format!("`{text}` is not a time HH:MM or HH:MM:SS (24-hour clock)");
        let parts: Vec<&str> = text.trim().split(':').collect();
        if !(2..=3).contains(&parts.len()) {
            return Err(bad());
        }
        let n = |i: usize, max: u32| -> Result<u32, String> {
            match parts.get(i) {
                None => Ok(0),
                Some(p) => p.parse::<u32>().ok().filter(|v| *v <= max).ok_or_else(bad),
            }
        };
        Ok(ClockTime {
            hour: n(0, 23)?,
            minute: n(1, 59)?,
            second: n(2, 59)?,
        })
    }

    fn hours(&self) -> f64 {
        f64::from(self.hour) + f64::from(self.minute) / 60.0 + f64::from(self.second) / 3600.0
    }
}

impl std::fmt::Display for ClockTime {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{:02}:{:02}", self.hour, self.minute)?;
        if self.second > 0 {
            write!(f, ":{:02}", self.second)?;
        }
        Ok(())
    }
}

/// A place on Earth and a local clock time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlaceTime {
    /// Degrees north (south negative).
    pub latitude_deg: f64,
    /// Degrees east (west negative).
    pub longitude_deg: f64,
    pub date: Date,
    /// Local clock time.
    pub time: ClockTime,
    /// Standard time zone, hours east of UTC (Tokyo 9, Denver −7).
    pub timezone_h: f64,
    /// Whether the clock is on daylight-saving time (one hour ahead of the zone).
    pub daylight_saving: bool,
}

/// Where the sun is seen from the place.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SunPosition {
    /// Apparent altitude above the horizon (refraction included), degrees.
    pub altitude_deg: f64,
    /// Azimuth from north towards east, degrees in [0, 360).
    pub azimuth_deg: f64,
    /// Altitude without refraction, degrees.
    pub true_altitude_deg: f64,
}

impl SunPosition {
    /// The apparent zenith angle, degrees.
    pub fn zenith_deg(&self) -> f64 {
        90.0 - self.altitude_deg
    }
}

/// Julian day at 0h UT of a Gregorian calendar date (Meeus ch. 7).
fn julian_day(date: Date) -> f64 {
    let (mut y, mut m) = (f64::from(date.year), f64::from(date.month));
    if m <= 2.0 {
        y -= 1.0;
        m += 12.0;
    }
    let a = (y / 100.0).floor();
    let b = 2.0 - a + (a / 4.0).floor();
    (365.25 * (y + 4716.0)).floor() + (30.6001 * (m + 1.0)).floor() + f64::from(date.day) + b
        - 1524.5
}

/// Refraction correction (degrees) for a true altitude `e` (degrees), standard atmosphere.
fn refraction_deg(e: f64) -> f64 {
    let arcsec = if e > 85.0 {
        0.0
    } else if e > 5.0 {
        let t = e.to_radians().tan();
        58.1 / t - 0.07 / t.powi(3) + 0.000086 / t.powi(5)
    } else if e > -0.575 {
        1735.0 + e * (-518.2 + e * (103.4 + e * (-12.79 + e * 0.711)))
    } else {
        -20.772 / e.to_radians().tan()
    };
    arcsec / 3600.0
}

/// The sun's apparent position at `at`.
pub fn sun_position(at: &PlaceTime) -> SunPosition {
    let local_h = at.time.hours();
    let zone_h = at.timezone_h + if at.daylight_saving { 1.0 } else { 0.0 };
    let jd = julian_day(at.date) + (local_h - zone_h) / 24.0;
    let t = (jd - 2_451_545.0) / 36_525.0;
    // The sun's mean longitude and anomaly, the orbit's eccentricity (degrees).
    let l0 = (280.46646 + t * (36000.76983 + t * 0.0003032)).rem_euclid(360.0);
    let m = 357.52911 + t * (35999.05029 - 0.0001537 * t);
    let e = 0.016708634 - t * (0.000042037 + 0.0000001267 * t);
    let mr = m.to_radians();
    let centre = mr.sin() * (1.914602 - t * (0.004817 + 0.000014 * t))
        + (2.0 * mr).sin() * (0.019993 - 0.000101 * t)
        + (3.0 * mr).sin() * 0.000289;
    let omega = (125.04 - 1934.136 * t).to_radians();
    let apparent_longitude = (l0 + centre - 0.00569 - 0.00478 * omega.sin()).to_radians();
    let mean_obliquity =
        23.0 + (26.0 + (21.448 - t * (46.815 + t * (0.00059 - t * 0.001813))) / 60.0) / 60.0;
    let obliquity = (mean_obliquity + 0.00256 * omega.cos()).to_radians();
    let declination = (obliquity.sin() * apparent_longitude.sin()).asin();
    // The equation of time, minutes.
    let y = (obliquity / 2.0).tan().powi(2);
    let l0r = l0.to_radians();
    let equation_of_time = 4.0
        * (y * (2.0 * l0r).sin() - 2.0 * e * mr.sin() + 4.0 * e * y * mr.sin() * (2.0 * l0r).cos()
            - 0.5 * y * y * (4.0 * l0r).sin()
            - 1.25 * e * e * (2.0 * mr).sin())
        .to_degrees();
    let true_solar_min = (local_h * 60.0 + equation_of_time + 4.0 * at.longitude_deg
        - 60.0 * zone_h)
        .rem_euclid(1440.0);
    let hour_angle = (true_solar_min / 4.0 - 180.0).to_radians();
    let lat = at.latitude_deg.to_radians();
    let cos_zenith = (lat.sin() * declination.sin()
        + lat.cos() * declination.cos() * hour_angle.cos())
    .clamp(-1.0, 1.0);
    let zenith = cos_zenith.acos();
    // Azimuth from north through east: atan2 of the east and north components of the sun.
    let east = -declination.cos() * hour_angle.sin();
    let north = declination.sin() * lat.cos() - declination.cos() * lat.sin() * hour_angle.cos();
    let azimuth_deg = east.atan2(north).to_degrees().rem_euclid(360.0);
    let true_altitude_deg = 90.0 - zenith.to_degrees();
    SunPosition {
        altitude_deg: true_altitude_deg + refraction_deg(true_altitude_deg),
        azimuth_deg,
        true_altitude_deg,
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    fn at(lat: f64, lon: f64, date: (i32, u32, u32), time: (u32, u32, u32), tz: f64) -> PlaceTime {
        PlaceTime {
            latitude_deg: lat,
            longitude_deg: lon,
            date: Date {
                year: date.0,
                month: date.1,
                day: date.2,
            },
            time: ClockTime {
                hour: time.0,
                minute: time.1,
                second: time.2,
            },
            timezone_h: tz,
            daylight_saving: false,
        }
    }

    /// NREL SPA's published example (Reda & Andreas 2004, table A5.1): 17 October 2003,
    /// 12:30:30 local, UTC−7, 39.742476° N, 105.1786° W: topocentric zenith 50.11162°, azimuth
    /// 194.34024°. SPA refracts for 820 hPa and 11 °C (0.0155° at this altitude) where NOAA's
    /// standard atmosphere gives 0.0192°, and adds parallax (0.002°): within 0.01° all the same.
    #[test]
    fn spa_example() {
        let s = sun_position(&at(
            39.742476,
            -105.1786,
            (2003, 10, 17),
            (12, 30, 30),
            -7.0,
        ));
        println!(
            "zenith {:.5}°, azimuth {:.5}°",
            s.zenith_deg(),
            s.azimuth_deg
        );
        assert!(
            (s.zenith_deg() - 50.11162).abs() < 0.01,
            "zenith {}",
            s.zenith_deg()
        );
        assert!(
            (s.azimuth_deg - 194.34024).abs() < 0.01,
            "azimuth {}",
            s.azimuth_deg
        );
    }

    /// Against pvlib 0.13's NREL SPA (`get_solarposition`, method `nrel_numpy`): the true
    /// (unrefracted) altitude and the azimuth within 0.01° at five places and seasons, from the
    /// polar summer's low midnight sun to the tropics. (pvlib's altitude is topocentric: up to
    /// 0.0024° of parallax below the geocentric one computed here.)
    #[test]
    fn against_pvlib_spa() {
        // (latitude, longitude, date, time, zone, pvlib's elevation and azimuth)
        type Case = (f64, f64, (i32, u32, u32), (u32, u32, u32), f64, f64, f64);
        #[rustfmt::skip]
        let cases: [Case; 5] = [
            (35.6895, 139.6917, (2026, 6, 21), (12, 0, 0), 9.0, 77.20433, 197.91374),
            (51.5074, -0.1278, (2026, 12, 21), (12, 0, 0), 0.0, 15.05263, 180.33832),
            (-33.8688, 151.2093, (2026, 3, 20), (9, 30, 0), 10.0, 40.92202, 54.90797),
            (64.1466, -21.9426, (2026, 6, 21), (23, 0, 0), 0.0, 2.30031, 326.08263),
            (1.35, 103.82, (2026, 9, 23), (15, 0, 0), 8.0, 59.25800, 267.50951),
        ];
        for (lat, lon, date, time, tz, elevation, azimuth) in cases {
            let s = sun_position(&at(lat, lon, date, time, tz));
            println!(
                "{lat} {lon} {date:?} {time:?}: altitude {:.5} vs {elevation}, azimuth {:.5} vs \
                 {azimuth}",
                s.true_altitude_deg, s.azimuth_deg
            );
            assert!((s.true_altitude_deg - elevation).abs() < 0.01, "{s:?}");
            assert!((s.azimuth_deg - azimuth).abs() < 0.01, "{s:?}");
        }
    }

    /// Julian days from Meeus' examples 7.a and 7.b.
    #[test]
    fn julian_days() {
        let jd = |year, month, day| julian_day(Date { year, month, day });
        assert_eq!(jd(1957, 10, 4), 2_436_115.5);
        assert_eq!(jd(2000, 1, 1), 2_451_544.5);
        assert_eq!(jd(1988, 1, 27), 2_447_187.5);
    }

    #[test]
    fn dates_and_times_parse_or_say_why_not() {
        assert_eq!(
            Date::parse("2024-02-29").unwrap(),
            Date {
                year: 2024,
                month: 2,
                day: 29
            }
        );
        assert!(Date::parse("2023-02-29").is_err());
        assert!(Date::parse("2023-13-01").unwrap_err().contains("month 13"));
        assert!(Date::parse("21 June").is_err());
        assert_eq!(ClockTime::parse("12:30").unwrap().to_string(), "12:30");
        assert_eq!(ClockTime::parse("12:30:30").unwrap().second, 30);
        assert!(ClockTime::parse("24:00").is_err());
        assert!(ClockTime::parse("noon").is_err());
    }

    /// Solar noon at the equinox on the equator, at the zone's own meridian: the sun stands
    /// within the equation of time's few minutes (about 1.9° of hour angle) of the zenith; at
    /// the June solstice at noon, 36° N sees it at 90 − 36 + 23.44 = 77.4°.
    #[test]
    fn noon_altitudes_follow_the_declination() {
        let s = sun_position(&at(0.0, 0.0, (2024, 3, 20), (12, 7, 0), 0.0));
        assert!(s.true_altitude_deg > 89.5, "{s:?}");
        let s = sun_position(&at(36.0, 135.0, (2024, 6, 20), (12, 0, 0), 9.0));
        assert!((s.true_altitude_deg - 77.4).abs() < 0.5, "{s:?}");
        assert!(s.azimuth_deg > 170.0 && s.azimuth_deg < 190.0, "{s:?}");
    }
}
