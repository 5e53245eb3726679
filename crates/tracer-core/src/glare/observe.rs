//! Glare at one observer: the fisheye it looks through, the check that its eye is in open air,
//! and both ways of finding sources judged from one rendered image.

use super::batches::SampleBatches;
use super::figures::{GlareFigures, glare_figures};
use super::image::GlareImage;
use super::openings::draw_openings;
use super::source::{Detection, image_sources, luminaire_sources};
use crate::geometry::Ray;
use crate::lit_scene::LitScene;
use crate::render::Film;
use crate::scene::{CameraBasis, Observer, Setup};
use glam::{DVec3, Vec3};

/// Side of the square fisheye glare is judged from, pixels (evalglare's own examples use
/// 800-1500). The image's sources lose about a quarter of a pixel row around their edge in
/// L²ω: a luminaire of 300 pixels (0.016 sr at 400) reads 0.3 UGR low at 400, about 0.2 at
/// 800.
pub const DEFAULT_IMAGE_SIZE: u32 = 800;

/// What the user chooses.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GlareOptions {
    pub detection: Detection,
    /// evalglare's DGP correction below 1000 lx.
    pub low_light: bool,
}

/// Glare at one observer, both ways.
#[derive(Clone, Debug)]
pub struct ObserverGlare {
    pub observer: String,
    /// Sources found in the image (every bright thing: openings, glowing surfaces, windows,
    /// the sun).
    pub from_image: GlareFigures,
    /// Sources from the luminaires' openings, None when no luminaire has one.
    pub analytic: Option<GlareFigures>,
    /// The image's threshold (cd/m²).
    pub threshold_cd_m2: f64,
    /// Pixels into which luminous openings were drawn.
    pub opening_pixels: usize,
    /// The image judged (openings drawn), for writing out.
    pub image: GlareImage,
}

/// `setup` looking through `observer`'s fisheye, for a square image of `size` pixels.
pub fn observer_setup(setup: &Setup, observer: &Observer) -> Setup {
    let mut s = setup.clone();
    s.camera = observer.fisheye_camera();
    s
}

/// The fisheye basis of `observer` in `setup`'s scene, `size` pixels square.
pub fn observer_basis(setup: &Setup, observer: &Observer, size: u32) -> CameraBasis {
    observer
        .fisheye_camera()
        .basis(setup.handedness, size.max(1), size.max(1))
}

/// Unit directions spread evenly over the sphere (a Fibonacci lattice).
fn sphere_directions(n: usize) -> impl Iterator<Item = Vec3> {
    let golden = std::f32::consts::PI * (3.0 - 5.0f32.sqrt());
    (0..n).map(move |i| {
        let z = 1.0 - 2.0 * (i as f32 + 0.5) / n as f32;
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = golden * i as f32;
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    })
}

/// Directions the eye test looks along; how many must meet a surface, and what share of those
/// must meet its back, to refuse the eye as outside a closed room or inside a closed solid.
const EYE_TEST_RAYS: usize = 128;
const EYE_TEST_MIN_HITS: usize = 16;
const EYE_TEST_BACK_SHARE: f32 = 0.9;
/// Inside an open solid (a block standing on the floor, without a bottom face, whose floor the
/// downward directions meet from the front): two in five of all directions meet a back.
const EYE_TEST_OPEN_BACK_SHARE: f32 = 0.4;

/// Whether `observer`'s eye is in open air: refused (naming the observer and its `position`)
/// when nine in ten of the directions from it that meet a surface meet its back first (inside a
/// closed solid, or outside a closed room), or when two in five of all directions do (inside a
/// block that stands on something).
pub fn check_eye(lit: &LitScene<'_>, observer: &Observer) -> Result<(), String> {
    let eye = Vec3::from(observer.position);
    let (mut back, mut hits) = (0usize, 0usize);
    for dir in sphere_directions(EYE_TEST_RAYS) {
        let ray = Ray::new(eye, dir);
        if let Some(hit) = lit.closest_visible(&ray) {
            hits += 1;
            if lit.front_normal(hit.prim).dot(dir) > 0.0 {
                back += 1;
            }
        }
    }
    let closed = hits >= EYE_TEST_MIN_HITS && back as f32 >= EYE_TEST_BACK_SHARE * hits as f32;
    let open = back as f32 >= EYE_TEST_OPEN_BACK_SHARE * EYE_TEST_RAYS as f32;
    if closed || open {
        let [x, y, z] = observer.position;
        return Err(format!(
            "observer {}: position [{x}, {y}, {z}] is inside a solid or outside the room: \
             {back} of the {hits} directions from it that meet a surface meet its back (or \
             the room's surfaces face away from its inside)",
            observer.name
        ));
    }
    Ok(())
}

/// Judges glare at `observer` from `film`, rendered through [`observer_setup`] at `size`
/// pixels square. `names` name `setup`'s lights in order (for the analytic sources). With
/// `batches` of the film's samples (needed where samples splat, see [`super::batches`]) the
/// standard errors are their spread.
pub fn judge_observer(
    lit: &LitScene<'_>,
    setup: &Setup,
    observer: &Observer,
    film: &Film,
    batches: Option<&SampleBatches>,
    options: &GlareOptions,
    names: &[String],
) -> ObserverGlare {
    let basis = observer_basis(setup, observer, film.width);
    let mut image = GlareImage::from_film(film, &basis);
    let opening_pixels = draw_openings(&mut image, lit, &basis);
    let threshold = options.detection.threshold_cd_m2(&image);
    let found = image_sources(&image, &options.detection);
    let from_image = glare_figures(&image, found, options.low_light, batches);
    let to_observer = |v: Vec3| {
        let v = v.as_dvec3();
        DVec3::new(
            v.dot(basis.right.as_dvec3()),
            v.dot(basis.up.as_dvec3()),
            v.dot(basis.forward.as_dvec3()),
        )
        .normalize_or_zero()
    };
    let eye = Vec3::from(observer.position);
    let has_openings = super::openings::luminaires_with_openings(lit)
        .next()
        .is_some();
    let analytic = has_openings.then(|| {
        let sources = luminaire_sources(lit, eye, to_observer, names);
        glare_figures(&image, sources, options.low_light, batches)
    });
    ObserverGlare {
        observer: observer.name.clone(),
        from_image,
        analytic,
        threshold_cd_m2: threshold,
        opening_pixels,
        image,
    }
}

/// Names for the lights a render places (`setup`'s valid lights, in order): "luminaire N
/// (FILE)" or "light N", N counting every light of the setup from 1.
pub fn light_names(setup: &Setup) -> Vec<String> {
    setup
        .lights
        .iter()
        .enumerate()
        .filter(|(_, l)| l.is_valid())
        .map(|(i, l)| match &l.kind {
            crate::light::LightKind::Luminaire(p) => {
                let file = p
                    .luminaire
                    .file
                    .file_name()
                    .map(|f| f.to_string_lossy().into_owned())
                    .unwrap_or_default();
                format!("luminaire {} ({file})", i + 1)
            }
            _ => format!("light {}", i + 1),
        })
        .collect()
}
