//! Any light of a render, by reference: a placed light or a glowing triangle. Integrators hold
//! lights as [`LightHandle`]s and ask them through [`LightSource`].

use super::{Emission, Incident, LightBounds, LightSource, PlacedLight, Receiver, TriangleLight};
use glam::Vec3;

#[derive(Clone, Copy, Debug)]
pub enum LightHandle<'a> {
    Placed(&'a PlacedLight),
    Triangle(TriangleLight<'a>),
}

impl LightSource for LightHandle<'_> {
    fn power_lm(&self) -> f64 {
        match self {
            LightHandle::Placed(l) => l.power_lm(),
            LightHandle::Triangle(l) => l.power_lm(),
        }
    }

    fn bounds(&self) -> LightBounds {
        match self {
            LightHandle::Placed(l) => l.bounds(),
            LightHandle::Triangle(l) => l.bounds(),
        }
    }

    #[inline]
    fn is_delta(&self) -> bool {
        matches!(self, LightHandle::Placed(_))
    }

    #[inline]
    fn samples_area(&self) -> bool {
        match self {
            LightHandle::Placed(l) => l.samples_area(),
            LightHandle::Triangle(_) => true,
        }
    }

    #[inline]
    fn area_share(&self, p: Vec3) -> f32 {
        match self {
            LightHandle::Placed(l) => l.area_share(p),
            LightHandle::Triangle(_) => 1.0,
        }
    }

    #[inline]
    fn emission_cosine(&self, n: Vec3, dir: Vec3) -> f32 {
        match self {
            LightHandle::Placed(l) => l.emission_cosine(n, dir),
            LightHandle::Triangle(l) => l.emission_cosine(n, dir),
        }
    }

    #[inline(always)]
    fn sample_incident(&self, at: Receiver, u: [f32; 2]) -> Option<Incident> {
        match self {
            LightHandle::Placed(l) => l.sample_incident(at, u),
            LightHandle::Triangle(l) => l.sample_incident(at, u),
        }
    }

    #[inline]
    fn incident_pdf(&self, origin: Vec3, wi: Vec3, distance: f32) -> f32 {
        match self {
            LightHandle::Placed(l) => l.incident_pdf(origin, wi, distance),
            LightHandle::Triangle(l) => l.incident_pdf(origin, wi, distance),
        }
    }

    #[inline]
    fn emitted(&self, dir: Vec3) -> Vec3 {
        match self {
            LightHandle::Placed(l) => l.emitted(dir),
            LightHandle::Triangle(l) => l.emitted(dir),
        }
    }

    fn sample_emission(&self, u_point: [f32; 2], u_dir: [f32; 2]) -> Option<Emission> {
        match self {
            LightHandle::Placed(l) => l.sample_emission(u_point, u_dir),
            LightHandle::Triangle(l) => l.sample_emission(u_point, u_dir),
        }
    }

    #[inline]
    fn emission_dir_pdf(&self, dir: Vec3) -> f32 {
        match self {
            LightHandle::Placed(l) => l.emission_dir_pdf(dir),
            LightHandle::Triangle(l) => l.emission_dir_pdf(dir),
        }
    }

    #[inline]
    fn emission_point_pdf(&self) -> f32 {
        match self {
            LightHandle::Placed(l) => l.emission_point_pdf(),
            LightHandle::Triangle(l) => l.emission_point_pdf(),
        }
    }

    #[inline]
    fn normal(&self) -> Vec3 {
        match self {
            LightHandle::Placed(l) => l.normal(),
            LightHandle::Triangle(l) => l.normal(),
        }
    }
}
