//! Glare sources, found two ways: analytically, the luminaires with a luminous opening (their
//! luminance towards the eye and projected solid angle), and from the fisheye luminance image
//! as evalglare finds them (pixels above a threshold, grouped by direction).

use super::image::GlareImage;
use super::openings::{luminaires_with_openings, opening_luminance};
use super::position_index::{IndexRule, position_index};
use crate::lit_scene::LitScene;
use crate::sampling::SampleRng;
use glam::{DVec3, Vec3};

/// CIE 117's UGR holds for sources of 0.0003 to 0.1 sr (CIE 147:2002 for the others).
pub const CIE117_MIN_SR: f64 = 3e-4;
pub const CIE117_MAX_SR: f64 = 0.1;

/// One glare source as the eye sees it.
#[derive(Clone, Debug, PartialEq)]
pub struct GlareSource {
    /// What it is: the luminaire's name, or "image source N".
    pub label: String,
    /// Unit direction from the eye, observer frame (x right, y up, z along the line of sight).
    pub direction: DVec3,
    /// Mean luminance towards the eye (cd/m²) and its standard error.
    pub luminance: f64,
    pub luminance_se: f64,
    /// Solid angle (sr).
    pub solid_angle: f64,
    /// The illuminance it gives at the eye on a plane facing the line of sight (lx).
    pub eye_illuminance: f64,
    /// Position index at `direction` and the rule that gave it.
    pub position_index: f64,
    pub index_rule: IndexRule,
    /// The image pixels it is made of (empty for an analytic source).
    pub pixels: Vec<usize>,
}

impl GlareSource {
    /// Whether its solid angle lies outside CIE 117's range.
    pub fn outside_cie117(&self) -> bool {
        !(CIE117_MIN_SR..=CIE117_MAX_SR).contains(&self.solid_angle)
    }

    /// Degrees above (+) or below (−) the line of sight, and to the right (+) or left (−).
    pub fn angles_deg(&self) -> (f64, f64) {
        let d = self.direction;
        // (+ 0.0 turns −0.0 into 0.0, so a source straight ahead is not "−0.0° right".)
        (
            d.y.atan2(d.z).to_degrees() + 0.0,
            d.x.atan2(d.z).to_degrees() + 0.0,
        )
    }
}

/// How the image's glare pixels are picked and grouped.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Detection {
    /// evalglare's `-b`: above 100 an absolute luminance (cd/m²), else a factor of the image's
    /// mean luminance.
    pub threshold: f64,
    /// evalglare's `-r` (radians, a full angle): glare pixels within half of it of each other
    /// belong to one source.
    pub search_radius: f64,
}

impl Default for Detection {
    fn default() -> Self {
        Detection {
            threshold: 5.0,
            search_radius: 0.2,
        }
    }
}

impl Detection {
    /// The luminance (cd/m²) above which a pixel is part of a glare source in `image`.
    pub fn threshold_cd_m2(&self, image: &GlareImage) -> f64 {
        if self.threshold > 100.0 {
            self.threshold
        } else {
            self.threshold * image.mean_luminance()
        }
    }
}

/// Union-find over pixel indices of the glare pixels.
struct Groups {
    parent: Vec<usize>,
}

impl Groups {
    fn root(&mut self, mut a: usize) -> usize {
        while self.parent[a] != a {
            self.parent[a] = self.parent[self.parent[a]];
            a = self.parent[a];
        }
        a
    }

    fn join(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.root(a), self.root(b));
        if ra != rb {
            self.parent[ra.max(rb)] = ra.min(rb);
        }
    }
}

/// The glare sources of `image`, grouped as evalglare's two scans end up grouping them: pixels
/// above the threshold belong to one source when a chain of such pixels joins them, each within
/// half the search radius (`-r` is a full angle) of the next. A source's luminance is the
/// solid-angle-weighted mean of its pixels, its solid angle their sum, its direction their
/// L·ω-weighted mean direction (evalglare takes the pixel its L·ω-weighted mean film position
/// falls in, which depends on the lens).
pub fn image_sources(image: &GlareImage, detection: &Detection) -> Vec<GlareSource> {
    let threshold = detection.threshold_cd_m2(image);
    let half = 0.5 * detection.search_radius;
    let cos_half = half.cos();
    let w = image.width as usize;
    let bright: Vec<usize> = image
        .seen()
        .filter(|&i| image.luminance[i] > threshold)
        .collect();
    if bright.is_empty() {
        return Vec::new();
    }
    // Pixels within `half` of each other are at most `reach` pixels apart (the equidistant
    // fisheye stretches arcs by up to π/2 at its rim; the centre pixel's side is the angle a
    // pixel spans).
    let per_px = image.solid_angle.iter().copied().fold(0.0, f64::max).sqrt();
    let reach = (half / per_px.max(1e-9) * std::f64::consts::FRAC_PI_2).ceil() as i64 + 1;
    let mut slot = vec![usize::MAX; image.luminance.len()];
    for (k, &i) in bright.iter().enumerate() {
        slot[i] = k;
    }
    let mut groups = Groups {
        parent: (0..bright.len()).collect(),
    };
    let (wi, hi) = (i64::from(image.width), i64::from(image.height));
    for (k, &i) in bright.iter().enumerate() {
        let (x, y) = ((i % w) as i64, (i / w) as i64);
        for ny in (y - reach).max(0)..=(y + reach).min(hi - 1) {
            for nx in (x - reach).max(0)..=(x + reach).min(wi - 1) {
                let j = (ny * wi + nx) as usize;
                let m = slot[j];
                if m == usize::MAX || m <= k {
                    continue;
                }
                if image.direction[i].dot(image.direction[j]) >= cos_half {
                    groups.join(k, m);
                }
            }
        }
    }
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); bright.len()];
    for (k, &i) in bright.iter().enumerate() {
        let r = groups.root(k);
        members[r].push(i);
    }
    members
        .into_iter()
        .filter(|m| !m.is_empty())
        .enumerate()
        .filter_map(|(k, pixels)| {
            let sr: f64 = pixels.iter().map(|&i| image.solid_angle[i]).sum();
            let lw: f64 = pixels
                .iter()
                .map(|&i| image.luminance[i] * image.solid_angle[i])
                .sum();
            let var: f64 = pixels
                .iter()
                .map(|&i| (image.std_error[i] * image.solid_angle[i]).powi(2))
                .sum();
            let direction = image.centroid_direction(&pixels);
            let eye_illuminance: f64 = pixels
                .iter()
                .map(|&i| image.luminance[i] * image.solid_angle[i] * image.direction[i].z.max(0.0))
                .sum();
            let (p, rule) = position_index(direction)?;
            Some(GlareSource {
                label: format!("image source {}", k + 1),
                direction,
                luminance: lw / sr,
                luminance_se: var.sqrt() / sr,
                solid_angle: sr,
                eye_illuminance,
                position_index: p,
                index_rule: rule,
                pixels,
            })
        })
        .collect()
}

/// Points a side on an opening to integrate what the eye sees of it.
const OPENING_SIDE: u32 = 16;

/// The luminaires of `lit` with a luminous opening, as glare sources seen from `eye` (scene
/// coordinates) by an observer whose frame `to_observer` turns scene directions into observer
/// ones. L = I / A_proj towards the eye (uniform over the opening, as the light model has it);
/// the solid angle, the illuminance at the eye and the mean direction integrated over the part
/// of the opening the eye sees (stratified points on the faces that face the eye, each with a
/// shadow ray), so that a near or partly hidden opening is right; p at that mean direction, as
/// for the image's sources. `names` name the lights of `lit` (its order). Openings behind the
/// eye's plane or wholly hidden are left out.
pub fn luminaire_sources(
    lit: &LitScene<'_>,
    eye: Vec3,
    to_observer: impl Fn(Vec3) -> DVec3,
    names: &[String],
) -> Vec<GlareSource> {
    let mut out = Vec::new();
    for (index, g) in luminaires_with_openings(lit) {
        let to_light = g.position - eye;
        let dist = to_light.length();
        if dist <= 1e-6 {
            continue;
        }
        let Some(luminance) = opening_luminance(g, -to_light / dist).filter(|l| *l > 0.0) else {
            // An opening that sends the eye no light (seen from behind) is no source.
            continue;
        };
        let local_eye = g.frame.to_local(eye - g.position);
        let facing = f64::from(g.shape.facing_area(local_eye));
        let mut rng = SampleRng::new(0x91a2e ^ index as u64, 0);
        let n = OPENING_SIDE * OPENING_SIDE;
        let (mut sr, mut e, mut dir) = (0.0f64, 0.0f64, DVec3::ZERO);
        for sy in 0..OPENING_SIDE {
            for sx in 0..OPENING_SIDE {
                let u = [
                    (sx as f32 + rng.next_f32()) / OPENING_SIDE as f32,
                    (sy as f32 + rng.next_f32()) / OPENING_SIDE as f32,
                ];
                let Some((p_local, n_local)) = g.shape.sample_facing(local_eye, u) else {
                    continue;
                };
                // A flat opening's normal is its plane's (both faces emit).
                let normal = if n_local == Vec3::ZERO {
                    Vec3::Z
                } else {
                    n_local
                };
                let to_eye_local = local_eye - p_local;
                let r2 = f64::from(to_eye_local.length_squared());
                if r2 <= 1e-12 {
                    continue;
                }
                let cos_at_opening = f64::from(normal.dot(to_eye_local).abs()) / r2.sqrt();
                let point = g.position + g.frame.to_scene(p_local);
                let d = to_observer((point - eye).normalize_or_zero());
                if d.z <= 0.0 {
                    // Behind the eye's plane: outside the 180° view, as in the image.
                    continue;
                }
                let seen = f64::from(lit.transmittance(eye, point - eye));
                if seen <= 0.0 {
                    continue;
                }
                let d_sr = seen * facing / f64::from(n) * cos_at_opening / r2;
                sr += d_sr;
                e += d_sr * d.z.max(0.0);
                dir += d * d_sr;
            }
        }
        let direction = dir.normalize_or_zero();
        if sr <= 0.0 {
            continue;
        }
        let Some((p, rule)) = position_index(direction) else {
            continue;
        };
        out.push(GlareSource {
            label: names
                .get(index)
                .cloned()
                .unwrap_or_else(|| format!("light {}", index + 1)),
            direction,
            luminance,
            luminance_se: 0.0,
            solid_angle: sr,
            eye_illuminance: luminance * e,
            position_index: p,
            index_rule: rule,
            pixels: Vec::new(),
        });
    }
    out
}
