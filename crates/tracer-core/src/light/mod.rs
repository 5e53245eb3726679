//! Lights behind one interface, [`LightSource`], with a type per kind and the data of that kind
//! (pbrt-v4's `Light` is the model): isotropic points ([`PointLight`]), spots ([`SpotLight`]),
//! goniometric luminaires ([`GoniometricLight`]) and glowing triangles ([`TriangleLight`], views
//! into an [`EmitterTable`]). Placed lights are one enum, [`PlacedLight`]; a [`LightHandle`]
//! names any light of a render. Every integrator reaches lights through the trait, and the light
//! tree ([`LightTree`]) picks one for a receiving point.
//!
//! The user's model of a placed light is [`Light`] (`model.rs`), which a render turns into a
//! [`PlacedLight`] for the scene's unit and handedness.
//!
//! Photometric SI: intensity in candela, flux in lumen, luminance in cd/m². A light's colour is a
//! tint normalised to Rec. 709 luminance 1, so its intensity stays in candela.

pub mod daylight;
mod emitters;
mod environment;
mod goniometric;
mod handle;
mod luminaire;
mod luminous_shape;
mod model;
mod placed;
mod point;
mod spot;
mod tree;
mod triangle;

pub use emitters::{EmissionSides, EmissiveTriangle, EmitterSample, EmitterTable};
pub use environment::{
    DistantSun, Environment, EnvironmentLight, EnvironmentMap, EnvironmentSource, SunDisc,
    map_direction,
};
pub use goniometric::{LuminaireInfo, Photometry, PhotometryError, Plane, cosine_flux};
pub use handle::LightHandle;
pub use luminaire::{GoniometricLight, Luminaire, LuminaireFrame};
pub use luminous_shape::{LuminousShape, SHAPE_NAMES};
pub use model::{KindTag, Light, LightKind, LightSummary, LuminairePlacement, ShapeChoice, Spot};
pub use placed::PlacedLight;
pub use point::PointLight;
pub use spot::{SpotLight, SpotProfile};
pub use tree::{LightBounds, LightTree, Picked};
pub use triangle::TriangleLight;

use glam::Vec3;

/// What every kind of light can do.
///
/// Units: a point-like light's values are intensities, an area light's are luminances. For a
/// receiving point ([`LightSource::sample_incident`]) a point-like light gives its intensity and
/// the squared distance in m² as its "density", so that `value · cos θ / pdf` is the
/// illuminance for every kind. Along a light subpath ([`LightSource::emitted`]) a point-like
/// light gives its intensity per squared scene unit (I / (m per unit)²), so that a geometry
/// term in scene units turns it into lx or cd/m² as it does a luminance.
pub trait LightSource {
    /// Luminous flux (lm) it emits, for the light tree and the light-subpath starts.
    fn power_lm(&self) -> f64;

    /// Its bounds for the light tree.
    fn bounds(&self) -> LightBounds;

    /// Whether its position is a point (no direction sampled at a surface can find it).
    fn is_delta(&self) -> bool;

    /// Light arriving at `at` from a point of the light chosen with `u` (point-like lights use
    /// no numbers: see [`LightSource::is_delta`]). None when the sample carries nothing.
    fn sample_incident(&self, at: Receiver, u: [f32; 2]) -> Option<Incident>;

    /// Density (1/sr) with which [`LightSource::sample_incident`] from `origin` reaches the
    /// light along unit `wi` at `distance` (scene units); 0 for point-like lights.
    fn incident_pdf(&self, origin: Vec3, wi: Vec3, distance: f32) -> f32;

    /// What leaves the light along unit `dir` from a point on it, per channel (see the trait's
    /// units): the luminance a ray that hit a glowing surface sees, the value a light vertex
    /// sends.
    fn emitted(&self, dir: Vec3) -> Vec3;

    /// The start of a light subpath: a point on the light from `u_point`, a direction from
    /// `u_dir`, with their densities.
    fn sample_emission(&self, u_point: [f32; 2], u_dir: [f32; 2]) -> Option<Emission>;

    /// Density (1/sr) of [`LightSource::sample_emission`] leaving along unit `dir`.
    fn emission_dir_pdf(&self, dir: Vec3) -> f32;

    /// Density per unit area (scene units) of the point [`LightSource::sample_emission`] picks
    /// (1 for a point-like light).
    fn emission_point_pdf(&self) -> f32;

    /// Unit front normal of an area light (zero for a point-like one).
    fn normal(&self) -> Vec3;

    /// The cosine a light vertex at a point with unit normal `n` (its [`Emission::n`] or
    /// [`Incident::n`]) carries along unit `dir`: |n · dir| on an area light, 1 for a
    /// point-like one. A luminaire with a luminous body weighs the face `n` instead.
    fn emission_cosine(&self, n: Vec3, dir: Vec3) -> f32 {
        if n == Vec3::ZERO {
            1.0
        } else {
            n.dot(dir).abs()
        }
    }

    /// The share of its emitting area that [`LightSource::sample_incident`] draws points from
    /// for a receiver at `p`, relative to [`LightSource::sample_emission`]'s: a luminous body
    /// samples only the faces that face `p`. 1 for every other light. Bidirectional methods
    /// divide their light-vertex densities by it.
    fn area_share(&self, _p: Vec3) -> f32 {
        1.0
    }

    /// Whether [`LightSource::sample_incident`] and [`LightSource::sample_emission`] use their
    /// numbers for the point: area lights, and luminaires with a luminous opening (which
    /// are still [`LightSource::is_delta`]: no ray finds them).
    fn samples_area(&self) -> bool {
        !self.is_delta()
    }
}

/// A point that receives light: placed lights see it from `p`, area lights from `origin` (the
/// ray origin lifted off the surface, where shadow rays leave).
#[derive(Clone, Copy, Debug)]
pub struct Receiver {
    pub p: Vec3,
    pub origin: Vec3,
}

/// Light arriving at a receiving point from one sample of one light.
#[derive(Clone, Copy, Debug)]
pub struct Incident {
    /// Unit direction from the receiving point towards the light.
    pub wi: Vec3,
    /// The point on the light: shadow rays end there.
    pub target: Vec3,
    /// Tint per channel: a placed light's colour of luminance 1, or a glowing triangle's
    /// luminance (cd/m²) with `level` 1.
    pub tint: Vec3,
    /// A placed light's intensity towards the point (cd); 1 for a glowing triangle.
    pub level: f32,
    /// Solid-angle density (1/sr) of the sample on an area light; for a point-like light the
    /// squared distance in m² (E = I cos θ / R²). Times the probability of the pick, when a
    /// sampler picked the light.
    pub pdf: f32,
    /// A point-like light: no direction sampled at a surface can find it (no MIS).
    pub delta: bool,
    /// Unit normal at `target` where the emission depends on it: a glowing triangle's front,
    /// a luminous body's face; zero for points and flat openings.
    pub n: Vec3,
}

impl Incident {
    /// The value per channel: tint × level (cd or cd/m²).
    #[inline]
    pub fn value(&self) -> Vec3 {
        self.tint * self.level
    }
}

/// The start of a light subpath.
#[derive(Clone, Copy, Debug)]
pub struct Emission {
    pub p: Vec3,
    /// Unit front normal of an area light (zero for a point-like one).
    pub n: Vec3,
    /// Unit direction it leaves in.
    pub dir: Vec3,
    /// Density per unit area of `p` (1 for a point-like light).
    pub pdf_point: f32,
    /// Density per sr of `dir`.
    pub pdf_dir: f32,
}

/// Rec. 709 / sRGB luminance weights of linear RGB.
pub const LUMINANCE_WEIGHTS: Vec3 = Vec3::new(0.2126, 0.7152, 0.0722);

/// Rec. 709 luminance Y of a linear RGB triple.
pub fn luminance(rgb: Vec3) -> f32 {
    rgb.dot(LUMINANCE_WEIGHTS)
}

/// `rgb` scaled to luminance 1 (white when it is black or invalid).
pub fn unit_luminance_tint(rgb: [f32; 3]) -> Vec3 {
    let c = Vec3::from(rgb).max(Vec3::ZERO);
    let y = luminance(c);
    if y.is_finite() && y > 0.0 {
        c / y
    } else {
        Vec3::ONE
    }
}
