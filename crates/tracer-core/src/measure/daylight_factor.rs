//! The daylight factor: DF = 100 % · E_in / E_out,h, both under the CIE overcast sky without
//! sun, E_out,h the unobstructed horizontal illuminance, 7π/9 · Lz, computed rather than
//! rendered. Whatever the setup's sky, sun and lights, a DF is measured in a setup of its own:
//! the overcast sky over the setup's ground (reflectance from its `[daylight]` sky, else 0.2),
//! no sun, no lights and no glowing surfaces.

use crate::light::daylight::{Sky, SkyModel};
use crate::scene::{Handedness, Setup};
use glam::Vec3;
use std::f64::consts::PI;

/// The overcast sky's unobstructed horizontal illuminance in a DF setup, lx. DF does not depend
/// on it; the readings in lx do.
pub const DF_OUTDOOR_LX: f64 = 10_000.0;

/// A setup that measures daylight factors, with the outdoor illuminance its readings divide
/// by.
#[derive(Debug)]
pub struct DaylightFactorSetup {
    pub setup: Setup,
    /// E_out,h (lx).
    pub outdoor_lx: f64,
}

impl DaylightFactorSetup {
    /// The DF setup of `setup`, or why there is none (a zenith other than +Y).
    pub fn new(setup: &Setup) -> Result<Self, String> {
        let mut s = setup.clone();
        let ground_reflectance = match &setup.daylight {
            Some(d) => {
                if d.zenith.dot(Vec3::Y) < 0.9999 {
                    return Err(
                        "daylight factor: the sky needs the zenith along +Y (the scene's up)"
                            .into(),
                    );
                }
                d.sky.map_or(0.2, |sky| sky.ground_reflectance)
            }
            None => 0.2,
        };
        let sky = Sky::new(
            SkyModel::CieOvercast,
            DF_OUTDOOR_LX / (7.0 * PI / 9.0),
            ground_reflectance,
            0.0,
            None,
        );
        let sign = match setup.handedness {
            Handedness::Right => 1.0,
            Handedness::Left => -1.0,
        };
        s.environment = Some(sky.environment(Vec3::Y, 0.0, sign));
        if let Some(d) = &mut s.daylight {
            d.sun_normal_illuminance_lx = None;
            d.sky = Some(sky);
        }
        s.lights.clear();
        for m in &mut s.materials {
            m.emission_cd_m2 = 0.0;
        }
        Ok(DaylightFactorSetup {
            setup: s,
            outdoor_lx: sky.horizontal_illuminance(),
        })
    }

    /// DF in % of an illuminance (lx) measured in this setup.
    pub fn percent(&self, illuminance_lx: f64) -> f64 {
        100.0 * illuminance_lx / self.outdoor_lx
    }
}
