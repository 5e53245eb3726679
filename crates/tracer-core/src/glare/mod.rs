//! Glare at observer positions: UGR (CIE 117:1995) and DGP (Wienold & Christoffersen 2006),
//! each with its standard error.
//!
//! ```text
//!  observer ──► 180° equidistant fisheye render (Film: mean and standard error per pixel)
//!                 │ image.rs: luminance, direction, solid angle per pixel
//!                 │ openings.rs: luminaires' luminous openings drawn in as the eye sees them
//!                 ├─► source.rs: image sources (evalglare's -b rule, grouped by direction)
//!                 ├─► source.rs: analytic sources (openings: I / A_proj, A_proj / d²)
//!                 │ position_index.rs: Guth (CIE 117 table) above, Iwata below the line of sight
//!                 └─► figures.rs: Ev, Lb, UGR, DGP and their standard errors
//!                       (batches.rs: from independent batches where samples splat)
//!
//! sun.rs marks the pixels the sun's disc may fall in: they get more samples (batches.rs).
//! ```
//!
//! `hdr.rs` writes the fisheye as a Radiance picture evalglare reads.

pub mod batches;
pub mod figures;
pub mod hdr;
pub mod image;
pub mod observe;
pub mod openings;
pub mod position_index;
pub mod source;
pub mod sun;

pub use batches::{SampleBatches, render_in_batches, samples_of};
pub use figures::{GlareFigures, LOW_LIGHT_LX, glare_figures};
pub use image::GlareImage;
pub use observe::{
    DEFAULT_IMAGE_SIZE, GlareOptions, ObserverGlare, check_eye, judge_observer, light_names,
    observer_basis, observer_setup,
};
pub use position_index::{IndexRule, guth_table, iwata, levin, position_index};
pub use source::{CIE117_MAX_SR, CIE117_MIN_SR, Detection, GlareSource};
pub use sun::{SUN_SAMPLES, sun_pixels};
