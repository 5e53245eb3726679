//! A material's per-render constants: Kd / π, the highlight's normalisation, glass, emission and
//! the metallic-roughness model, so the per-ray code does no conversions.

use super::{MetalRough, Pane};
use crate::scene::Material;
use glam::Vec3;

#[derive(Clone, Copy, Debug)]
pub struct PreparedMaterial {
    pub kd_over_pi: Vec3,
    pub ks: Vec3,
    pub glossiness: f32,
    /// (g + 8) / (8π), the normalisation of the Blinn-Phong lobe.
    pub highlight_norm: f32,
    /// Weight of the glass interface per channel, and the refractive index behind the front.
    pub kt: Vec3,
    pub ior: f32,
    /// Emitted luminance per channel, cd/m² (zero for surfaces that are not lights).
    pub emission: Vec3,
    /// Metallic-roughness instead of Kd, Ks and glossiness.
    pub pbr: Option<MetalRough>,
    /// A thin pane instead of every lobe.
    pub pane: Option<Pane>,
}

impl PreparedMaterial {
    /// The constants of `m` (already clamped to a physical material).
    pub fn new(m: &Material) -> Self {
        Self {
            kd_over_pi: m.kd() / std::f32::consts::PI,
            ks: m.ks(),
            glossiness: m.glossiness,
            highlight_norm: (m.glossiness + 8.0) / (8.0 * std::f32::consts::PI),
            kt: m.kt(),
            ior: m.ior,
            emission: m.emission(),
            pbr: m.pbr.map(|p| {
                MetalRough::new(Vec3::from(p.base_color), p.metallic, p.roughness, m.ior)
                    .with_transmission(p.transmission)
            }),
            // A clamped material's index is at least 1; a pane needs more.
            pane: m
                .pane
                .and_then(|g| Pane::new(m.ior.max(1.0001), g.transmittance).ok()),
        }
    }
}
