//! Path vertices of bidirectional transport and the densities between them.
//!
//! Densities are per unit area (scene units) at the vertex they lead to, as in Veach's thesis
//! (ch. 10): `pdf_fwd` is the density with which the subpath that owns the vertex reached it,
//! `pdf_rev` the density with which the other direction would have.

use super::Bidirectional;
use super::emit::{direction_pdf, emission_cosine, emitted};
use crate::lit_scene::TreeLight;
use crate::shading::Scatter;
use glam::Vec3;
use std::f32::consts::PI;

/// What a vertex is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// The first vertex of a camera or sensor subpath.
    Eye,
    /// The first vertex of a light subpath (or a light sampled for a connection).
    Light(TreeLight),
    /// The first vertex of a light subpath from the environment (the light tracer's), on the
    /// disc across the bounding sphere: never joined to anything.
    Environment,
    /// A surface point a subpath reached.
    Surface(u32),
}

#[derive(Clone, Copy, Debug)]
pub struct Vertex<S> {
    pub kind: Kind,
    pub p: Vec3,
    /// Unit geometric normal (surfaces, glowing triangles, the eye's axis); zero for point
    /// lights.
    pub n: Vec3,
    /// Unit shading normal on the side of `n` (the vertex normals interpolated; `n` when flat).
    pub ns: Vec3,
    /// Origin for rays leaving a surface vertex on the side of `n`: lifted off a smooth mesh
    /// against the shadow terminator (see `shading::Surface`).
    pub origin: Vec3,
    /// A vertex of a light subpath: its BSDF is the adjoint one (shading normals are not
    /// symmetric, Veach §5.3).
    pub adjoint: bool,
    /// Unit direction towards the previous vertex of the subpath (zero for the first).
    pub wo: Vec3,
    /// Throughput of the subpath up to here (camera: 1 at the eye; light: per its start).
    pub beta: Vec3,
    /// Squared distance to the previous vertex of the subpath (0 for the first).
    pub dist2_prev: f32,
    /// Light subpath vertex 1 only: p_tree(x0 | here) / p_flux(x0), how much likelier strategy
    /// s = 1 makes the light vertex when it joins it here (see `Bidirectional::tree_factor`).
    pub tree_ratio: f32,
    pub pdf_fwd: f32,
    pub pdf_rev: f32,
    /// A delta lobe scattered the subpath here (mirror, glass): no connection can use it.
    pub delta: bool,
    /// The scattering at a surface vertex (its non-delta part does not depend on the side).
    pub bsdf: Option<S>,
}

impl<S: Scatter> Vertex<S> {
    pub fn new(kind: Kind, p: Vec3, n: Vec3, beta: Vec3, pdf_fwd: f32) -> Self {
        Self {
            kind,
            p,
            n,
            ns: n,
            origin: p,
            adjoint: false,
            wo: Vec3::ZERO,
            beta,
            dist2_prev: 0.0,
            tree_ratio: 1.0,
            pdf_fwd,
            pdf_rev: 0.0,
            delta: false,
            bsdf: None,
        }
    }

    /// Whether a density arriving here is measured per area of a surface (with its cosine).
    fn on_surface(&self) -> bool {
        matches!(
            self.kind,
            Kind::Surface(_) | Kind::Light(TreeLight::Triangle(_))
        )
    }

    /// A density per sr towards this vertex, from a vertex at squared distance `dist2` along
    /// unit `w` (pointing here), as a density per unit area here.
    #[inline]
    pub fn density_from(&self, pdf_dir: f32, dist2: f32, w: Vec3) -> f32 {
        if dist2 <= 0.0 {
            return 0.0;
        }
        let pdf = pdf_dir / dist2;
        if self.on_surface() {
            pdf * self.n.dot(w).abs()
        } else {
            pdf
        }
    }

    /// Whether paths may be connected here (a light, the eye, or a surface with a non-delta
    /// lobe).
    pub fn connectible(&self) -> bool {
        match self.kind {
            Kind::Surface(_) => self.bsdf.is_some_and(|b| b.has_smooth_lobe()),
            Kind::Environment => false,
            _ => true,
        }
    }

    /// The unit normal of a surface vertex turned towards `w`.
    pub fn facing(&self, w: Vec3) -> Vec3 {
        if self.n.dot(w) >= 0.0 {
            self.n
        } else {
            -self.n
        }
    }

    /// The shading normal turned towards `w` (by the geometric side `w` is on).
    pub fn shading_facing(&self, w: Vec3) -> Vec3 {
        if self.n.dot(w) >= 0.0 {
            self.ns
        } else {
            -self.ns
        }
    }

    /// The scattering (or emission) factor at this vertex from `wo` towards unit `w`, without
    /// the cosine: the BSDF at surfaces, the emitted intensity or luminance at lights, the
    /// importance at the eye.
    ///
    /// With a shading normal the BSDF is Veach's `f(ωl → ωc) · |ns·ωl| / |ng·ωl|` for the
    /// direction ωl towards the light, so that geometric cosines in the geometry term give the
    /// shading cosine: ωl is `w` on a camera subpath and `wo` on a light subpath.
    #[inline(always)]
    pub fn f(&self, bd: &Bidirectional<'_, '_>, w: Vec3) -> Vec3 {
        match self.kind {
            Kind::Surface(_) => match &self.bsdf {
                Some(bsdf) => {
                    let f = bsdf.eval(self.shading_facing(self.wo), self.wo, w);
                    if self.ns == self.n || self.ns == -self.n {
                        return f;
                    }
                    let wl = if self.adjoint { self.wo } else { w };
                    f * shading_correction(self.ns, self.n, wl)
                }
                None => Vec3::ZERO,
            },
            Kind::Light(light) => emitted(bd.lit, light, self.p, w),
            Kind::Environment => Vec3::ZERO,
            Kind::Eye => Vec3::splat(bd.eye_importance(self, w)),
        }
    }

    /// The cosine at this vertex towards unit `w` that a connection's geometry term carries.
    #[inline]
    pub fn cosine(&self, bd: &Bidirectional<'_, '_>, w: Vec3) -> f32 {
        match self.kind {
            Kind::Surface(_) => self.n.dot(w).abs(),
            Kind::Light(light) => emission_cosine(bd.lit, light, self.n, w),
            Kind::Environment => 1.0,
            Kind::Eye => bd.eye_cosine(self.n, w),
        }
    }

    /// Density per sr with which this vertex's subpath would leave along unit `to`, having
    /// arrived from unit `from` (pointing back at the previous vertex; lights and the eye ignore
    /// it). Connections know both directions, so nothing is normalised here.
    #[inline(always)]
    pub fn pdf_dir(&self, bd: &Bidirectional<'_, '_>, from: Vec3, to: Vec3) -> f32 {
        match self.kind {
            Kind::Surface(_) => match &self.bsdf {
                Some(bsdf) => bsdf.pdf(self.shading_facing(from), from, to),
                None => 0.0,
            },
            Kind::Light(light) => direction_pdf(bd.lit, light, to),
            Kind::Environment => 0.0,
            Kind::Eye => bd.eye_direction_pdf(self, to),
        }
    }

    /// Density per unit area with which a light subpath starts at this vertex (a glowing
    /// surface point hit by the camera path, or a light vertex).
    pub fn pdf_light_origin(&self, bd: &Bidirectional<'_, '_>) -> f32 {
        match self.kind {
            Kind::Light(light) => bd.lights.pdf_origin(bd.lit, light),
            Kind::Surface(prim) => bd.lights.pdf_origin(bd.lit, TreeLight::Triangle(prim)),
            Kind::Eye | Kind::Environment => 0.0,
        }
    }

    /// Density per unit area at `prev` (this vertex's predecessor, along `wo`) of a light
    /// subpath leaving this glowing point for it.
    pub fn pdf_light_back(&self, bd: &Bidirectional<'_, '_>, prev: &Vertex<S>) -> f32 {
        let light = match self.kind {
            Kind::Light(light) => light,
            Kind::Surface(prim) => TreeLight::Triangle(prim),
            Kind::Eye | Kind::Environment => return 0.0,
        };
        prev.density_from(
            direction_pdf(bd.lit, light, self.wo),
            self.dist2_prev,
            self.wo,
        )
    }

    /// Whether this is a light with a delta position (point, spot, luminaire).
    pub fn is_delta_light(&self) -> bool {
        matches!(self.kind, Kind::Light(TreeLight::Placed(_)))
    }

    /// Luminance this surface vertex emits towards the previous vertex (0 for non-emitters).
    pub fn emission(&self, bd: &Bidirectional<'_, '_>) -> Vec3 {
        match self.kind {
            Kind::Surface(prim) => bd.lit.glow(prim, self.p, self.wo),
            _ => Vec3::ZERO,
        }
    }
}

/// `|ns·w| / |ng·w|`, 0 where `w` lies in the geometric plane.
pub fn shading_correction(ns: Vec3, ng: Vec3, w: Vec3) -> f32 {
    let g = ng.dot(w).abs();
    if g > 1e-6 { ns.dot(w).abs() / g } else { 0.0 }
}

/// Cosine-weighted hemisphere density per sr (the sensor's direction sampling).
pub fn cosine_pdf(n: Vec3, w: Vec3) -> f32 {
    n.dot(w).max(0.0) / PI
}
